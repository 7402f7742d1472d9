// Bad input reaching the native core: a clear error naming the problem, never a crash, a hang or an
// allocation that cannot succeed.
#include <gtest/gtest.h>

#include <chrono>

#include "core/error.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

SceneArrays small_scene() {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -2, b.add_material(Color(0.5f), Color(1.f))));
    return b.arrays();
}

std::string error_of(SceneArrays a, Params p) {
    try {
        Session s(std::move(a), std::move(p));
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

TEST(BadInput, HugeResolutionIsRefusedBeforeAllocation) {
    const std::string e = error_of(small_scene(), basic_params(1000000, 1000000, 1, 1));
    EXPECT_NE(e.find("GB"), std::string::npos) << e;
}

TEST(BadInput, ZeroResolutionIsRefused) {
    EXPECT_NE(error_of(small_scene(), basic_params(0, 10, 1, 1)).find("resolution"), std::string::npos);
}

TEST(BadInput, MeshWithoutFacesRendersNothingForIt) {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -2, b.add_material(Color(0.5f), Color(1.f))));
    b.mesh_tri_start.push_back(b.mesh_tri_start.back());  // an empty mesh
    b.add_instance(1);
    const RenderResult r = render(b.arrays(), basic_params(8, 8, 1, 1));
    EXPECT_GT(r.mean_rgb, 0.0);
}

TEST(BadInput, SceneWithoutLightsWarnsAndIsBlack) {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -2, b.add_material(Color(0.5f), Color(0.f))));
    Session s(b.arrays(), basic_params(8, 8, 1, 1));
    s.start();
    s.join();
    bool warned = false;
    for (const auto& line : s.take_log()) warned |= line.find("no lights") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(BadInput, CancelDuringTheBvhBuildReturnsQuickly) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_sphere(1.f, 1024, 512, m));  // a million triangles
    b.add_point_light(Vec3(0.f), Color(1.f));
    Session s(b.arrays(), basic_params(64, 64, 1000, 8));
    s.start();
    s.cancel();
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_TRUE(s.wait(10.0));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(s.progress().phase, SessionPhase::Cancelled);
    EXPECT_FALSE(s.error().has_value());
    EXPECT_LT(seconds, 2.0);
}

}  // namespace
}  // namespace candela::test
