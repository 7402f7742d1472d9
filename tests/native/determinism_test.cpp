// The same seed renders the same image whatever the thread count or tile size.
#include <gtest/gtest.h>

#include "core/math.h"
#include "integrators/integrator.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

SceneArrays lit_scene() {
    MeshBuilder b;
    const uint32_t grey = b.add_material(Color(0.7f, 0.5f, 0.3f), Color(0.f));
    const uint32_t lamp = b.add_material(Color(0.f), Color(4.f, 3.f, 2.f));
    b.add_instance(b.add_sphere(2.f, 48, 24, grey));
    b.add_instance(b.add_quad_z(-0.3f, 0.3f, -0.3f, 0.3f, -1.5f, lamp));
    b.add_point_light(Vec3(0.5f, 0.5f, -1.f), Color(20.f), 0.1f);
    return b.arrays();
}

RenderResult render_with(int threads, int tile_size, int seed, const std::string& integrator = "PATH") {
    Params p = basic_params(40, 30, 12, 8);
    p.set("integrator", integrator);
    p.set("threads", int64_t(threads));
    p.set("tile_size", int64_t(tile_size));
    p.set("seed", int64_t(seed));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    return render(lit_scene(), p);
}

TEST(Determinism, SameImageForOneAndTwoThreads) {
    const RenderResult one = render_with(1, 32, 3), two = render_with(2, 32, 3);
    ASSERT_EQ(one.rgba.size(), two.rgba.size());
    for (size_t i = 0; i < one.rgba.size(); ++i) ASSERT_EQ(one.rgba[i], two.rgba[i]) << "value " << i;
}

TEST(Determinism, SameImageForAnyTileSize) {
    const RenderResult a = render_with(2, 8, 3), b = render_with(2, 64, 3);
    for (size_t i = 0; i < a.rgba.size(); ++i) ASSERT_EQ(a.rgba[i], b.rgba[i]) << "value " << i;
}

// Every integrator of the registry: 1 vs 4 threads and two tile sizes give the same image, bit for bit.
TEST(Determinism, EveryIntegratorIsThreadCountAndTileOrderInvariant) {
    for (const IntegratorEntry& e : integrator_registry()) {
        const RenderResult a = render_with(1, 8, 5, e.name), b = render_with(4, 64, 5, e.name);
        ASSERT_EQ(a.rgba.size(), b.rgba.size());
        size_t differ = 0;
        for (size_t i = 0; i < a.rgba.size(); ++i) differ += a.rgba[i] != b.rgba[i];
        EXPECT_EQ(differ, 0u) << e.name;
        for (size_t i = 0; i < a.noise.size(); ++i) ASSERT_EQ(a.noise[i], b.noise[i]) << e.name << " noise " << i;
    }
}

TEST(Determinism, DifferentSeedsDiffer) {
    const RenderResult a = render_with(2, 32, 3), b = render_with(2, 32, 4);
    size_t differ = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) differ += a.rgba[i] != b.rgba[i];
    EXPECT_GT(differ, a.rgba.size() / 4);
}

}  // namespace
}  // namespace candela::test
