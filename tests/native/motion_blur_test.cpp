// Motion blur (docs/light_paths.md, "Motion blur"): the transform interpolation, the scene's moving instances and
// camera, and the integrators that render it (PATH, LIGHT, BDPT, the path generators). The image of a moving scene is the time average
// of its still images over the shutter: a render with motion is compared, block by block, with the mean of still
// renders at evenly spaced times (the midpoint rule over the shutter), within statistical tolerances from both
// renders' noise estimates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "agreement.h"
#include "core/error.h"
#include "core/motion_transform.h"
#include "integrators/integrator.h"
#include "scene/scene.h"
#include "scene/shutter_time.h"
#include "scene/surface_sampler.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

std::vector<float> rows_of(const Affine& a) {
    std::vector<float> r(16, 0.f);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) r[4 * i + j] = a.m[i][j];
    r[15] = 1.f;
    return r;
}

Affine rotation_y(float angle, Vec3 t = Vec3(0.f)) {
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

/// A black box (half size 0.5; diffuse of `albedo` if given, and so is the emitting backdrop) 5 units in front of the camera against a white world,
/// moving from x0 to x1 over the shutter (a 2-step instance_motion), or still at x0 when x1 is not given.
SceneArrays moving_box(float x0, float x1, bool moves, bool emitter_backdrop = false, float albedo = 0.f) {
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

/// Per-block means (b×b blocks, RGB mean) and their standard errors from the per-pixel noise estimates.
struct Blocks {
    std::vector<double> mean, sigma;
};
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

/// Every block agrees within 4.5 σ of the difference (two-sided false alarm ≈ 7e-6 per block, under 1e-3 for
/// the 64 blocks), plus `quadrature`: midpoint_bound's error of the still average.
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

/// The midpoint rule's error over the shutter for an edge of full contrast (1: black on white) sweeping `shift_px`
/// pixels across b×b blocks, with n still times. With the 1-pixel box filter a block's value is linear in the
/// edge's position while the edge crosses it and constant otherwise: piecewise linear in time with slope at most
/// s = shift_px/b per shutter, kinks where an edge enters or leaves (at most 4: two edges). The midpoint rule is
/// exact on linear pieces; a kink of slope jump s in a part of width h = 1/n costs at most s·h²/8.
double midpoint_bound(double shift_px, int n, int b) { return 4.0 * (shift_px / b) / (8.0 * n * n); }

Params motion_params(const std::string& integrator, int samples, int threads = 2) {
    Params p = basic_params(32, 32, samples, 0);
    p.set("integrator", integrator);
    p.set("threads", int64_t(threads));
    p.set("sampler", std::string("RANDOM"));
    return p;
}

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

TEST(MotionBlur, LightAndBdptAgreeWithPathOnAMovingBox) {
    // An emitting wall behind the box, so light paths see what camera paths see; one shutter time per path (both
    // BDPT subpaths share it).
    const int b = 4;
    const Blocks path = blocks_of(render(moving_box(-1.f, 1.f, true, true), motion_params("PATH", 256)), b);
    ASSERT_GT(*std::max_element(path.mean.begin(), path.mean.end()), 0.9);  // the wall is seen
    for (const char* name : {"LIGHT", "BDPT"}) {
        const Blocks other = blocks_of(render(moving_box(-1.f, 1.f, true, true), motion_params(name, 256)), b);
        expect_blocks_agree(other, path, 0.0, name);
    }
}

TEST(MotionBlur, PathGeneratorsAgreeWithPathOnAMovingBox) {
    // A grey box before a grey emitting wall (light between them: the generators' indirect estimates are
    // exercised: surface points, light paths and gathered rays all at the sample's one shutter time), each generator and
    // their MIS combination against PATH, block by block (expect_blocks_agree's 4.5 σ).
    const int b = 4;
    // Two bounces (motion_params has none), so paths wall → box → wall (the indirect term I) exist.
    Params path_params = motion_params("PATH", 256);
    path_params.set("max_bounces", int64_t(2));
    const Blocks path = blocks_of(render(moving_box(-1.f, 1.f, true, true, 0.5f), path_params), b);
    for (const char* name : {"SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING"})
        for (bool mis : {false, true}) {
            Params p = motion_params(name, 256);
            p.set("max_bounces", int64_t(2));
            p.set("generators_mis", mis);
            const Blocks other = blocks_of(render(moving_box(-1.f, 1.f, true, true, 0.5f), p), b);
            expect_blocks_agree(other, path, 0.0, std::string(name) + (mis ? "_mis" : ""));
        }
}

TEST(MotionBlur, MltAndMmltAgreeWithPathOnAMovingBox) {
    // The shutter time is a coordinate of the chain's state. A Metropolis image's error is correlated across pixels,
    // so (as tests/native/mlt_test.cpp does) 8 independent runs per integrator are compared by their spread: mean
    // within 4.5 and 4×4 blocks within 6.5 standard errors (t with 14 dof: false alarms 5e-4 and 1.5e-5 per
    // comparison and block).
    const SceneArrays scene = moving_box(-1.f, 1.f, true, true, 0.5f);
    Params path = motion_params("PATH", 64);
    path.set("max_bounces", int64_t(2));
    for (const char* name : {"MLT", "MMLT"}) {
        Params p = motion_params(name, 256);
        p.set("max_bounces", int64_t(2));
        p.set("mlt_bootstrap", int64_t(4000));
        p.set("mlt_chains", int64_t(32));
        const Agreement g = compare_seed_sets(render_seeds(scene, p, 8), render_seeds(scene, path, 8), 4);
        std::printf("%s, moving box: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", name, g.mean_a, g.mean_b,
                    g.mean_z, g.worst_block_z, g.blocks);
        EXPECT_LT(std::fabs(g.mean_z), 4.5) << name;
        EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << name << ": block " << g.worst_block;
    }
}

TEST(MotionBlur, SppmAgreesWithPathOnAMovingBox) {
    // One shutter time per iteration (camera pass, photons and statistics share it): the average over iterations
    // is the time average. 8 independent runs (seeds) compared by their spread as for MLT above: SPPM's error is
    // correlated across iterations through the shrinking radii. The grey box's indirect light (photons) is small
    // beside the direct light, so its radius bias stays far below the tolerance.
    const SceneArrays scene = moving_box(-1.f, 1.f, true, true, 0.5f);
    Params path = motion_params("PATH", 64);
    path.set("max_bounces", int64_t(2));
    Params p = motion_params("SPPM", 32);
    p.set("max_bounces", int64_t(2));
    const Agreement g = compare_seed_sets(render_seeds(scene, p, 8), render_seeds(scene, path, 8), 4);
    std::printf("SPPM, moving box: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", g.mean_a, g.mean_b,
                g.mean_z, g.worst_block_z, g.blocks);
    EXPECT_LT(std::fabs(g.mean_z), 4.5);
    EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << "block " << g.worst_block;
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

TEST(MotionBlur, ImagesDoNotDependOnTheThreadCount) {
    for (const char* name : {"PATH", "LIGHT", "BDPT", "SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING",
                             "MLT", "MMLT", "SPPM"}) {
        // A grey box and wall with two bounces: every path generator's indirect estimate runs.
        Params p1 = motion_params(name, 8, 1), p2 = motion_params(name, 8, 2);
        p1.set("max_bounces", int64_t(2)), p2.set("max_bounces", int64_t(2));
        const RenderResult one = render(moving_box(-1.f, 1.f, true, true, 0.5f), p1);
        const RenderResult two = render(moving_box(-1.f, 1.f, true, true, 0.5f), p2);
        EXPECT_EQ(one.rgba, two.rgba) << name;
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

TEST(MotionBlur, IntegratorsThatDoNotRenderItSaySo) {
    const PreparedScene scene(moving_box(-1.f, 1.f, true), basic_params(4, 4, 1, 0));
    // PHOTON and IRRADIANCE_CACHE build one cache at one time (the shutter's middle): they say so.
    for (const char* name : {"PHOTON", "IRRADIANCE_CACHE"})
        EXPECT_NE(
            unhonoured_features_note(name, make_integrator(motion_params(name, 1))->honoured_features(), scene.scene())
                .find("motion blur is not rendered"),
            std::string::npos)
            << name;
    for (const char* name : {"SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING", "MLT", "MMLT", "SPPM"})
        EXPECT_TRUE(
            unhonoured_features_note(name, make_integrator(motion_params(name, 1))->honoured_features(), scene.scene())
                .find("motion blur") == std::string::npos)
            << name;
    EXPECT_TRUE(unhonoured_features_note("PATH", k_feature_motion_blur, scene.scene()).empty());
}

TEST(MotionBlur, AutoNotesWhatItsChoiceDoesNotRender) {
    // AUTO renders with the integrator it chose: the note (if any) is that integrator's, logged after the choice,
    // never one for AUTO itself; a choice that renders motion blur logs no motion-blur note.
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
    const bool blurs = chosen == "PATH" || chosen == "LIGHT" || chosen == "BDPT" || chosen == "SURFACE_SAMPLING" ||
                       chosen == "SOURCE_SHOOTING" || chosen == "RECEIVER_GATHERING" || chosen == "MLT" ||
                       chosen == "MMLT" || chosen == "SPPM";
    int notes = 0;
    for (const std::string& l : log) {
        EXPECT_NE(l.rfind("AUTO: ", 0), 0u) << l;
        if (l.find("motion blur is not rendered") != std::string::npos) {
            ++notes;
            EXPECT_EQ(l.rfind(chosen + ": ", 0), 0u) << l;
        }
    }
    EXPECT_EQ(notes, blurs ? 0 : 1) << "AUTO chose " << chosen;
}

}  // namespace
}  // namespace candela::test
