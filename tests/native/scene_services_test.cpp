// What the scene offers integrators besides ray queries: the bounding sphere, occlusion by ray type, and the
// BSDF flags a material can have (scene analysis).
#include <gtest/gtest.h>

#include "bsdf/bsdf_sample.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

TEST(SceneServices, TheBoundingSphereEnclosesGeometryAreaLightsAndPointLights) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_quad_z(-1.f, 3.f, -2.f, 2.f, -5.f, m));
    b.add_point_light(Vec3(-4.f, 0.f, -5.f), Color(1.f));
    b.add_area_light(Vec3(0.f, 6.f, -5.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 0.f, 2.f), Vec3(0.f, -1.f, 0.f), Color(1.f),
                     false);
    const SceneArrays a = b.arrays();
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    const SceneSphere& s = scene.bounds();
    // Everything lies in x ∈ [−4, 3], y ∈ [−2, 6], z ∈ [−6, −4] (the camera at the origin: camera-world space).
    const Vec3 points[] = {{-1, -2, -5}, {3, 2, -5}, {-4, 0, -5}, {-1, 6, -6}, {1, 6, -4}};
    for (const Vec3& p : points) EXPECT_LE(length(p - s.center), s.radius * (1.f + 1e-5f));
    EXPECT_NEAR(s.center.x, -0.5f, 1e-5f);
    EXPECT_NEAR(s.center.y, 2.f, 1e-5f);
    EXPECT_NEAR(s.center.z, -5.f, 1e-5f);
    EXPECT_NEAR(s.radius, 0.5f * std::sqrt(7.f * 7.f + 8.f * 8.f + 2.f * 2.f), 1e-4f);
}

// A connection to the camera is a CAMERA ray: an object hidden from the camera does not block it, while it still
// casts shadows — and the reverse for an object hidden from shadows.
TEST(SceneServices, OcclusionHonoursTheRayType) {
    for (uint8_t hidden : {uint8_t(k_ray_camera), uint8_t(k_ray_shadow)}) {
        MeshBuilder b;
        const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
        b.add_instance(b.add_quad_z(-10.f, 10.f, -10.f, 10.f, -2.f, m));
        SceneArrays a = b.arrays();
        const uint8_t flags[1] = {uint8_t(k_object_default & ~hidden)};
        a.set("instance_flags", ElemType::U8, {1}, flags);
        const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
        const Vec3 o(0.f), d(0.f, 0.f, -3.f);
        EXPECT_EQ(scene.occluded(o, d, 1.f, k_ray_camera), hidden != k_ray_camera);
        EXPECT_EQ(scene.occluded(o, d, 1.f, k_ray_shadow), hidden != k_ray_shadow);
        EXPECT_EQ(scene.occluded(o, d, 1.f), hidden != k_ray_shadow);  // the default: a shadow ray
    }
}

TEST(SceneServices, MaterialFlagsSayWhatEachMaterialCanDo) {
    MeshBuilder b;
    const uint32_t diffuse = b.add_material(Color(0.5f), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    const uint32_t mirror = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(mirror, "GLOSSY", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"roughness", 0.f}});
    const uint32_t rough = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(rough, "GLOSSY", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"roughness", 0.5f}});
    b.add_instance(b.add_quad_z(-1.f, 1.f, -1.f, 1.f, -2.f, diffuse));
    const SceneArrays a = b.arrays();
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    EXPECT_EQ(scene.material_flags(diffuse), uint32_t(k_bsdf_reflection | k_bsdf_diffuse));
    EXPECT_TRUE(scene.material_flags(glass) & k_bsdf_specular);
    EXPECT_TRUE(scene.material_flags(glass) & k_bsdf_transmission);
    EXPECT_TRUE(scene.material_flags(mirror) & k_bsdf_specular);
    EXPECT_FALSE(scene.material_flags(mirror) & k_bsdf_transmission);
    EXPECT_EQ(scene.material_flags(rough), uint32_t(k_bsdf_reflection | k_bsdf_glossy));
}

}  // namespace
}  // namespace candela::test
