#include "motion_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace candela::test {

std::vector<float> rows_of(const Affine& a) {
    std::vector<float> r(16, 0.f);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) r[4 * i + j] = a.m[i][j];
    r[15] = 1.f;
    return r;
}

Affine rotation_y(float angle, Vec3 t) {
    Affine a;
    a.m[0][0] = std::cos(angle);
    a.m[0][2] = std::sin(angle);
    a.m[2][0] = -std::sin(angle);
    a.m[2][2] = std::cos(angle);
    a.m[0][3] = t.x;
    a.m[1][3] = t.y;
    a.m[2][3] = t.z;
    return a;
}

Affine translation(Vec3 t) { return rotation_y(0.f, t); }

SceneArrays moving_box(float x0, float x1, bool moves, bool emitter_backdrop, float albedo) {
    MeshBuilder b;
    const uint32_t black = b.add_material(Color(albedo), Color(0.f));
    const uint32_t box = b.add_box(Vec3(0.5f), black);
    const std::vector<float> start = rows_of(translation(Vec3(x0, 0.f, -5.f)));
    b.add_instance(box, start.data());
    if (emitter_backdrop) {  // an emitting wall behind: light-rooted integrators then see the same image
        const uint32_t glow = b.add_material(Color(albedo), Color(1.f));  // reflecting the box's light if grey
        b.add_instance(b.add_quad_z(-6.f, 6.f, -6.f, 6.f, -8.f, glow));
    } else {
        b.world_color = {1.f, 1.f, 1.f};
    }
    SceneArrays a = b.arrays();
    if (moves) {
        const size_t instances = a.rows("instance_mesh");
        std::vector<float> motion;
        for (size_t i = 0; i < instances; ++i) {
            const float* still = a.get("instance_transform").data<float>() + 16 * i;
            const std::vector<float> end = rows_of(translation(Vec3(x1, 0.f, -5.f)));
            motion.insert(motion.end(), still, still + 16);
            const float* second = i == 0 ? end.data() : still;  // only the box moves
            motion.insert(motion.end(), second, second + 16);
        }
        a.set("instance_motion", ElemType::F32, {instances, 2, 4, 4}, motion.data());
    }
    return a;
}

Blocks blocks_of(const RenderResult& r, int b) {
    Blocks out;
    for (int by = 0; by < r.height / b; ++by)
        for (int bx = 0; bx < r.width / b; ++bx) {
            double sum = 0.0, var = 0.0;
            for (int y = by * b; y < (by + 1) * b; ++y)
                for (int x = bx * b; x < (bx + 1) * b; ++x) {
                    const size_t i = size_t(y) * r.width + x;
                    sum += (r.rgba[4 * i] + r.rgba[4 * i + 1] + r.rgba[4 * i + 2]) / 3.0;
                    var += double(r.noise[i]) * r.noise[i];
                }
            out.mean.push_back(sum / (b * b));
            out.sigma.push_back(std::sqrt(var) / (b * b));
        }
    return out;
}

void expect_blocks_agree(const Blocks& a, const Blocks& b, double quadrature, const std::string& what) {
    ASSERT_EQ(a.mean.size(), b.mean.size());
    double largest = 0.0;
    for (size_t i = 0; i < a.mean.size(); ++i) {
        const double sigma = std::sqrt(a.sigma[i] * a.sigma[i] + b.sigma[i] * b.sigma[i]);
        EXPECT_LE(std::fabs(a.mean[i] - b.mean[i]), 4.5 * sigma + quadrature)
            << what << ": block " << i << " " << a.mean[i] << " vs " << b.mean[i] << " (σ " << sigma << ")";
        largest = std::fmax(largest, std::fabs(a.mean[i] - b.mean[i]));
    }
    ::testing::Test::RecordProperty(what + "_largest_block_difference", std::to_string(largest));
}

Params motion_params(const std::string& integrator, int samples, int threads) {
    Params p = basic_params(32, 32, samples, 0);
    p.set("integrator", integrator);
    p.set("threads", int64_t(threads));
    p.set("sampler", std::string("RANDOM"));
    return p;
}

SceneArrays grey_moving_box() { return moving_box(-1.f, 1.f, true, true, 0.5f); }
Params grey_box_params(const std::string& integrator, int samples, int threads) {
    Params p = motion_params(integrator, samples, threads);
    p.set("max_bounces", int64_t(2));
    return p;
}

}  // namespace candela::test
