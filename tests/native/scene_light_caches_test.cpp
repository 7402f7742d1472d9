// The scene keeps what it derives from its lights (scene/scene_light_caches.cpp): Scene::light_sampler(kind) and
// Scene::emitters() are built once per scene, on first use, from any thread, and survive Scene::set_camera (the 3D
// viewport's view changes and coarse levels render one scene through many cameras and film sizes); each is the
// object a fresh build gives (same strategy, same probabilities), so images do not change.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "lights/emitter_set.h"
#include "lights/light_sampler.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

SceneArrays many_lights() {
    MeshBuilder b;
    b.add_instance(b.add_box(Vec3(3.f, 3.f, 3.f), b.add_material(Color(0.5f), Color(0.f))));
    const uint32_t glow = b.add_material(Color(0.f), Color(3.f));
    for (int i = 0; i < 6; ++i) {
        const float x = -2.f + 0.8f * float(i);
        b.add_instance(b.add_triangle(Vec3(x, 2.9f, -1.f), Vec3(x + 0.3f, 2.9f, -1.f), Vec3(x, 2.9f, -1.4f), glow));
        b.add_point_light(Vec3(x, 1.f, -2.f), Color(2.f + float(i)));
    }
    b.world_color = {0.2f, 0.2f, 0.2f};
    return b.arrays();
}

TEST(SceneLightCaches, BuiltOnceSurviveSetCameraAndEqualAFreshBuild) {
    const Params p = basic_params(16, 12, 1, 2);
    Scene scene(many_lights(), p, nullptr);
    const LightSampleContext at{Vec3(0.3f, -1.f, -1.5f), Vec3(0.f, 1.f, 0.f)};
    for (size_t k = 0; k < light_selection_names().size(); ++k) {
        const auto kind = LightSelection(k);
        const LightSampler& first = scene.light_sampler(kind);
        EXPECT_EQ(&first, &scene.light_sampler(kind)) << first.name();
        const LightSampler fresh = make_light_sampler(kind, scene.lights());
        ASSERT_EQ(first.kind(), fresh.kind());
        ASSERT_EQ(first.size(), fresh.size());
        for (uint32_t i = 0; i < fresh.size(); ++i)
            EXPECT_EQ(first.pmf(at, i), fresh.pmf(at, i)) << first.name() << " light " << i;
    }
    const EmitterSet& emitters = scene.emitters();
    const EmitterSet fresh(scene.lights(), scene.bounds());
    ASSERT_EQ(emitters.size(), fresh.size());
    for (uint32_t i = 0; i < fresh.size(); ++i) EXPECT_EQ(emitters.pmf(i), fresh.pmf(i)) << "emitter " << i;

    // A view change (the viewport's restart or coarse level): the same objects.
    const LightSampler* tree = &scene.light_sampler(LightSelection::Tree);
    Params coarse = p;
    coarse.set("width", int64_t(4));
    coarse.set("height", int64_t(3));
    scene.set_camera(coarse, Affine());
    EXPECT_EQ(tree, &scene.light_sampler(LightSelection::Tree));
    EXPECT_EQ(&emitters, &scene.emitters());
}

TEST(SceneLightCaches, ThreadsAskingAtOnceGetOneObject) {
    const Scene scene(many_lights(), basic_params(16, 12, 1, 2), nullptr);
    std::vector<const LightSampler*> got(4, nullptr);
    std::vector<const EmitterSet*> sets(4, nullptr);
    std::vector<std::thread> threads;
    for (size_t t = 0; t < got.size(); ++t)
        threads.emplace_back([&, t] {
            got[t] = &scene.light_sampler(LightSelection::Tree);
            sets[t] = &scene.emitters();
        });
    for (std::thread& t : threads) t.join();
    for (size_t t = 1; t < got.size(); ++t) {
        EXPECT_EQ(got[t], got[0]);
        EXPECT_EQ(sets[t], sets[0]);
    }
}

}  // namespace
}  // namespace candela::test
