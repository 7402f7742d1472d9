// AUTO's static scene features (native/integrators/auto/scene_features.h, docs/auto.md "Features") on built
// scenes: a diffuse box, a glass sphere, a mirror under delta, soft and large lights, constant and textured worlds, an
// orthographic camera, hidden objects, a zero-strength light. Each feature is exact (areas to float rounding).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/auto/scene_features.h"
#include "reference_scenes.h"
#include "scene/scene.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr double k_pi_d = 3.14159265358979;

SceneFeatures features_of(const SceneArrays& a, const Params& p = basic_params(8, 8, 1, 2)) {
    const Scene scene(a, p, nullptr);
    return analyse_scene(scene);
}

// A 4 × 4 diffuse floor at y = −1 and, with `mirror`, a 2 × 2 mirror standing on it.
MeshBuilder floor_and_mirror(bool mirror) {
    MeshBuilder b;
    const uint32_t floor = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(add_parallelogram(b, Vec3(-2.f, -1.f, -6.f), Vec3(0.f, 0.f, 4.f), Vec3(4.f, 0.f, 0.f), floor));
    if (mirror) {
        const uint32_t m = b.add_material(Color(0.f), Color(0.f));
        b.add_closure(m, "GLOSSY", {{"color_r", 0.9f}, {"color_g", 0.9f}, {"color_b", 0.9f}, {"roughness", 0.f}});
        b.add_instance(add_parallelogram(b, Vec3(-1.f, -1.f, -5.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 2.f, 0.f), m));
    }
    return b;
}

TEST(SceneFeatures, DiffuseBoxUnderALargePanel) {
    const SceneFeatures f = features_of(cornell_box());
    EXPECT_EQ(f.light_count, 2);  // the panel's two triangles
    EXPECT_EQ(f.large_emitters, 1);
    EXPECT_EQ(f.small_emitters, 0);
    EXPECT_EQ(f.unhittable_lights, 0);
    EXPECT_EQ(f.delta_lights, 0);
    EXPECT_EQ(f.zero_power_lights, 0);
    EXPECT_EQ(f.world, WorldKind::None);
    EXPECT_NEAR(f.emissive_area, 0.25, 1e-5);                // 0.5 × 0.5
    EXPECT_NEAR(f.diffuse_area, f.total_area - 0.25, 1e-6);  // everything but the panel (a pure emitter: no lobe)
    EXPECT_EQ(f.specular_area, 0.0);
    EXPECT_EQ(f.glossy_area, 0.0);
    EXPECT_EQ(f.transmissive_area, 0.0);
    EXPECT_EQ(f.specular_materials, 0);
    EXPECT_FALSE(f.caustic_paths);
    EXPECT_FALSE(f.orthographic);
    EXPECT_TRUE(f.camera_connectable);
    EXPECT_EQ(f.hidden_ray_types, 0u);
    EXPECT_NEAR(f.total_power, 2.0 * k_pi_d * 0.25 * luminance(Color(17.f, 12.f, 4.f)), 1e-3);
}

TEST(SceneFeatures, GlassSphereUnderASmallLight) {
    const SceneFeatures f = features_of(glass_caustic());
    EXPECT_EQ(f.light_count, 1);
    EXPECT_EQ(f.small_emitters, 1);  // a 0.3-wide disk: 0.0707 of area against πR² ≈ 32
    EXPECT_EQ(f.large_emitters, 0);
    EXPECT_NEAR(f.small_power_share(), 1.0, 1e-12);
    EXPECT_EQ(f.specular_materials, 1);
    EXPECT_EQ(f.transmissive_materials, 1);
    EXPECT_NEAR(f.diffuse_area, 16.0 + 12.0, 1e-4);  // the 4 × 4 floor and the 4 × 3 wall
    EXPECT_EQ(f.specular_area, f.transmissive_area);
    // A UV sphere of radius 0.5 inscribed in the true sphere: a little under 4π·0.25.
    EXPECT_GT(f.specular_area, 0.97 * k_pi_d);
    EXPECT_LT(f.specular_area, k_pi_d);
    EXPECT_NEAR(f.total_area, f.diffuse_area + f.specular_area, 1e-4);
    EXPECT_TRUE(f.caustic_paths);
}

TEST(SceneFeatures, MirrorUnderAPointLightHasCausticPathsUnderALargeLightNot) {
    MeshBuilder b = floor_and_mirror(true);
    b.add_point_light(Vec3(0.f, 1.f, -3.f), Color(50.f));
    const SceneFeatures f = features_of(b.arrays());
    EXPECT_EQ(f.unhittable_lights, 1);
    EXPECT_EQ(f.delta_lights, 1);
    EXPECT_NEAR(f.unhittable_power_share(), 1.0, 1e-12);
    EXPECT_EQ(f.specular_materials, 1);
    EXPECT_EQ(f.transmissive_materials, 0);
    EXPECT_NEAR(f.specular_area, 4.0, 1e-5);
    EXPECT_NEAR(f.diffuse_area, 16.0, 1e-5);
    EXPECT_EQ(f.transmissive_area, 0.0);
    EXPECT_TRUE(f.caustic_paths);

    MeshBuilder soft = floor_and_mirror(true);
    soft.add_point_light(Vec3(0.f, 1.f, -3.f), Color(50.f), 0.1f);
    const SceneFeatures fs = features_of(soft.arrays());
    EXPECT_EQ(fs.unhittable_lights, 1);  // a soft point light is still never hit
    EXPECT_EQ(fs.delta_lights, 0);
    EXPECT_TRUE(fs.caustic_paths);

    MeshBuilder large = floor_and_mirror(true);
    large.add_area_light(Vec3(0.f, 2.f, -4.f), Vec3(3.f, 0.f, 0.f), Vec3(0.f, 0.f, 3.f), Vec3(0.f, -1.f, 0.f),
                         Color(100.f), false);
    const SceneFeatures fl = features_of(large.arrays());
    EXPECT_EQ(fl.large_emitters, 1);
    EXPECT_EQ(fl.small_emitters, 0);
    EXPECT_FALSE(fl.caustic_paths);  // the path tracer hits a 9 m² light after the mirror often enough

    MeshBuilder plain = floor_and_mirror(false);
    plain.add_point_light(Vec3(0.f, 1.f, -3.f), Color(50.f));
    EXPECT_FALSE(features_of(plain.arrays()).caustic_paths);  // no delta surface
}

TEST(SceneFeatures, ConstantAndTexturedWorlds) {
    MeshBuilder b = floor_and_mirror(false);
    EXPECT_EQ(features_of(b.arrays()).world, WorldKind::None);
    b.world_color = {0.2f, 0.3f, 0.4f};
    const SceneFeatures c = features_of(b.arrays());
    EXPECT_EQ(c.world, WorldKind::Constant);
    EXPECT_EQ(c.light_count, 0);  // a constant world is the background, not a light
    MeshBuilder t = floor_and_mirror(false);
    SceneArrays a = t.arrays();
    ProgramBuilder pb;
    const uint32_t tex = pb.image(8, 4, std::vector<Color>(32, Color(0.5f)));
    const uint32_t dir = pb.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
    const uint32_t img =
        pb.op(ShaderOpCode::Image, dir, 0, 0,
              {tex, uint32_t(TexInterpolation::Linear), 0, uint32_t(ImageProjection::Equirectangular)});
    pb.bind(InputTarget::World, 0, 0, 3, pb.end_program(), img);
    pb.add_to(a);
    const SceneFeatures e = features_of(a);
    EXPECT_EQ(e.world, WorldKind::Textured);
    EXPECT_EQ(e.light_count, 1);
    EXPECT_EQ(e.unhittable_lights + e.small_emitters + e.large_emitters, 0);  // the world is none of those
}

TEST(SceneFeatures, OrthographicCamera) {
    MeshBuilder b = floor_and_mirror(false);
    b.add_point_light(Vec3(0.f, 1.f, -3.f), Color(50.f));
    Params p = basic_params(8, 8, 1, 2);
    p.set("camera_type", std::string("ORTHO"));
    p.set("ortho_scale", 4.f);
    const SceneFeatures o = features_of(b.arrays(), p);
    EXPECT_TRUE(o.orthographic);
    EXPECT_FALSE(o.camera_connectable);
    const SceneFeatures persp = features_of(b.arrays());
    EXPECT_FALSE(persp.orthographic);
    EXPECT_TRUE(persp.camera_connectable);
}

TEST(SceneFeatures, HiddenObjects) {
    MeshBuilder b = floor_and_mirror(true);
    b.add_point_light(Vec3(0.f, 1.f, -3.f), Color(50.f));
    SceneArrays a = b.arrays();
    const uint8_t flags[2] = {uint8_t(k_object_default), uint8_t(k_object_default & ~k_ray_diffuse)};
    a.set("instance_flags", ElemType::U8, {2}, flags);
    const SceneFeatures f = features_of(a);
    EXPECT_EQ(f.hidden_ray_types, uint32_t(k_ray_diffuse));
    EXPECT_TRUE(f.caustic_paths);

    SceneArrays cam = floor_and_mirror(true).arrays();
    const uint8_t camera_hidden[2] = {uint8_t(k_object_default), uint8_t(k_object_default & ~k_ray_camera)};
    cam.set("instance_flags", ElemType::U8, {2}, camera_hidden);
    EXPECT_EQ(features_of(cam).hidden_ray_types, uint32_t(k_ray_camera));
}

TEST(SceneFeatures, NoLightsAndZeroStrengthLights) {
    MeshBuilder b = floor_and_mirror(false);
    b.add_point_light(Vec3(0.f, 1.f, -3.f), Color(0.f));  // dropped at load (lights/light.h)
    const SceneFeatures f = features_of(b.arrays());
    EXPECT_EQ(f.light_count, 0);
    EXPECT_EQ(f.zero_power_lights, 0);
    EXPECT_EQ(f.world, WorldKind::None);
}

}  // namespace
}  // namespace candela::test
