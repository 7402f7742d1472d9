// BDPT (bidirectional path tracing, integrators/bdpt/) against PATH: the same image within noise on scenes with every
// light type, delta lobes (a glass caustic, a mirror), tilted shading normals and an orthographic camera without a
// light-tracing strategy; the closed-sphere furnaces against their closed forms (docs/verification.md §1).
//
// Agreement (agreement.h): 12 seeds per integrator, t-statistics with 22 degrees of freedom; the image mean within
// 4 (two-sided false alarm 6e-4 per comparison), every 4×4 block within 6 (5e-6 per block). Over this file's ~12
// comparisons and ~300 blocks the family-wise false-alarm rate is below 1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "agreement.h"
#include "core/math.h"
#include "lights/light.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 12;

std::vector<float> at(float x, float y, float z) { return {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1}; }

/// A room: diffuse walls (open toward a dim world through a window), a rough glossy sphere and — with `specular` — a
/// glass sphere on the floor and a mirror; lit by `lights` (a bit mask: 1 point, 2 soft point, 4 spot, 8 sun, 16 soft
/// sun, 32 disk area light, 64 rectangle area light, 128 emissive triangle, 256 constant world).
///
/// Lights no ray can hit (point, spot, sun) light the floor through the glass and the mirror along paths a path
/// tracer cannot build (after a delta bounce it would have to hit the light): BDPT renders those caustics and PATH
/// does not, so the agreement with PATH is tested for them without the specular objects.
SceneArrays lit_room(unsigned lights, bool specular) {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f, 0.55f, 0.5f), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    const uint32_t mirror = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(mirror, "GLOSSY", {{"color_r", 0.9f}, {"color_g", 0.9f}, {"color_b", 0.9f}, {"roughness", 0.f}});
    const uint32_t glossy = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glossy, "GLOSSY", {{"color_r", 0.8f}, {"color_g", 0.6f}, {"color_b", 0.4f}, {"roughness", 0.35f}});
    const uint32_t lamp = b.add_material(Color(0.f), Color(4.f));
    // Floor, back wall, left wall; the room is open to the right, the top and behind the camera (a dim world).
    b.add_instance(b.add_quad_z(-2.f, 2.f, -1.5f, 1.5f, -3.f, wall));
    const std::vector<float> floor = {1, 0, 0, 0, 0, 0, 1, -1.2f, 0, -1, 0, -1.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-2.f, 2.f, -1.5f, 1.5f, 0.f, wall), floor.data());
    const std::vector<float> left = {0, 0, 1, -1.8f, 0, 1, 0, 0, -1, 0, 0, -1.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-1.5f, 1.5f, -1.5f, 1.5f, 0.f, wall), left.data());
    const std::vector<float> g = at(0.5f, -0.8f, -1.8f), s = at(-0.8f, -0.85f, -2.2f);
    if (specular) b.add_instance(b.add_sphere(0.4f, 24, 12, glass), g.data());
    b.add_instance(b.add_sphere(0.35f, 24, 12, glossy), s.data());
    const std::vector<float> m = {0.7f, 0, 0.7f, -1.3f, 0, 1, 0, 0.3f, -0.7f, 0, 0.7f, -2.5f, 0, 0, 0, 1};
    if (specular) b.add_instance(b.add_quad_z(-0.4f, 0.4f, -0.4f, 0.4f, 0.f, mirror), m.data());
    if (lights & 1) b.add_point_light(Vec3(0.6f, 0.7f, -1.6f), Color(6.f));
    if (lights & 2) b.add_point_light(Vec3(-0.5f, 0.8f, -1.4f), Color(6.f), 0.15f);
    if (lights & 4) {
        std::vector<float> spot(light_columns().size(), 0.f);
        for (int c = 0; c < 3; ++c) spot[c] = 25.f;
        spot[3] = 0.3f, spot[4] = 1.2f, spot[5] = -1.5f;
        const Vec3 d = normalize(Vec3(0.1f, -1.f, -0.2f));
        spot[6] = d.x, spot[7] = d.y, spot[8] = d.z;
        spot[16] = 1.f, spot[17] = 0.2f;
        b.add_light(1, spot);
    }
    if (lights & (8 | 16)) {
        std::vector<float> sun(light_columns().size(), 0.f);
        for (int c = 0; c < 3; ++c) sun[c] = 2.f;
        const Vec3 d = normalize(Vec3(-0.6f, -0.7f, -0.3f));
        sun[6] = d.x, sun[7] = d.y, sun[8] = d.z;
        sun[18] = (lights & 16) ? 0.2f : 0.f;
        b.add_light(2, sun);
    }
    if (lights & 32)
        b.add_area_light(Vec3(0.f, 1.2f, -1.8f), Vec3(0.7f, 0.f, 0.f), Vec3(0.f, 0.f, 0.5f), Vec3(0.f, -1.f, 0.f),
                         Color(12.f), true);
    if (lights & 64)
        b.add_area_light(Vec3(1.f, 0.3f, -2.9f), Vec3(0.5f, 0.f, 0.f), Vec3(0.f, 0.4f, 0.f), Vec3(0.f, 0.f, 1.f),
                         Color(10.f), false);
    if (lights & 128) b.add_instance(b.add_triangle(Vec3(-1.f, 1.f, -2.f), Vec3(-0.4f, 1.f, -2.f), Vec3(-0.7f, 1.f, -2.6f), lamp));
    if (lights & 256) b.world_color = {0.3f, 0.35f, 0.4f};
    return b.arrays();
}

Params base_params(int w, int h) {
    Params p = basic_params(w, h, 0, 5);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("rr_start_bounce", int64_t(2));
    return p;
}

void expect_agree(const SceneArrays& arrays, const Params& base, const std::string& what, int bdpt_samples = 24,
                  int path_samples = 48) {
    Params a = base, b = base;
    a.set("integrator", std::string("BDPT"));
    a.set("samples", int64_t(bdpt_samples));
    b.set("integrator", std::string("PATH"));
    b.set("samples", int64_t(path_samples));
    const Agreement g = compare_seed_sets(render_seeds(arrays, a, k_seeds), render_seeds(arrays, b, k_seeds), 4);
    EXPECT_GT(g.mean_b, 0.0) << what;
    EXPECT_LT(std::fabs(g.mean_z), 4.0) << what << ": BDPT mean " << g.mean_a << ", PATH " << g.mean_b;
    EXPECT_LT(std::fabs(g.worst_block_z), 6.0) << what << ": block " << g.worst_block << " of " << g.blocks;
}

TEST(Bdpt, EqualsPathTracingWithPointSpotAndSoftPointLights) { expect_agree(lit_room(1 | 2 | 4, false), base_params(24, 18), "points"); }
TEST(Bdpt, EqualsPathTracingWithSuns) { expect_agree(lit_room(8 | 16 | 256, false), base_params(24, 18), "suns and world"); }
TEST(Bdpt, EqualsPathTracingWithAreaLightsAndEmissiveTriangles) {
    // Hittable lights: PATH finds the caustics through the glass and the mirror too.
    expect_agree(lit_room(32 | 64 | 128 | 256, true), base_params(24, 18), "area lights, a triangle, glass, a mirror");
}
TEST(Bdpt, EqualsPathTracingWithAThinLensAndAnOrthographicCamera) {
    Params lens = base_params(20, 16);
    lens.set("use_dof", true);
    lens.set("focus_distance", 2.f);
    lens.set("aperture_fstop", 0.8f);
    lens.set("aperture_blades", int64_t(6));
    expect_agree(lit_room(1 | 32, false), lens, "thin lens");
    Params ortho = base_params(20, 16);
    ortho.set("camera_type", std::string("ORTHO"));  // no t = 1 strategy: the others carry everything
    ortho.set("ortho_scale", 4.f);
    expect_agree(lit_room(1 | 32, false), ortho, "orthographic pinhole");
}

TEST(Bdpt, ClosedSphereFurnaces) {
    // 12 seeds: the spread of their means gives the standard error (t with 11 degrees of freedom: 5 has a two-sided
    // false-alarm probability of 4e-4).
    for (FurnaceScene kind : {FurnaceScene::EmissiveSphere, FurnaceScene::PointLight}) {
        Params p = basic_params(8, 6, 64, 5);
        p.set("integrator", std::string("BDPT"));
        p.set("rr_mode", std::string("OFF"));
        p.set("threads", int64_t(2));
        const SeedMean m = seed_mean(render_seeds(furnace_scene(kind, 128, 64), p, 12));
        // The UV sphere's area is below the true sphere's: the point light's answer scales with it (test_helpers.h).
        const double expected =
            furnace_expected(kind, 5) * (kind == FurnaceScene::PointLight ? 1.0 + furnace_facet_bias(128, 64) : 1.0);
        EXPECT_NEAR(m.mean, expected, 5.0 * m.standard_error + 1e-6) << int(kind);
    }
}

}  // namespace
}  // namespace candela::test
