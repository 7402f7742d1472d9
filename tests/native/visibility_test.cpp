// Object ray visibility and holdout (scene/ray_visibility.h, integrators/camera_hit.h): each ray type sees only
// the objects visible to it, shadow rays ignore objects hidden from shadows, and holdouts take their weight out of
// alpha (Cycles 3.4's rules).
#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/bsdf_sample.h"
#include "core/error.h"
#include "integrators/ray_types.h"
#include "scene/scene.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// Two parallel planes in front of the camera: instance 0 at z = −2 with `near_flags`, instance 1 at z = −4.
SceneArrays two_planes(uint8_t near_flags, MeshBuilder* builder = nullptr) {
    MeshBuilder local;
    MeshBuilder& b = builder ? *builder : local;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_quad_z(-10.f, 10.f, -10.f, 10.f, -2.f, m));
    b.add_instance(b.add_quad_z(-10.f, 10.f, -10.f, 10.f, -4.f, m));
    SceneArrays a = b.arrays();
    const uint8_t flags[2] = {near_flags, k_object_default};
    a.set("instance_flags", ElemType::U8, {2}, flags);
    return a;
}

float first_hit_distance(const Scene& scene, uint8_t ray_type) {
    Ray r{Vec3(0.f), Vec3(0.f, 0.f, -1.f)};
    r.type = ray_type;
    SurfaceHit hit;
    return scene.intersect(r, &hit) ? hit.t : -1.f;
}

TEST(Visibility, EachRayTypeSeesOnlyTheObjectsVisibleToIt) {
    const uint8_t types[] = {k_ray_camera, k_ray_diffuse, k_ray_glossy, k_ray_transmission};
    for (uint8_t hidden : types) {
        const SceneArrays a = two_planes(uint8_t(k_object_default & ~hidden));
        const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
        for (uint8_t type : types)
            EXPECT_NEAR(first_hit_distance(scene, type), type == hidden ? 4.f : 2.f, 1e-5f)
                << "object hidden from " << int(hidden) << ", ray type " << int(type);
        EXPECT_NEAR(first_hit_distance(scene, k_ray_all), 2.f, 1e-5f);  // an untyped ray sees it
    }
}

TEST(Visibility, ShadowRaysIgnoreObjectsHiddenFromShadows) {
    const SceneArrays shadowing = two_planes(k_object_default);
    const Scene a(shadowing, basic_params(8, 8, 1, 1), nullptr);
    EXPECT_TRUE(a.occluded(Vec3(0.f), Vec3(0.f, 0.f, -1.f), 3.f));
    const SceneArrays hidden = two_planes(uint8_t(k_object_default & ~k_ray_shadow));
    const Scene b(hidden, basic_params(8, 8, 1, 1), nullptr);
    EXPECT_FALSE(b.occluded(Vec3(0.f), Vec3(0.f, 0.f, -1.f), 3.f));
    EXPECT_TRUE(b.occluded(Vec3(0.f), Vec3(0.f, 0.f, -1.f), 5.f));  // the far plane still shadows
    EXPECT_NEAR(first_hit_distance(b, k_ray_camera), 2.f, 1e-5f);   // and the camera still sees the near one
}

TEST(Visibility, InstancedMeshesHonourTheirOwnFlags) {
    // One mesh drawn twice (an Embree instance each): hiding one instance must not hide the other.
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const uint32_t quad = b.add_quad_z(-10.f, 10.f, -10.f, 10.f, 0.f, m);
    const float near_xf[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -2, 0, 0, 0, 1};
    const float far_xf[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -4, 0, 0, 0, 1};
    b.add_instance(quad, near_xf);
    b.add_instance(quad, far_xf);
    SceneArrays a = b.arrays();
    const uint8_t flags[2] = {uint8_t(k_object_default & ~k_ray_camera), k_object_default};
    a.set("instance_flags", ElemType::U8, {2}, flags);
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    ASSERT_EQ(scene.stats().instances, 2u);
    EXPECT_NEAR(first_hit_distance(scene, k_ray_camera), 4.f, 1e-5f);
    EXPECT_NEAR(first_hit_distance(scene, k_ray_diffuse), 2.f, 1e-5f);
}

TEST(Visibility, ContinuationRayTypesFollowCycles) {
    BsdfSample s;
    s.flags = k_bsdf_reflection | k_bsdf_diffuse;
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_diffuse);
    s.flags = k_bsdf_reflection | k_bsdf_glossy;
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_glossy);
    s.flags = k_bsdf_reflection | k_bsdf_specular;  // a mirror counts as glossy
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_glossy);
    s.flags = k_bsdf_transmission | k_bsdf_diffuse;  // translucent
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_transmission);
    s.flags = k_bsdf_transmission | k_bsdf_specular;
    s.eta = 1.5f;  // glass
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_transmission);
    s.eta = 1.f;  // glass of IOR 1 still refracts (Cycles: a transmission ray), only a Transparent BSDF does not
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_transmission);
    s.flags = k_bsdf_transmission | k_bsdf_specular | k_bsdf_transparent;  // transparent: the ray keeps its type
    EXPECT_EQ(continuation_ray_type(s, k_ray_camera), k_ray_camera);
    EXPECT_EQ(continuation_ray_type(s, k_ray_diffuse), k_ray_diffuse);
}

/// Alpha and luminance of a render of a lit plane (instance 0, white) in front of a transparent film, with an
/// optional holdout object or material in front of its left half.
struct AlphaImage {
    std::vector<float> rgba;
    int w = 16, h = 8;
    float alpha(int x, int y) const { return rgba[4 * (size_t(y) * w + x) + 3]; }
    float lum(int x, int y) const {
        const float* p = &rgba[4 * (size_t(y) * w + x)];
        return luminance(Color(p[0], p[1], p[2]));
    }
};

AlphaImage render_holdout(uint8_t blocker_flags, float material_holdout) {
    MeshBuilder b;
    const uint32_t white = b.add_material(Color(0.8f), Color(0.f));
    const uint32_t other = b.add_material(Color(0.8f), Color(0.f));
    b.add_instance(b.add_quad_z(-10.f, 10.f, -10.f, 10.f, -4.f, white));  // fills the view
    b.add_instance(b.add_quad_z(-10.f, 0.f, -10.f, 10.f, -2.f, other));   // the left half of the view
    b.add_point_light(Vec3(0.f, 0.f, 0.f), Color(200.f));
    SceneArrays a = b.arrays();
    const uint8_t flags[2] = {k_object_default, blocker_flags};
    a.set("instance_flags", ElemType::U8, {2}, flags);
    const float holdout[2] = {0.f, material_holdout};
    a.set("material_holdout", ElemType::F32, {2}, holdout);
    Params p = basic_params(16, 8, 4, 2);
    p.set("film_transparent", true);
    Session s(std::move(a), std::move(p));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    AlphaImage img;
    int ch = 0;
    img.rgba = s.get_pass("Combined", &ch);
    return img;
}

TEST(Holdout, HoldoutObjectPunchesAlphaAndEndsThePath) {
    // The blocker covers pixel columns 0–7 (x < 0); away from its edge (box filter: samples stay in the pixel).
    const AlphaImage img = render_holdout(k_object_default | k_object_holdout, 0.f);
    for (int y = 0; y < img.h; ++y) {
        for (int x = 0; x < 7; ++x) {
            EXPECT_EQ(img.alpha(x, y), 0.f);
            EXPECT_EQ(img.lum(x, y), 0.f);
        }
        for (int x = 9; x < img.w; ++x) {
            EXPECT_EQ(img.alpha(x, y), 1.f);
            EXPECT_GT(img.lum(x, y), 0.f);
        }
    }
}

TEST(Holdout, HoldoutClosureWeightIsTakenOutOfAlpha) {
    const AlphaImage half = render_holdout(k_object_default, 0.5f);
    const AlphaImage none = render_holdout(k_object_default, 0.f);
    for (int y = 0; y < half.h; ++y)
        for (int x = 0; x < 7; ++x) {
            EXPECT_FLOAT_EQ(half.alpha(x, y), 0.5f);
            EXPECT_EQ(none.alpha(x, y), 1.f);
        }
}

TEST(Holdout, CameraInvisibleHoldoutCutsNothing) {
    const AlphaImage img = render_holdout(uint8_t((k_object_default & ~k_ray_camera) | k_object_holdout), 0.f);
    for (int y = 0; y < img.h; ++y)
        for (int x = 0; x < img.w; ++x) EXPECT_EQ(img.alpha(x, y), 1.f);
}

TEST(Visibility, BadFlagsAndHoldoutsAreRejected) {
    MeshBuilder b;
    SceneArrays a = two_planes(k_object_default, &b);
    const uint8_t bad[2] = {64, 0};
    a.set("instance_flags", ElemType::U8, {2}, bad);
    EXPECT_THROW(a.validate(), InvalidScene);
    SceneArrays c = two_planes(k_object_default);
    const uint8_t one[1] = {0};
    c.set("instance_flags", ElemType::U8, {1}, one);
    EXPECT_THROW(c.validate(), InvalidScene);
    SceneArrays d = two_planes(k_object_default);
    const float w = 1.5f;
    d.set("material_holdout", ElemType::F32, {1}, &w);
    EXPECT_THROW(d.validate(), InvalidScene);
}

}  // namespace
}  // namespace candela::test
