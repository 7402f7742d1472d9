// Motion blur (docs/light_paths.md, "Motion blur"): the transform interpolation, the scene's moving instances and
// camera, the shutter passes' times and the notes. The image of a moving scene is the time average of its still
// images over the shutter: PATH's render with motion is compared, block by block, with the mean of still renders
// at evenly spaced times (the midpoint rule over the shutter), within statistical tolerances from both renders'
// noise estimates. The other integrators are compared with PATH in motion_blur_integrators_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/motion_transform.h"
#include "integrators/integrator.h"
#include "motion_scenes.h"
#include "scene/scene.h"
#include "scene/shutter_time.h"
#include "scene/surface_sampler.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

float max_difference(const Affine& a, const Affine& b) {
    float d = 0.f;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) d = std::fmax(d, std::fabs(a.m[i][j] - b.m[i][j]));
    return d;
}

TEST(MotionTransform, DecompositionComposesBackToTheMatrix) {
    Affine m = rotation_y(0.7f, Vec3(1.f, -2.f, 3.f));
    m.m[0][1] = 0.3f;  // a shear
    for (int r = 0; r < 3; ++r) m.m[r][2] *= 2.5f;
    Affine mirrored = m;
    for (int r = 0; r < 3; ++r) mirrored.m[r][0] = -mirrored.m[r][0];
    EXPECT_LT(max_difference(DecomposedTransform::from(m).compose(), m), 1e-5f);
    EXPECT_LT(max_difference(DecomposedTransform::from(mirrored).compose(), mirrored), 1e-5f);
}

TEST(MotionTransform, RotationsInterpolateOnTheArc) {
    // A quarter turn over the shutter: at its middle an eighth turn (slerp), not the shrunken chord a linear blend
    // of the matrices gives; the translation moves linearly.
    const MotionTransform motion({rotation_y(0.f, Vec3(0.f)), rotation_y(1.5707963f, Vec3(2.f, 0.f, 0.f))});
    EXPECT_LT(max_difference(motion.at(0.5f), rotation_y(0.78539816f, Vec3(1.f, 0.f, 0.f))), 1e-5f);
    EXPECT_LT(max_difference(motion.at(0.25f), rotation_y(0.39269908f, Vec3(0.5f, 0.f, 0.f))), 1e-5f);
    EXPECT_LT(max_difference(motion.at(0.f), rotation_y(0.f)), 1e-6f);
    // Three samples: the second half follows the second pair.
    const MotionTransform three(
        {translation(Vec3(0.f)), translation(Vec3(1.f, 0.f, 0.f)), translation(Vec3(1.f, 4.f, 0.f))});
    EXPECT_LT(max_difference(three.at(0.75f), translation(Vec3(1.f, 2.f, 0.f))), 1e-6f);
}

/// The mean of n still renders at the midpoints of n equal parts of the shutter (its σ combines theirs).
Blocks still_average(int n, int b, const std::function<RenderResult(float)>& render_at) {
    Blocks sum;
    for (int k = 0; k < n; ++k) {
        const Blocks one = blocks_of(render_at((float(k) + 0.5f) / float(n)), b);
        if (sum.mean.empty()) sum.mean.assign(one.mean.size(), 0.0), sum.sigma.assign(one.mean.size(), 0.0);
        for (size_t i = 0; i < one.mean.size(); ++i) {
            sum.mean[i] += one.mean[i] / n;
            sum.sigma[i] += one.sigma[i] * one.sigma[i] / (double(n) * n);
        }
    }
    for (double& s : sum.sigma) s = std::sqrt(s);
    return sum;
}

/// The midpoint rule's error over the shutter for an edge of full contrast (1: black on white) sweeping `shift_px`
/// pixels across b×b blocks, with n still times. With the 1-pixel box filter a block's value is linear in the
/// edge's position while the edge crosses it and constant otherwise: piecewise linear in time with slope at most
/// s = shift_px/b per shutter, kinks where an edge enters or leaves (at most 4: two edges). The midpoint rule is
/// exact on linear pieces; a kink of slope jump s in a part of width h = 1/n costs at most s·h²/8.
double midpoint_bound(double shift_px, int n, int b) { return 4.0 * (shift_px / b) / (8.0 * n * n); }

// The camera (basic_params: a 36 mm sensor behind a 50 mm lens, 32 px) sees 1 unit at the box's front face
// (z = −4.5) as 32/(4.5·0.72) ≈ 9.9 px: moving the box 2 units sweeps ~20 px.
constexpr double k_shift_px = 20.0;

TEST(MotionBlur, MovingBoxIsTheTimeAverageOfStillBoxes) {
    const int n = 16, b = 4;
    const RenderResult moving = render(moving_box(-1.f, 1.f, true), motion_params("PATH", 512));
    const Blocks still = still_average(
        n, b, [&](float t) { return render(moving_box(-1.f + 2.f * t, 0.f, false), motion_params("PATH", 64)); });
    expect_blocks_agree(blocks_of(moving, b), still, midpoint_bound(k_shift_px, n, b), "PATH");
    // And it is not the still box at the shutter's middle: the blur is there.
    const Blocks middle = blocks_of(render(moving_box(0.f, 0.f, false), motion_params("PATH", 64)), b);
    double largest = 0.0;
    const Blocks m = blocks_of(moving, b);
    for (size_t i = 0; i < m.mean.size(); ++i) largest = std::fmax(largest, std::fabs(m.mean[i] - middle.mean[i]));
    EXPECT_GT(largest, 0.2);
}

TEST(MotionBlur, ShutterPassesAreStratifiedAndEveryPrefixSpreads) {
    // stratified_shutter_time: n passes hold one time in each 1/n of the shutter, and the first j of them leave no
    // gap over 4/j + 2/n (their strata's largest gap is under 4/j: shutter_time.h).
    for (uint64_t n : {1u, 2u, 3u, 7u, 16u, 40u, 64u, 100u, 257u}) {
        std::vector<int> hits(n, 0);
        std::vector<float> times;
        for (uint64_t j = 0; j < n; ++j) {
            const float t = stratified_shutter_time(99, j, n);
            ASSERT_GE(t, 0.f);
            ASSERT_LT(t, 1.f);
            ++hits[std::min<uint64_t>(n - 1, uint64_t(double(t) * double(n)))];
            times.push_back(t);
            if (j < 1) continue;
            std::vector<float> sorted(times);
            std::sort(sorted.begin(), sorted.end());
            double gap = 1.0 - sorted.back() + sorted.front();
            for (size_t i = 1; i < sorted.size(); ++i) gap = std::fmax(gap, sorted[i] - sorted[i - 1]);
            EXPECT_LE(gap, 4.0 / double(j + 1) + 2.0 / double(n)) << n << " passes, prefix " << j + 1;
        }
        for (uint64_t k = 0; k < n; ++k) EXPECT_EQ(hits[k], 1) << n << " passes, stratum " << k;
        // Another key jitters differently within the same strata.
        EXPECT_NE(stratified_shutter_time(99, 0, n), stratified_shutter_time(100, 0, n)) << n;
    }
}

TEST(MotionBlur, SurfacePointsAreWhereRaysFindThemAtTheirTime) {
    // Scene::surface_point (the surface sampler's points) of a moving box under a ShutterScope is the point a ray
    // traced at that time hits: the box's front face centre moves from x = −1 to x = 1.
    const PreparedScene prepared(moving_box(-1.f, 1.f, true), basic_params(4, 4, 1, 0));
    const Scene& scene = prepared.scene();
    ASSERT_TRUE(scene.object_moves(0));
    for (float t : {0.f, 0.25f, 1.f}) {
        const ShutterScope scope(t);
        const SurfaceSampler surfaces(scene);
        Vec3 lo(1e30f), hi(-1e30f);
        float pdf_sum = 0.f;
        for (int k = 0; k < 64; ++k) {
            const SurfaceSample s = surfaces.sample((k + 0.5f) / 64.f, Vec2{0.3f, 0.3f});
            if (s.hit.object != 0) continue;
            lo.x = std::min(lo.x, s.hit.p.x), hi.x = std::max(hi.x, s.hit.p.x);
            EXPECT_NEAR(surfaces.pdf(s.hit), s.pdf_area, 1e-6f * s.pdf_area);
            pdf_sum += s.pdf_area;
        }
        ASSERT_GT(pdf_sum, 0.f);
        // The box's points span its extent around its centre at time t (camera-world space: x is unchanged by the
        // scene's offset, which only translates).
        const float x = -1.f + 2.f * t;
        EXPECT_GT(hi.x - lo.x, 0.5f) << t;
        EXPECT_LE(hi.x - x, 0.5f + 1e-4f) << t;
        EXPECT_GE(lo.x - x, -0.5f - 1e-4f) << t;
    }
}

/// The camera turning 10° about its vertical axis over the shutter (a pan) in front of a still box.
SceneArrays panning_camera(float t0, float t1) {
    SceneArrays a = moving_box(0.f, 0.f, false);
    const MotionTransform pan({rotation_y(0.f), rotation_y(0.17453293f)});
    const std::vector<float> start = rows_of(pan.at(t0)), end = rows_of(pan.at(t1));
    a.set("camera_to_world", ElemType::F32, {4, 4}, start.data());
    if (t0 != t1) {
        std::vector<float> motion(start);
        motion.insert(motion.end(), end.begin(), end.end());
        a.set("camera_motion", ElemType::F32, {2, 4, 4}, motion.data());
    }
    return a;
}

TEST(MotionBlur, CameraPanIsTheTimeAverageOfStillCameras) {
    // 10° of a 39.6° field over 32 px: the image slides ~8 px (9 taken for the bound: perspective stretches it).
    const int n = 16, b = 4;
    for (const char* name : {"PATH", "BDPT"}) {
        const RenderResult moving = render(panning_camera(0.f, 1.f), motion_params(name, 512));
        const Blocks still =
            still_average(n, b, [&](float t) { return render(panning_camera(t, t), motion_params(name, 64)); });
        expect_blocks_agree(blocks_of(moving, b), still, midpoint_bound(9.0, n, b), name);
    }
}

TEST(MotionBlur, ShadingUsesTheTransformAtTheRaysTime) {
    // A box turning a quarter turn about y: a ray down −z at time t meets its front face turned by t·90°, and the
    // hit's normal is that face's normal then (Embree's motion and the shading transform agree).
    MeshBuilder b;
    const uint32_t grey = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_box(Vec3(0.5f), grey), rows_of(translation(Vec3(0.f, 0.f, -5.f))).data());
    b.world_color = {1.f, 1.f, 1.f};
    SceneArrays a = b.arrays();
    std::vector<float> motion = rows_of(rotation_y(0.f, Vec3(0.f, 0.f, -5.f)));
    const std::vector<float> end = rows_of(rotation_y(1.5707963f, Vec3(0.f, 0.f, -5.f)));
    motion.insert(motion.end(), end.begin(), end.end());
    a.set("instance_motion", ElemType::F32, {1, 2, 4, 4}, motion.data());
    a.validate();
    const Scene scene(a, basic_params(8, 8, 1, 0), nullptr);
    ASSERT_TRUE(scene.has_motion());
    for (float t : {0.1f, 0.3f}) {  // the +z face faces the camera (within 45°)
        const ShutterScope scope(t);
        Ray ray;
        ray.o = Vec3(0.f, 0.f, 0.f);
        ray.d = Vec3(0.f, 0.f, -1.f);
        SurfaceHit hit;
        ASSERT_TRUE(scene.intersect(ray, &hit));
        const float angle = t * 1.5707963f;
        const Vec3 expected(std::sin(angle), 0.f, std::cos(angle));
        EXPECT_NEAR(dot(hit.ng, expected), 1.f, 1e-4f) << t;
        // The front face's distance: its centre is at 0.5 along the turned normal from the box's centre.
        EXPECT_NEAR(hit.t, 5.f - 0.5f / std::cos(angle), 1e-3f) << t;
    }
}

TEST(MotionBlur, BadMotionArraysAreNamed) {
    SceneArrays a = moving_box(-1.f, 1.f, false);
    const std::vector<float> one(16 * 3, 0.f);
    a.set("instance_motion", ElemType::F32, {3, 1, 4, 4}, one.data());
    try {
        a.validate();
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("instance_motion"), std::string::npos) << e.what();
    }
    SceneArrays c = moving_box(-1.f, 1.f, false);
    std::vector<float> nan(32, 0.f);
    nan[5] = std::nanf("");
    c.set("camera_motion", ElemType::F32, {2, 4, 4}, nan.data());
    EXPECT_THROW(c.validate(), InvalidScene);
}

TEST(MotionBlur, MovingEmittersStayStillAndSaySo) {
    // The box emits: its triangles are lights at fixed places, so it is not moved (in any integrator) and the
    // session's note says so, even for PATH.
    MeshBuilder b;
    const uint32_t glow = b.add_material(Color(0.f), Color(1.f));
    b.add_instance(b.add_box(Vec3(0.5f), glow), rows_of(translation(Vec3(-1.f, 0.f, -5.f))).data());
    SceneArrays a = b.arrays();
    std::vector<float> motion = rows_of(translation(Vec3(-1.f, 0.f, -5.f)));
    const std::vector<float> end = rows_of(translation(Vec3(1.f, 0.f, -5.f)));
    motion.insert(motion.end(), end.begin(), end.end());
    a.set("instance_motion", ElemType::F32, {1, 2, 4, 4}, motion.data());
    const PreparedScene scene(a, basic_params(4, 4, 1, 0));
    EXPECT_TRUE(scene.scene().has_still_moving_emitters());
    EXPECT_FALSE(scene.scene().has_motion());
    EXPECT_NE(unhonoured_features_note("PATH", ~0u, scene.scene()).find("moving emitting objects"), std::string::npos);
}

TEST(MotionBlur, EveryIntegratorRendersItAndOneThatDidNotWouldSaySo) {
    const PreparedScene scene(moving_box(-1.f, 1.f, true), basic_params(4, 4, 1, 0));
    // Every integrator of the registry renders motion blur (PHOTON and IRRADIANCE_CACHE by shutter passes with a
    // cache each): none gets the note.
    for (const IntegratorEntry& e : integrator_registry())
        EXPECT_TRUE(unhonoured_features_note(e.name, make_integrator(motion_params(e.name, 1))->honoured_features(),
                                             scene.scene())
                        .find("motion blur") == std::string::npos)
            << e.name;
    // One that did not would say so, and a still scene gets no note.
    EXPECT_NE(unhonoured_features_note("X", 0, scene.scene()).find("motion blur is not rendered"), std::string::npos);
    const PreparedScene still(moving_box(-1.f, 1.f, false), basic_params(4, 4, 1, 0));
    EXPECT_TRUE(unhonoured_features_note("X", 0, still.scene()).empty());
}

TEST(MotionBlur, AutoNotesWhatItsChoiceDoesNotRender) {
    // AUTO renders with the integrator it chose: a note (if any) is that integrator's, logged after the choice,
    // never one for AUTO itself; every choice renders motion blur, so no motion-blur note is logged.
    Params p = motion_params("AUTO", 2);
    Session s(moving_box(-1.f, 1.f, true), p);
    s.start();
    s.join();
    ASSERT_FALSE(s.error().has_value()) << *s.error();
    const std::vector<std::string> log = s.take_log();
    std::string chosen;
    for (const std::string& l : log)
        if (l.rfind("Auto: chose ", 0) == 0) chosen = l.substr(12, l.find(' ', 12) - 12);
    ASSERT_FALSE(chosen.empty());
    int notes = 0;
    for (const std::string& l : log) {
        EXPECT_NE(l.rfind("AUTO: ", 0), 0u) << l;
        if (l.find("motion blur is not rendered") != std::string::npos) {
            ++notes;
            EXPECT_EQ(l.rfind(chosen + ": ", 0), 0u) << l;
        }
    }
    EXPECT_EQ(notes, 0) << "AUTO chose " << chosen;  // every choice renders it
}

}  // namespace
}  // namespace candela::test
