// LIGHT (light tracing, integrators/light/) against PATH: the same image within noise, for every camera model,
// pixel filter and width, resolution and border, and with tilted shading normals (where it fails without Veach's
// adjoint correction); the closed-sphere furnaces against their closed forms (docs/verification.md §1).
//
// Agreement (agreement.h): 12 seeds per integrator, t-statistics with 22 degrees of freedom; the image mean within
// 4 (two-sided false alarm 6e-4 per comparison), every 4×4 block within 6 (5e-6 per block). Over the ~14
// comparisons and ~600 blocks of this file the family-wise false-alarm rate is about 1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "agreement.h"
#include "core/error.h"
#include "core/math.h"
#include "integrators/integrator.h"
#include "lights/light.h"
#include "reference_scenes.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 12;

/// A diffuse room with a rough glossy sphere, lit by a disk area light, a point light and an emissive triangle;
/// nothing specular, so every path light tracing can build is one the camera sees.
SceneArrays diffuse_room() {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f, 0.5f, 0.4f), Color(0.f));
    const uint32_t glossy = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glossy, "GLOSSY", {{"color_r", 0.8f}, {"color_g", 0.8f}, {"color_b", 0.8f}, {"roughness", 0.4f}});
    const uint32_t lamp = b.add_material(Color(0.f), Color(5.f));
    b.add_instance(b.add_box(Vec3(2.f, 1.5f, 3.f), wall));
    const std::vector<float> xf = {1, 0, 0, -0.6f, 0, 1, 0, -1.f, 0, 0, 1, -1.8f, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(0.5f, 24, 12, glossy), xf.data());
    b.add_instance(b.add_triangle(Vec3(-0.3f, 1.45f, -1.5f), Vec3(0.3f, 1.45f, -1.5f), Vec3(0.f, 1.45f, -2.1f), lamp));
    b.add_point_light(Vec3(1.f, 0.8f, -1.2f), Color(6.f));
    b.add_area_light(Vec3(0.8f, -1.f, -2.95f), Vec3(0.8f, 0.f, 0.f), Vec3(0.f, 0.5f, 0.f), Vec3(0.f, 0.f, 1.f),
                     Color(8.f, 6.f, 4.f), /*disk=*/true);
    return b.arrays();
}

Params room_params(int w, int h, int samples) {
    Params p = basic_params(w, h, samples, 6);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("rr_start_bounce", int64_t(2));
    return p;
}

void expect_agree(const SceneArrays& arrays, const Params& base, const std::string& what, int light_samples = 64,
                  int path_samples = 32) {
    Params lt = base, pt = base;
    lt.set("integrator", std::string("LIGHT"));
    lt.set("samples", int64_t(light_samples));
    pt.set("integrator", std::string("PATH"));
    pt.set("samples", int64_t(path_samples));
    const Agreement a = compare_seed_sets(render_seeds(arrays, lt, k_seeds), render_seeds(arrays, pt, k_seeds), 4);
    EXPECT_GT(a.mean_b, 0.0) << what;
    EXPECT_LT(std::fabs(a.mean_z), 4.0) << what << ": LIGHT mean " << a.mean_a << ", PATH " << a.mean_b;
    EXPECT_LT(std::fabs(a.worst_block_z), 6.0) << what << ": block " << a.worst_block << " of " << a.blocks;
}

TEST(LightTracing, EqualsPathTracingOnARoom) { expect_agree(diffuse_room(), room_params(24, 18, 0), "room"); }

TEST(LightTracing, EqualsPathTracingForEveryCameraModel) {
    {
        Params p = room_params(24, 18, 0);
        p.set("use_dof", true);
        p.set("focus_distance", 2.f);
        p.set("aperture_fstop", 0.7f);
        p.set("aperture_blades", int64_t(5));
        p.set("aperture_ratio", 1.6f);
        expect_agree(diffuse_room(), p, "thin lens with blades and ratio");
    }
    {
        Params p = room_params(24, 18, 0);
        p.set("camera_type", std::string("ORTHO"));
        p.set("ortho_scale", 3.5f);
        p.set("use_dof", true);
        p.set("focus_distance", 2.f);
        p.set("aperture_fstop", 4.f);
        expect_agree(diffuse_room(), p, "orthographic with depth of field");
    }
    {
        Params p = room_params(20, 20, 0);
        p.set("shift_x", 0.1f);
        p.set("sensor_fit", std::string("VERTICAL"));
        p.set("pixel_aspect_x", 1.5f);
        expect_agree(diffuse_room(), p, "shift, vertical fit, pixel aspect");
    }
}

TEST(LightTracing, EqualsPathTracingForEveryPixelFilterWidthAndResolution) {
    for (const char* filter : {"BOX", "GAUSSIAN", "BLACKMAN_HARRIS"})
        for (double width : {1.0, 2.5}) {
            Params p = room_params(16, 12, 0);
            p.set("pixel_filter", std::string(filter));
            p.set("filter_width", width);
            expect_agree(diffuse_room(), p, std::string(filter) + " " + std::to_string(width));
        }
    expect_agree(diffuse_room(), room_params(40, 30, 0), "40x30", 32, 16);
}

TEST(LightTracing, ABorderRendersTheSamePixelsAsTheFullFrame) {
    Params full = room_params(24, 18, 64), crop = full;
    full.set("integrator", std::string("LIGHT"));
    crop.set("integrator", std::string("LIGHT"));
    crop.set("crop_x0", int64_t(6));
    crop.set("crop_y0", int64_t(4));
    crop.set("crop_x1", int64_t(18));
    crop.set("crop_y1", int64_t(12));
    std::vector<RenderResult> a = render_seeds(diffuse_room(), full, k_seeds),
                              b = render_seeds(diffuse_room(), crop, k_seeds);
    // The full frame's pixels inside the border, as renders of the border's size.
    for (RenderResult& r : a) {
        RenderResult c;
        c.width = 12;
        c.height = 8;
        for (int y = 4; y < 12; ++y)
            for (int x = 6; x < 18; ++x)
                for (int k = 0; k < 4; ++k) c.rgba.push_back(r.rgba[4 * (size_t(y) * 24 + x) + k]);
        r = c;
    }
    const Agreement g = compare_seed_sets(a, b, 4);
    EXPECT_LT(std::fabs(g.mean_z), 4.0) << g.mean_a << " vs " << g.mean_b;
    EXPECT_LT(std::fabs(g.worst_block_z), 6.0) << g.worst_block;
}

/// A floor in front of the camera whose shading normal is tilted 0.6 rad toward a low point light: the incoming
/// light's shading cosine is far from its geometric one, so Veach's adjoint factor |w_l·ns|/|w_l·ng| is far from 1
/// (light tracing without it is 30–60 % off here).
SceneArrays tilted_floor() {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.7f), Color(0.f));
    b.add_instance(b.add_triangle(Vec3(-8.f, -1.f, 2.f), Vec3(8.f, -1.f, 2.f), Vec3(0.f, -1.f, -14.f), m));
    b.add_point_light(Vec3(3.f, -0.6f, -3.f), Color(30.f));
    SceneArrays a = b.arrays();
    const Vec3 n = normalize(Vec3(std::sin(0.6f), std::cos(0.6f), 0.f));
    std::vector<float> normals;
    for (int k = 0; k < 3; ++k) normals.insert(normals.end(), {n.x, n.y, n.z});
    const uint8_t smooth[1] = {1};
    a.set("normals", ElemType::F32, {1, 3, 3}, normals.data());
    a.set("tri_smooth", ElemType::U8, {1}, smooth);
    return a;
}

TEST(LightTracing, EqualsPathTracingWithATiltedShadingNormal) {
    Params p = room_params(24, 18, 0);
    p.set("max_bounces", int64_t(0));
    expect_agree(tilted_floor(), p, "tilted floor");
}

TEST(LightTracing, EqualsPathTracingWithTiltedShadingNormals) {
    Params p = room_params(24, 18, 0);
    p.set("max_bounces", int64_t(3));
    expect_agree(smooth_lowpoly_sphere(), p, "low-poly smooth sphere");
}

TEST(LightTracing, ClosedSphereFurnaces) {
    // 12 seeds: the spread of their means gives the standard error (t with 11 degrees of freedom: 5 has a two-sided
    // false-alarm probability of 4e-4).
    for (FurnaceScene kind : {FurnaceScene::EmissiveSphere, FurnaceScene::PointLight}) {
        Params p = basic_params(8, 6, 64, 5);
        p.set("integrator", std::string("LIGHT"));
        p.set("rr_mode", std::string("OFF"));
        p.set("threads", int64_t(2));
        const SeedMean m = seed_mean(render_seeds(furnace_scene(kind, 128, 64), p, 12));
        // The UV sphere's area is below the true sphere's: the point light's answer scales with it (test_helpers.h).
        const double expected =
            furnace_expected(kind, 5) * (kind == FurnaceScene::PointLight ? 1.0 + furnace_facet_bias(128, 64) : 1.0);
        EXPECT_NEAR(m.mean, expected, 5.0 * m.standard_error + 1e-6) << int(kind);
    }
}

TEST(LightTracing, AnOrthographicPinholeCameraIsRefusedByName) {
    Params p = basic_params(8, 6, 4, 2);
    p.set("integrator", std::string("LIGHT"));
    p.set("camera_type", std::string("ORTHO"));
    try {
        make_integrator(p);
        ADD_FAILURE() << "accepted";
    } catch (const InvalidParameter& e) {
        EXPECT_NE(std::string(e.what()).find("orthographic"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace candela::test
