#include "ic_test_scenes.h"

#include <vector>

namespace candela::test {

namespace {

/// Official Cornell coordinates (mm, y up) → metres, Z up.
Vec3 cornell(float x, float y, float z) { return Vec3((278.f - x) * 1e-3f, z * 1e-3f, y * 1e-3f); }

void add_quad(MeshBuilder& b, const std::vector<Vec3>& q, uint32_t material) {
    b.add_instance(b.add_triangle(q[0], q[1], q[2], material));
    b.add_instance(b.add_triangle(q[0], q[2], q[3], material));
}

}  // namespace

SceneArrays cornell_box_arrays(Color world) {
    MeshBuilder b;
    if (!is_black(world)) b.world_color = {world.x, world.y, world.z};
    const uint32_t white = b.add_material(Color(0.725f, 0.71f, 0.68f), Color(0.f));
    const uint32_t red = b.add_material(Color(0.63f, 0.065f, 0.05f), Color(0.f));
    const uint32_t green = b.add_material(Color(0.14f, 0.45f, 0.091f), Color(0.f));
    const uint32_t light = b.add_material(Color(0.f), Color(17.f, 12.f, 4.f));
    using Q = std::vector<Vec3>;
    add_quad(b, Q{cornell(552.8f, 0, 0), cornell(0, 0, 0), cornell(0, 0, 559.2f), cornell(549.6f, 0, 559.2f)}, white);
    add_quad(
        b, Q{cornell(556, 548.8f, 0), cornell(556, 548.8f, 559.2f), cornell(0, 548.8f, 559.2f), cornell(0, 548.8f, 0)},
        white);
    add_quad(
        b,
        Q{cornell(549.6f, 0, 559.2f), cornell(0, 0, 559.2f), cornell(0, 548.8f, 559.2f), cornell(556, 548.8f, 559.2f)},
        white);
    add_quad(b, Q{cornell(0, 0, 559.2f), cornell(0, 0, 0), cornell(0, 548.8f, 0), cornell(0, 548.8f, 559.2f)}, green);
    add_quad(
        b, Q{cornell(552.8f, 0, 0), cornell(549.6f, 0, 559.2f), cornell(556, 548.8f, 559.2f), cornell(556, 548.8f, 0)},
        red);
    const float short_block[5][4][3] = {{{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}},
                                        {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}},
                                        {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}},
                                        {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}},
                                        {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}};
    const float tall_block[5][4][3] = {{{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}},
                                       {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}},
                                       {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}},
                                       {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}},
                                       {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}};
    for (const auto* block : {short_block, tall_block})
        for (int f = 0; f < 5; ++f) {
            Q q;
            for (int k = 0; k < 4; ++k) q.push_back(cornell(block[f][k][0], block[f][k][1], block[f][k][2]));
            add_quad(b, q, white);
        }
    const float y = 548.8f - 0.5f;
    add_quad(b, Q{cornell(343, y, 227), cornell(343, y, 332), cornell(213, y, 332), cornell(213, y, 227)}, light);
    const std::vector<float> camera = look_at(Vec3(0.f, -0.8f, 0.273f), Vec3(0.f, 1.f, 0.273f), Vec3(0.f, 0.f, 1.f));
    return b.arrays(camera.data());
}

Params cornell_box_params(int w, int h, int samples, const std::string& integrator) {
    Params p = basic_params(w, h, samples, 12);
    p.set("integrator", integrator);
    p.set("lens", 35.0);
    p.set("sensor_width", 25.0);
    p.set("sensor_height", 25.0);
    return p;
}

}  // namespace candela::test
