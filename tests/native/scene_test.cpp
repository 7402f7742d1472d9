#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

Params params() { return basic_params(8, 8, 1, 1); }

TEST(Scene, InstancesShareOneMesh) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const uint32_t sphere = b.add_sphere(0.1f, 16, 8, m);
    for (int i = 0; i < 1000; ++i) {
        const float xf[16] = {1, 0, 0, float(i % 10),         0, 1, 0, float(i / 10 % 10),
                              0, 0, 1, -5.f - float(i / 100), 0, 0, 0, 1};
        b.add_instance(sphere, xf);
    }
    SceneArrays a = b.arrays();
    a.validate();
    const Scene scene(a, params(), nullptr);
    const size_t tris = b.triangles.size() / 3;
    EXPECT_EQ(scene.stats().unique_triangles, tris);
    EXPECT_EQ(scene.stats().instanced_triangles, 1000 * tris);
    EXPECT_EQ(scene.stats().instances, 1000u);
    // A ray down −Z from (3, 4, 0) hits the sphere instanced at (3, 4, −5) at distance 5 − 0.1.
    SurfaceHit hit;
    ASSERT_TRUE(scene.intersect({Vec3(3.f, 4.f, 0.f), Vec3(0, 0, -1)}, &hit));
    EXPECT_NEAR(hit.t, 4.9f, 2e-3f);
    EXPECT_NEAR(std::fabs(hit.ng.z), 1.f, 0.05f);
}

TEST(Scene, FlattenedMeshIsTransformedToWorldSpace) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const float xf[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, -3, 0, 0, 0, 1};  // scale 2, move to z = −3
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, 0, m), xf);
    SceneArrays a = b.arrays();
    const Scene scene(a, params(), nullptr);
    SurfaceHit hit;
    ASSERT_TRUE(scene.intersect({Vec3(1.9f, 0.f, 0.f), Vec3(0, 0, -1)}, &hit));  // inside the scaled quad
    EXPECT_NEAR(hit.t, 3.f, 1e-5f);
    EXPECT_FALSE(scene.intersect({Vec3(2.1f, 0.f, 0.f), Vec3(0, 0, -1)}, &hit));
}

TEST(Scene, CameraWorldSpaceKeepsFarScenesIntact) {
    // The same quad 1e5 units away from the origin, seen from a camera next to it.
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const float xf[16] = {1, 0, 0, 1e5f, 0, 1, 0, 1e5f, 0, 0, 1, 1e5f - 2.f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, 0, m), xf);
    const float cam[16] = {1, 0, 0, 1e5f, 0, 1, 0, 1e5f, 0, 0, 1, 1e5f, 0, 0, 0, 1};
    SceneArrays a = b.arrays(cam);
    const Scene scene(a, params(), nullptr);
    SurfaceHit hit;
    const Ray r = scene.camera().generate_ray({4.f, 4.f});
    ASSERT_TRUE(scene.intersect(r, &hit));
    EXPECT_NEAR(hit.t, 2.f, 1e-5f);  // exact in camera-world space
}

TEST(Scene, EmissiveTrianglesBecomeLights) {
    MeshBuilder b;
    const uint32_t lamp = b.add_material(Color(0.f), Color(2.f));
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -1, lamp));
    SceneArrays a = b.arrays();
    const Scene scene(a, params(), nullptr);
    EXPECT_EQ(scene.lights().size(), 2u);
    SurfaceHit hit;
    ASSERT_TRUE(scene.intersect({Vec3(0.2f, 0.3f, 0.f), Vec3(0, 0, -1)}, &hit));
    EXPECT_GE(hit.light, 0);
}

SceneArrays valid_arrays() {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -1, b.add_material(Color(0.5f), Color(0.f))));
    return b.arrays();
}

TEST(SceneArrays, ValidSceneValidates) { EXPECT_NO_THROW(valid_arrays().validate()); }

TEST(SceneArrays, OutOfRangeIndexNamesTheArray) {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -1, b.add_material(Color(0.5f), Color(0.f))));
    b.triangles[4] = 99;
    try {
        b.arrays().validate();
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("triangles[1]"), std::string::npos) << e.what();
    }
}

TEST(SceneArrays, NonFiniteVertexIsRejected) {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -1, b.add_material(Color(0.5f), Color(0.f))));
    b.positions[5] = std::numeric_limits<float>::quiet_NaN();
    try {
        b.arrays().validate();
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("positions[1]"), std::string::npos) << e.what();
    }
}

TEST(SceneArrays, WrongShapeIsRejected) {
    SceneArrays a;
    const float p[6] = {0, 0, 0, 1, 1, 1};
    EXPECT_THROW(a.set("positions", ElemType::F32, {3, 2}, p), InvalidScene);
    EXPECT_THROW(a.set("no_such_array", ElemType::F32, {6}, p), InvalidScene);
}

}  // namespace
}  // namespace candela::test

namespace candela::test {
namespace {

// Camera rays traced eight at a time (Scene::intersect_packet, Embree's packet traversal) find the hits one by
// one tracing finds: the same triangle, and distance and barycentrics equal up to the packet kernel's own
// rounding. Groups of every size 1–8, rays that miss, flattened meshes and shared (instanced) ones.
TEST(Scene, PacketHitsMatchSingleRayHits) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -3, m));  // flattened
    const uint32_t box = b.add_box(Vec3(0.2f, 0.2f, 0.2f), m);
    for (int i = 0; i < 3; ++i) {  // shared: instanced
        const float xf[16] = {1, 0, 0, -0.5f + 0.5f * i, 0, 1, 0, 0.1f * i, 0, 0, 1, -2.f, 0, 0, 0, 1};
        b.add_instance(box, xf);
    }
    const float sphere_xf[16] = {1, 0, 0, 0.6f, 0, 1, 0, -0.6f, 0, 0, 1, -2.5f, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(0.3f, 24, 12, m), sphere_xf);  // flattened, smooth-free facets
    const Scene scene(b.arrays(), basic_params(16, 16, 1, 1), nullptr);
    Pcg32 rng(5, 9);
    int compared = 0, misses = 0;
    for (int py = 0; py < 16; ++py)
        for (int px = 0; px < 16; ++px) {
            const int n = 1 + (px + 16 * py) % Scene::k_packet_size;
            Ray rays[Scene::k_packet_size];
            for (int j = 0; j < n; ++j)
                rays[j] = scene.camera().generate_ray({px + rng.next_float(), py + rng.next_float()});
            TracedHit hits[Scene::k_packet_size];
            scene.intersect_packet(rays, n, hits);
            for (int j = 0; j < n; ++j) {
                SurfaceHit one;
                const bool found = scene.intersect(rays[j], &one);
                ASSERT_EQ(hits[j].found, found) << "pixel " << px << ", " << py << " ray " << j;
                if (!found) {
                    ++misses;
                    continue;
                }
                const SurfaceHit& h = hits[j].hit;
                EXPECT_TRUE(h.primitive == one.primitive);
                EXPECT_EQ(h.object, one.object);
                EXPECT_EQ(h.material, one.material);
                EXPECT_NEAR(h.t, one.t, 1e-5f * one.t);
                EXPECT_NEAR(h.b1, one.b1, 1e-5f);
                EXPECT_NEAR(h.b2, one.b2, 1e-5f);
                EXPECT_NEAR(dot(h.ng, one.ng), 1.f, 1e-6f);
                ++compared;
            }
        }
    EXPECT_GT(compared, 500);
    EXPECT_GT(misses, 50);
}

}  // namespace
}  // namespace candela::test
