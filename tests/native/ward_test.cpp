// light_selection = WARD in the path tracer: adaptive shadow testing (Ward 1991) must give the same image as
// estimating every light (ALL) — it is unbiased — while tracing fewer shadow rays when a few lights dominate;
// and with ward_threshold = 0 it tests every light, i.e. it is ALL.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "session/session.h"
#include "test_helpers.h"

namespace candela {
namespace {

struct WardRender {
    double mean = 0.0, se = 0.0;
    uint64_t rays = 0;
};

/// A diffuse floor at z = −1 filling the view, 40 point lights of strengths spread over three decades and
/// two square area lights (MIS with the BSDF-sampled bounce) at z = −0.6, and an occluding quad at z = −0.8
/// that shadows part of the floor from some of them.
SceneArrays many_light_scene() {
    test::MeshBuilder b;
    const uint32_t floor_mat = b.add_material(Color(0.8f), Color(0.f));
    b.add_instance(b.add_quad_z(-3, 3, -3, 3, -1, floor_mat));
    b.add_instance(b.add_quad_z(-0.1f, 0.25f, -0.15f, 0.1f, -0.8f, floor_mat));
    for (int i = 0; i < 40; ++i) {
        const float x = -0.5f + 0.25f * float(i % 5), y = -0.5f + 0.15f * float(i / 5);
        const float strength = 0.02f * std::pow(10.f, 3.f * float((i * 7) % 40) / 40.f);  // 0.02 … 20 W
        b.add_point_light(Vec3(x, y, -0.6f), Color(strength));
    }
    for (int i = 0; i < 2; ++i) {
        std::vector<float> row(20, 0.f);
        row[0] = row[1] = row[2] = 2.f + 8.f * float(i);  // W
        row[3] = i == 0 ? -0.3f : 0.35f;
        row[4] = 0.1f;
        row[5] = -0.6f;  // position
        row[8] = -1.f;   // shines down (−Z)
        row[9] = 0.2f;   // u: 0.2 along X
        row[13] = 0.2f;  // v: 0.2 along Y
        row[19] = 0.f;   // square
        b.add_light(3, row);
    }
    return b.arrays();
}

WardRender render(const std::string& selection, float threshold, int samples, int max_bounces = 1) {
    Params p = test::basic_params(24, 24, samples, max_bounces);
    p.set("light_selection", selection);
    p.set("ward_threshold", double(threshold));
    p.set("sampler", std::string("RANDOM"));
    p.set("seed", int64_t(selection == "WARD" ? 11 + int(threshold * 100) : 3));
    Session s(many_light_scene(), std::move(p));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    int channels = 0;
    const std::vector<float> rgba = s.get_pass("Combined", &channels);
    const size_t n = rgba.size() / 4;
    // Pixel means are independent estimates: the standard error of the image mean from their spread over
    // many pixels would mix in the image's own variation, so use the per-pixel sample variances instead.
    const std::vector<float> noise = s.get_pass("Noise", &channels);
    double sum = 0.0, var = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sum += luminance(Color(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]));
        var += double(noise[i]) * noise[i];
    }
    WardRender r;
    r.mean = sum / double(n);
    r.se = std::sqrt(var) / double(n);
    r.rays = s.stats().rays;
    return r;
}

TEST(WardAdaptiveShadowTesting, AgreesWithAllLightsAndTracesFewerShadowRays) {
    const WardRender all = render("ALL", 0.f, 64);
    const WardRender ward = render("WARD", 0.05f, 64);
    const WardRender loose = render("WARD", 0.5f, 64);
    std::printf("ALL  %.5f ± %.5f  %llu rays\nWARD(0.05) %.5f ± %.5f  %llu rays\nWARD(0.5) %.5f ± %.5f  %llu rays\n",
                all.mean, all.se, (unsigned long long)all.rays, ward.mean, ward.se, (unsigned long long)ward.rays,
                loose.mean, loose.se, (unsigned long long)loose.rays);
    ASSERT_GT(all.mean, 0.0);
    // Unbiased: independent estimates of the same mean agree within 4 combined standard errors.
    EXPECT_NEAR(ward.mean, all.mean, 4.0 * std::hypot(ward.se, all.se));
    EXPECT_NEAR(loose.mean, all.mean, 4.0 * std::hypot(loose.se, all.se));
    // ALL traces 42 shadow rays per vertex; the dominant lights carry most of the light here, so Ward stops
    // long before that (a loose threshold sooner still).
    EXPECT_LT(ward.rays, all.rays / 2);
    EXPECT_LT(loose.rays, ward.rays);
}

TEST(WardAdaptiveShadowTesting, ThresholdZeroTestsEveryLight) {
    // Direct light only (max_bounces 0): the camera rays are the same in both, so ray counts compare exactly.
    const WardRender all = render("ALL", 0.f, 8, 0);
    const WardRender ward = render("WARD", 0.f, 8, 0);
    // Every light with a non-zero bound is shadow-tested; lights that cannot reach a point (bound 0) are
    // skipped, so at most as many rays as ALL, and the same estimate up to noise.
    EXPECT_LE(ward.rays, all.rays);
    EXPECT_GT(ward.rays, all.rays * 9 / 10);
    EXPECT_NEAR(ward.mean, all.mean, 4.0 * std::hypot(ward.se, all.se));
}

}  // namespace
}  // namespace candela
