// The path vertex BSDF in both directions (integrators/common/vertex_bsdf.h): light-side sampling has the density
// it reports (χ²) and covers the whole support of the path BSDF f(w_c, w_l) — also where a tilted shading normal
// makes f non-zero below the shading hemisphere —, so E[weight] equals ∫ f(w_c, w_l)·|w_c·ng|·c(w_c, w_l) dω(w_c)
// by quadrature (c: the adjoint shading-normal factor). Checked for diffuse, glossy and glass with and without tilted
// shading normals. Tolerances: 5 estimated standard errors (400,000 samples); χ² at family-wise 1e-3.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "chi2.h"
#include "core/rng.h"
#include "integrators/common/fixed_view_bsdf.h"
#include "integrators/common/vertex_bsdf.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// One triangle in the z = −2 plane facing the camera (+z), its corner shading normals tilted by `tilt` radians.
SceneArrays tilted_triangle(const std::string& closure, float roughness, float tilt) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.f), Color(0.f));
    if (closure == "GLASS")
        b.add_closure(m, "GLASS",
                      {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}, {"roughness", roughness}});
    else
        b.add_closure(m, closure, {{"color_r", 0.8f}, {"color_g", 0.8f}, {"color_b", 0.8f}, {"roughness", roughness}});
    b.add_instance(b.add_triangle(Vec3(-1.f, -1.f, -2.f), Vec3(1.f, -1.f, -2.f), Vec3(0.f, 1.f, -2.f), m));
    SceneArrays a = b.arrays();
    const Vec3 n = normalize(Vec3(std::sin(tilt), 0.f, std::cos(tilt)));
    std::vector<float> normals;
    for (int k = 0; k < 3; ++k) normals.insert(normals.end(), {n.x, n.y, n.z});
    const uint8_t smooth[1] = {1};
    a.set("normals", ElemType::F32, {1, 3, 3}, normals.data());
    a.set("tri_smooth", ElemType::U8, {1}, smooth);
    return a;
}

struct Case {
    const char* closure;
    float roughness, tilt;
};
const Case k_cases[] = {{"DIFFUSE", 0.f, 0.f},  {"DIFFUSE", 0.f, 0.5f}, {"GLOSSY", 0.5f, 0.f},
                        {"GLOSSY", 0.5f, 0.4f}, {"GLASS", 0.5f, 0.f},   {"GLASS", 0.5f, 0.35f}};
const double k_alpha = sidak_alpha(1e-3, 2 * int(std::size(k_cases)) * 3);

struct Fixture {
    std::unique_ptr<Scene> scene;
    SurfaceHit hit;
    explicit Fixture(const Case& c) {
        const SceneArrays a = tilted_triangle(c.closure, c.roughness, c.tilt);
        scene = std::make_unique<Scene>(a, basic_params(8, 8, 1, 1), nullptr);
        EXPECT_TRUE(scene->intersect({Vec3(0.f, -0.2f, 0.f), Vec3(0.f, 0.f, -1.f)}, &hit));
    }
};

/// Incoming light directions: steep, oblique and grazing, on the front (and, for glass, the back).
std::vector<Vec3> light_directions(const Case& c) {
    std::vector<Vec3> out = {normalize(Vec3(0.2f, 0.1f, 1.f)), normalize(Vec3(-0.8f, 0.3f, 0.5f)),
                             normalize(Vec3(0.95f, 0.f, 0.12f))};
    if (std::string(c.closure) == "GLASS") out.push_back(normalize(Vec3(0.3f, -0.2f, -1.f)));
    return out;
}

TEST(VertexBsdf, LightSideSamplesFollowTheirDensity) {
    for (const Case& c : k_cases) {
        Fixture fx(c);
        for (const Vec3& w_l : light_directions(c)) {
            const VertexBsdf v(*fx.scene, fx.hit, w_l, fx.scene->shade(fx.hit, w_l));
            auto sampler = [&](Vec2 u, float uc, Vec3* w) {
                const VertexBsdf::Sample s = v.sample_light(w_l, u, uc);
                if (!(s.pdf > 0.f) || s.delta) return false;  // a zero weight is still a sample of the density
                *w = s.w;
                return true;
            };
            auto pdf = [&](const Vec3& w) { return double(v.pdf_light(w_l, w)); };
            Chi2Config cfg;
            cfg.samples = 400000;
            const Chi2Result r = chi2_test(sampler, pdf, cfg);
            EXPECT_GT(r.p_value, k_alpha) << c.closure << " tilt " << c.tilt << ": " << r.summary();
        }
    }
}

// E[weight] of light-side sampling = ∫ f(w_c, w_l)·|w_c·ng|·c(w_c, w_l) dω(w_c): the sampling reaches every direction
// f is non-zero for. Without the geometric-cosine share this fails for tilted normals (the band below the shading
// hemisphere is never sampled).
TEST(VertexBsdf, LightSideSamplingCoversThePathBsdf) {
    for (const Case& c : k_cases) {
        Fixture fx(c);
        for (const Vec3& w_l : light_directions(c)) {
            const VertexBsdf v(*fx.scene, fx.hit, w_l, fx.scene->shade(fx.hit, w_l));
            // Quadrature over the sphere (non-delta lobes only: glass is rough here).
            const int nt = 400, np = 800;
            double integral = 0.0;
            for (int i = 0; i < nt; ++i)
                for (int j = 0; j < np; ++j) {
                    const double ct = -1.0 + (i + 0.5) * 2.0 / nt, phi = (j + 0.5) * 2.0 * M_PI / np;
                    const double st = std::sqrt(1.0 - ct * ct);
                    const Vec3 w(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
                    integral += luminance(v.f(w, w_l)) * std::fabs(dot(w, fx.hit.ng)) * v.adjoint_factor(w, w_l) *
                                (2.0 / nt) * (2.0 * M_PI / np);
                }
            Pcg32 rng(9, 4);
            const int n = 400000;
            double sum = 0.0, sum_sq = 0.0;
            for (int k = 0; k < n; ++k) {
                const VertexBsdf::Sample s =
                    v.sample_light(w_l, {rng.next_float(), rng.next_float()}, rng.next_float());
                const double x = s.valid() ? luminance(s.weight) : 0.0;
                sum += x;
                sum_sq += x * x;
            }
            const double mean = sum / n, se = std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n);
            // The quadrature's own error (400 × 800 cells, lobes of roughness 0.5) is below 0.3 %.
            EXPECT_NEAR(mean, integral, 5.0 * se + 3e-3 * integral)
                << c.closure << " tilt " << c.tilt << " w_l " << w_l.x;
        }
    }
}

// Camera-side and light-side views of a vertex agree on f: f(w_c, w_l) evaluated from a vertex shaded from either
// side is the same value (the rule depends on w_c only).
TEST(VertexBsdf, TheBsdfIsTheSameWhicheverSideShadedFirst) {
    for (const Case& c : k_cases) {
        Fixture fx(c);
        const Vec3 a = normalize(Vec3(0.2f, 0.1f, 1.f)), b = std::string(c.closure) == "GLASS"
                                                                 ? normalize(Vec3(-0.3f, 0.2f, -1.f))
                                                                 : normalize(Vec3(-0.5f, 0.2f, 0.7f));
        const VertexBsdf from_a(*fx.scene, fx.hit, a, fx.scene->shade(fx.hit, a));
        const VertexBsdf from_b(*fx.scene, fx.hit, b, fx.scene->shade(fx.hit, b));
        EXPECT_EQ(luminance(from_a.f(a, b)), luminance(from_b.f(a, b))) << c.closure;
        EXPECT_EQ(luminance(from_a.f(b, a)), luminance(from_b.f(b, a))) << c.closure;
    }
}

// The gather's precomputed camera side (common/fixed_view_bsdf.h) is VertexBsdf's f·a for its w_c, on both sides,
// with tilted shading normals (where the frame switches to ng below ns, and directions leak), with and without the
// estimated-lobe subset. Relative 1e-5: the two compute the local frame's cosines in different orders of operations.
// A wrong input fails it: the adjoint factor left out (tried by hand: fails at the first tilted diffuse case).
TEST(VertexBsdf, FixedViewEqualsTheVertexBsdf) {
    Pcg32 rng(21, 4);
    const LobeSubset estimated{0.f, false};
    size_t nonzero = 0, leaked = 0;
    for (const Case& c : k_cases) {
        Fixture fx(c);
        for (int i = 0; i < 64; ++i) {
            const Vec3 wc = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
            for (const LobeSubset* subset : {static_cast<const LobeSubset*>(nullptr), &estimated}) {
                const ShadingPoint sp = fx.scene->shade(fx.hit, wc);
                const VertexBsdf vb(*fx.scene, fx.hit, wc, sp, subset);
                const FixedViewBsdf fv(fx.hit, wc, sp, subset);
                for (int j = 0; j < 16; ++j) {
                    const Vec3 wl =
                        normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
                    const float want = luminance(vb.f(wc, wl)) * vb.adjoint_factor(wc, wl);
                    const float got = luminance(fv.f_adjoint(wl));
                    ASSERT_NEAR(got, want, 1e-5f * std::fabs(want) + 1e-12f) << c.closure << " tilt " << c.tilt;
                    if (want > 0.f) ++nonzero;
                    if (want == 0.f && luminance(vb.f(wc, wl)) == 0.f) ++leaked;
                }
            }
        }
    }
    EXPECT_GT(nonzero, 1000u);
    EXPECT_GT(leaked, 100u);
}

}  // namespace
}  // namespace candela::test
