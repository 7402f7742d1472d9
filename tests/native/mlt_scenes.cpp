#include "mlt_scenes.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "agreement.h"

namespace candela::test {

SceneArrays box_scene(bool door) {
    MeshBuilder b;
    const uint32_t white = b.add_material(Color(0.7f), Color(0.f));
    const uint32_t red = b.add_material(Color(0.63f, 0.07f, 0.05f), Color(0.f));
    const uint32_t green = b.add_material(Color(0.12f, 0.45f, 0.09f), Color(0.f));
    auto quad = [&](const std::vector<float>& m, float x0, float x1, float y0, float y1, uint32_t mat) {
        b.add_instance(b.add_quad_z(x0, x1, y0, y1, 0.f, mat), m.data());
    };
    // (x, y, 0) of a quad ↦ world by these rows.
    const float zc = door ? -2.5f : -2.f, half = door ? 1.5f : 1.f;  // the rooms' z centre and half depth
    quad({1, 0, 0, 0, 0, 0, 1, -1, 0, -1, 0, zc, 0, 0, 0, 1}, -1, 1, -half, half, white);  // floor
    quad({1, 0, 0, 0, 0, 0, 1, 1, 0, -1, 0, zc, 0, 0, 0, 1}, -1, 1, -half, half, white);   // ceiling
    quad({0, 0, 1, -1, 0, 1, 0, 0, -1, 0, 0, zc, 0, 0, 0, 1}, -half, half, -1, 1, red);    // left
    quad({0, 0, 1, 1, 0, 1, 0, 0, -1, 0, 0, zc, 0, 0, 0, 1}, -half, half, -1, 1, green);   // right
    const uint32_t box = b.add_box(Vec3(0.25f, 0.4f, 0.25f), white);
    const std::vector<float> tall = {0.8f, 0, 0.6f, -0.4f, 0, 1, 0, -0.6f, -0.6f, 0, 0.8f, -2.4f, 0, 0, 0, 1};
    b.add_instance(box, tall.data());
    const uint32_t cube = b.add_box(Vec3(0.22f), white);
    const std::vector<float> low = {0.9f, 0, -0.44f, 0.4f, 0, 1, 0, -0.78f, 0.44f, 0, 0.9f, -1.7f, 0, 0, 0, 1};
    b.add_instance(cube, low.data());
    if (!door) {
        b.add_instance(b.add_quad_z(-1, 1, -1, 1, -3.f, white));  // back wall
        b.add_area_light(Vec3(0.f, 0.99f, -2.f), Vec3(0.5f, 0.f, 0.f), Vec3(0.f, 0.f, 0.4f), Vec3(0.f, -1.f, 0.f),
                         Color(16.f), false);
    } else {
        b.add_instance(b.add_quad_z(-1, 1, -0.85f, 1, -3.f, white));  // the partition: a slit from y = −1 to −0.85
        b.add_instance(b.add_quad_z(-1, 1, -1, 1, -4.f, white));      // the second room's far wall
        b.add_area_light(Vec3(0.f, 0.3f, -3.3f), Vec3(0.6f, 0.f, 0.f), Vec3(0.f, 0.5f, 0.f), Vec3(0.f, 0.f, -1.f),
                         Color(60.f), false);
    }
    const std::vector<float> camera = look_at(Vec3(0.f, 0.f, 1.6f), Vec3(0.f, 0.f, -2.f), Vec3(0.f, 1.f, 0.f));
    return b.arrays(camera.data());
}

Params base_params(const std::string& integrator, int samples) {
    Params p = basic_params(16, 12, samples, 5);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("integrator", integrator);
    if (integrator == "MLT" || integrator == "MMLT") {
        p.set("mlt_bootstrap", int64_t(integrator == "MLT" ? 20000 : 4000));  // MMLT's is per depth (7 here)
        p.set("mlt_chains", int64_t(32));
    }
    return p;
}

void expect_agree(const SceneArrays& arrays, const Params& a, const Params& b, const std::string& what, int runs) {
    const Agreement g = compare_seed_sets(render_seeds(arrays, a, runs), render_seeds(arrays, b, runs), 4);
    std::printf("%s: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", what.c_str(), g.mean_a, g.mean_b,
                g.mean_z, g.worst_block_z, g.blocks);
    EXPECT_GT(g.mean_b, 0.0) << what;
    EXPECT_LT(std::fabs(g.mean_z), 4.5) << what << ": mean " << g.mean_a << " vs " << g.mean_b;
    EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << what << ": block " << g.worst_block << " of " << g.blocks
                                               << " (means " << g.mean_a << " vs " << g.mean_b << ")";
}

}  // namespace candela::test
