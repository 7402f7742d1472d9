// The viewport's native side: the mesh BVH cache (keys, reuse across scene builds, same hits), Scene::set_camera
// and ViewportSession (coarse to fine, the final level equal to a Session render of the same view, restarts,
// errors, stop at any time).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "core/error.h"
#include "scene/mesh_bvh_cache.h"
#include "scene/scene.h"
#include "session/viewport_session.h"
#include "test_helpers.h"

namespace candela {
namespace {

using test::MeshBuilder;

MeshBuilder two_objects() {
    MeshBuilder b;
    const uint32_t grey = b.add_material(Color(0.7f), Color(0.f));
    const uint32_t glow = b.add_material(Color(0.f), Color(4.f));
    b.add_instance(b.add_quad_z(-3.f, 3.f, -3.f, 3.f, -4.f, grey));
    b.add_instance(b.add_sphere(0.6f, 24, 12, grey));
    b.add_instance(b.add_quad_z(-0.4f, 0.4f, -0.4f, 0.4f, -1.5f, glow));
    b.world_color = {0.1f, 0.1f, 0.1f};
    return b;
}

/// Moves instance i by (dx, dy, dz).
void translate_instance(MeshBuilder& b, size_t i, float dx, float dy, float dz) {
    b.instance_transform[16 * i + 3] += dx;
    b.instance_transform[16 * i + 7] += dy;
    b.instance_transform[16 * i + 11] += dz;
}

TEST(MeshBvhCache, KeyDependsOnContentOnly) {
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5};
    const uint32_t tri_a[] = {0, 1, 2};
    const uint32_t tri_b[] = {3, 4, 5};
    const auto a = MeshBvhCache::key(pos, 3, tri_a, 1, 0, 0);
    EXPECT_EQ(a, MeshBvhCache::key(pos, 3, tri_a, 1, 0, 0));
    // The same triangle stored elsewhere in the shared arrays (indices relative to its first vertex).
    const float moved[] = {9, 9, 9, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t tri_moved[] = {1, 2, 3};
    EXPECT_EQ(a, MeshBvhCache::key(moved + 3, 3, tri_moved, 1, 1, 0));
    EXPECT_FALSE(a == MeshBvhCache::key(pos + 9, 3, tri_b, 1, 3, 0));  // other vertices
    EXPECT_FALSE(a == MeshBvhCache::key(pos, 3, tri_a, 1, 0, 1));      // other filter flags
}

TEST(MeshBvhCache, TransformEditsReuseEveryMeshBvhAndHitTheSame) {
    MeshBuilder b = two_objects();
    Params params = test::basic_params(32, 24, 1, 1);
    MeshBvhCache cache(2);
    { Scene first(b.arrays(), params, nullptr, &cache); }
    cache.end_build();
    EXPECT_EQ(cache.built(), 3u);
    translate_instance(b, 1, 0.5f, -0.2f, 0.3f);
    const SceneArrays arrays = b.arrays();
    const Scene cached(arrays, params, nullptr, &cache);
    cache.end_build();
    EXPECT_EQ(cache.built(), 3u) << "a transform-only edit built a mesh BVH";
    EXPECT_EQ(cache.reused(), 3u);
    EXPECT_EQ(cache.size(), 3u);
    // The instanced scene hits what the flattened one hits (same t to float rounding).
    const Scene flat(arrays, params, nullptr);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) {
            const Ray ray = flat.camera().generate_ray({x + 0.5f, y + 0.5f});
            SurfaceHit h1, h2;
            const bool f1 = flat.intersect(ray, &h1), f2 = cached.intersect(ray, &h2);
            ASSERT_EQ(f1, f2) << x << "," << y;
            if (f1) EXPECT_NEAR(h1.t, h2.t, 1e-4f * (1.f + h1.t));
        }
    // A mesh no longer in the scene leaves the cache after the next build.
    MeshBuilder one;
    one.add_material(Color(0.5f), Color(0.f));
    one.add_instance(one.add_quad_z(-3.f, 3.f, -3.f, 3.f, -4.f, 0));
    { Scene smaller(one.arrays(), params, nullptr, &cache); }
    cache.end_build();
    EXPECT_EQ(cache.size(), 1u);
}

TEST(SceneSetCamera, TheNewCameraSeesWhatABuiltSceneWithItSees) {
    const MeshBuilder b = two_objects();
    const std::vector<float> eye = test::look_at({1.f, 0.5f, 1.f}, {0.f, 0.f, -4.f}, {0.f, 1.f, 0.f});
    Params params = test::basic_params(16, 12, 1, 1);
    Scene moved(b.arrays(), params, nullptr);
    moved.set_camera(params, Affine::from_rows(eye.data()));
    const Scene built(b.arrays(eye.data()), params, nullptr);
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) {
            SurfaceHit h1, h2;
            const bool f1 = moved.intersect(moved.camera().generate_ray({x + 0.5f, y + 0.5f}), &h1);
            const bool f2 = built.intersect(built.camera().generate_ray({x + 0.5f, y + 0.5f}), &h2);
            ASSERT_EQ(f1, f2);
            if (f1) EXPECT_NEAR(h1.t, h2.t, 1e-4f * (1.f + h1.t));
        }
}

Params view_params(int w, int h) {
    Params v;
    v.set("width", int64_t(w));
    v.set("height", int64_t(h));
    v.set("pixel_size", int64_t(1));
    v.set("start_resolution", int64_t(8));
    return v;
}

/// Polls the session until it is done (or failed), recording every new image's pixel size.
ViewportStatus wait_done(ViewportSession& s, std::vector<int>* pixel_sizes = nullptr) {
    uint64_t seen = 0;
    for (int i = 0; i < 30000; ++i) {
        ViewportImage image;
        if (pixel_sizes && s.image(seen, &image)) {
            seen = image.version;
            if (pixel_sizes->empty() || pixel_sizes->back() != image.pixel_size)
                pixel_sizes->push_back(image.pixel_size);
        }
        const ViewportStatus st = s.status();
        if (st.phase == "done" || st.phase == "failed") return st;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ADD_FAILURE() << "the viewport session did not finish";
    return s.status();
}

TEST(ViewportSession, CoarseToFineThenTheSessionsImage) {
    const MeshBuilder b = two_objects();
    Params settings = test::basic_params(40, 30, 8, 3);
    ViewportSession vs(2);
    const uint64_t r1 = vs.update_scene(b.arrays(), settings);
    const uint64_t r2 = vs.set_view(view_params(40, 30), Affine());
    EXPECT_GT(r2, r1);
    std::vector<int> sizes;
    const ViewportStatus st = wait_done(vs, &sizes);
    ASSERT_FALSE(st.error) << *st.error;
    // 40x30 = 1200 pixels > 8² → levels 1/8 (5x4), 1/4, 1/2, then full: coarse to fine, never the other way.
    ASSERT_FALSE(sizes.empty());
    for (size_t i = 1; i < sizes.size(); ++i) EXPECT_LT(sizes[i], sizes[i - 1]);
    EXPECT_EQ(sizes.back(), 1);
    EXPECT_LE(sizes.front(), 8);
    ViewportImage image;
    ASSERT_TRUE(vs.image(0, &image));
    EXPECT_EQ(image.samples, 8);
    EXPECT_EQ(image.request, r2);
    EXPECT_EQ(vs.image_request(), r2);
    // The final level draws the samples a Session draws for that pixel and sample index: the same image, up to
    // the float rounding of instanced (viewport) against flattened (Session) meshes.
    const test::RenderResult ref = test::render(b.arrays(), settings);
    ASSERT_EQ(image.rgba.size(), ref.rgba.size());
    size_t close = 0;
    for (size_t i = 0; i < ref.rgba.size(); ++i)
        close += std::fabs(image.rgba[i] - ref.rgba[i]) <= 1e-4f + 1e-3f * std::fabs(ref.rgba[i]);
    EXPECT_GT(double(close) / ref.rgba.size(), 0.99);
}

TEST(ViewportSession, ViewChangesDoNotRebuildAndTransformsReuseBvhs) {
    MeshBuilder b = two_objects();
    Params settings = test::basic_params(24, 18, 2, 2);
    ViewportSession vs(2);
    vs.update_scene(b.arrays(), settings);
    vs.set_view(view_params(24, 18), Affine());
    ViewportStatus st = wait_done(vs);
    EXPECT_EQ(st.bvh_built, 3u);
    const std::vector<float> eye = test::look_at({0.5f, 0.f, 0.f}, {0.f, 0.f, -4.f}, {0.f, 1.f, 0.f});
    for (int i = 0; i < 5; ++i) {
        vs.set_view(view_params(24, 18), Affine::from_rows(eye.data()));
        vs.set_view(view_params(24, 18), Affine());
    }
    st = wait_done(vs);
    EXPECT_EQ(st.bvh_built + st.bvh_reused, 3u) << "a view change rebuilt the scene";
    translate_instance(b, 1, 0.3f, 0.f, 0.f);
    vs.update_scene(b.arrays(), settings);
    st = wait_done(vs);
    EXPECT_EQ(st.bvh_built, 3u);
    EXPECT_EQ(st.bvh_reused, 3u);
}

TEST(ViewportSession, ErrorsAreReportedAndClearedByTheNextScene) {
    MeshBuilder b = two_objects();
    Params settings = test::basic_params(16, 12, 1, 1);
    ViewportSession vs(1);
    EXPECT_THROW(vs.set_view(Params(), Affine()), InvalidParameter);  // no size: refused at once
    Params bad_view = view_params(16, 12);
    bad_view.set("pixel_size", int64_t(0));
    EXPECT_THROW(vs.set_view(bad_view, Affine()), InvalidParameter);
    MeshBuilder broken = b;
    broken.triangles[0] = 999;
    EXPECT_THROW(vs.update_scene(broken.arrays(), settings), InvalidScene);  // validated on the caller's thread
    MeshBuilder degenerate = b;
    for (int k = 0; k < 12; ++k) degenerate.instance_transform[16 + k] = 0.f;  // instance 1: zero scale
    vs.update_scene(degenerate.arrays(), settings);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the build may fail before the view arrives
    vs.set_view(view_params(16, 12), Affine());
    ViewportStatus st = wait_done(vs);
    ASSERT_TRUE(st.error);
    EXPECT_NE(st.error->find("instance 1"), std::string::npos) << *st.error;
    vs.set_view(view_params(16, 12), Affine());  // a view change does not hide a scene that cannot be built
    EXPECT_TRUE(vs.status().error);
    vs.update_scene(b.arrays(), settings);
    st = wait_done(vs);
    EXPECT_FALSE(st.error);
    EXPECT_EQ(st.phase, "done");
}

TEST(ViewportSession, RendersWithTheChosenIntegratorWhereItCanElsePathWithANote) {
    // The registry's viewport flags (integrators/integrator.h): LIGHT and BDPT render progressively, so the
    // viewport uses them; through a camera their t = 1 connections cannot reach (an orthographic pinhole for
    // LIGHT, a panorama for both) it renders with PATH and says so in the status note, without an error.
    const MeshBuilder b = two_objects();
    struct Case {
        const char* integrator;
        const char* camera_type;
        const char* note;  // "" : no fallback
    };
    const Case cases[] = {
        {"PATH", "PANO", ""},
        {"LIGHT", "PERSP", ""},
        {"BDPT", "ORTHO", ""},  // BDPT renders an orthographic pinhole without its t = 1 strategies
        {"LIGHT", "ORTHO", "Light Tracing cannot see through the orthographic camera without depth of field"},
        {"LIGHT", "PANO", "Light Tracing cannot see through the panoramic camera (Equirectangular)"},
        {"BDPT", "PANO", "Bidirectional cannot see through the panoramic camera (Equirectangular)"},
    };
    for (const Case& c : cases) {
        const std::string what = std::string(c.integrator) + " " + c.camera_type;
        Params settings = test::basic_params(16, 12, 2, 3);
        settings.set("integrator", std::string(c.integrator));
        ViewportSession vs(2);
        vs.update_scene(b.arrays(), settings);
        Params view = view_params(16, 12);
        view.set("camera_type", std::string(c.camera_type));
        if (std::string(c.camera_type) == "PANO") view.set("panorama_type", std::string("EQUIRECTANGULAR"));
        vs.set_view(view, Affine());
        const ViewportStatus st = wait_done(vs);
        ASSERT_FALSE(st.error) << what << ": " << *st.error;
        EXPECT_EQ(st.phase, "done") << what;
        if (*c.note) {
            EXPECT_NE(st.note.find(c.note), std::string::npos) << what << ": " << st.note;
            EXPECT_NE(st.note.find("the viewport shows Path Tracing"), std::string::npos) << what << ": " << st.note;
        } else {
            EXPECT_EQ(st.note, "") << what;
        }
        ViewportImage image;
        ASSERT_TRUE(vs.image(0, &image)) << what;
        double sum = 0.0;
        for (float v : image.rgba) sum += v;
        EXPECT_GT(sum, 0.0) << what << ": a black image";
    }
}

TEST(ViewportSession, StopsAtAnyMoment) {
    // A scene big enough that builds and renders take a while: stop during the build, during the render, and
    // let the destructor stop a running session. Each returns (the test would hang otherwise).
    MeshBuilder b;
    const uint32_t grey = b.add_material(Color(0.7f), Color(0.f));
    b.add_instance(b.add_sphere(1.f, 400, 200, grey));
    b.add_point_light({0.f, 2.f, 0.f}, Color(100.f));
    Params settings = test::basic_params(200, 150, 1 << 20, 8);
    for (int when : {0, 5, 50}) {
        ViewportSession vs(2);
        vs.update_scene(b.arrays(), settings);
        vs.set_view(view_params(200, 150), Affine());
        std::this_thread::sleep_for(std::chrono::milliseconds(when));
        vs.stop();
        EXPECT_EQ(vs.status().phase, "stopped");
        EXPECT_EQ(vs.set_view(view_params(200, 150), Affine()), 0u);  // ignored after stop
    }
    ViewportSession running(2);
    running.update_scene(b.arrays(), settings);
    running.set_view(view_params(200, 150), Affine());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
}  // ~ViewportSession stops it

}  // namespace
}  // namespace candela
