// Numerical hard cases: self-intersection at every scale, far-from-origin scenes, extreme emitters, albedo 1.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "sampling/warp.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

// From points on a lone triangle, rays leaving toward either side must never hit the triangle again
// (pbrt's Triangle.Reintersect): the origin offset scales with the coordinates.
TEST(SelfIntersection, NoSelfHitsFromTrianglesAtAnyScale) {
    Pcg32 rng(21, 22);
    for (float scale : {1e-4f, 1e-2f, 1.f, 1e2f, 1e4f}) {
        for (int tri = 0; tri < 20; ++tri) {
            MeshBuilder b;
            const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
            auto rnd = [&] { return (rng.next_float() * 2.f - 1.f) * scale; };
            const Vec3 offset(rnd() * 10.f, rnd() * 10.f, rnd() * 10.f);  // away from the origin too
            Vec3 v[3];
            for (Vec3& p : v) p = offset + Vec3(rnd(), rnd(), rnd());
            for (const Vec3& p : v) b.positions.insert(b.positions.end(), {p.x, p.y, p.z});
            b.triangles = {0, 1, 2};
            b.tri_material = {m};
            b.mesh_tri_start.push_back(1);
            b.add_instance(0);
            SceneArrays a = b.arrays();
            const Scene scene(a, basic_params(4, 4, 1, 1), nullptr);
            const Vec3 ng = normalize(cross(v[1] - v[0], v[2] - v[0]));
            if (!is_finite(ng)) continue;
            int self_hits = 0;
            for (int i = 0; i < 500; ++i) {
                const Vec2 bary = sample_uniform_triangle({rng.next_float(), rng.next_float()});
                // The hit point as an intersection would report it: camera-world space (camera at the origin).
                const Vec3 p = v[0] * bary.x + v[1] * bary.y + v[2] * (1.f - bary.x - bary.y);
                Vec3 d = sample_uniform_sphere({rng.next_float(), rng.next_float()});
                SurfaceHit hit;
                self_hits += scene.intersect({spawn_origin(p, ng, d), d, 0.f, 1e30f}, &hit);
            }
            EXPECT_EQ(self_hits, 0) << "scale " << scale << ", triangle " << tri;
        }
    }
}

SceneArrays room(float shift) {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f), Color(0.f));
    const uint32_t lamp = b.add_material(Color(0.f), Color(20.f));
    const float xf[16] = {1, 0, 0, shift, 0, 1, 0, shift, 0, 0, 1, shift, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(2.f, 48, 24, wall), xf);
    b.add_instance(b.add_quad_z(-0.3f, 0.3f, -0.3f, 0.3f, -1.5f, lamp), xf);
    const float cam[16] = {1, 0, 0, shift, 0, 1, 0, shift, 0, 0, 1, shift, 0, 0, 0, 1};
    return b.arrays(cam);
}

// The same room 1e5 units from the origin renders the same image (camera-world space keeps precision).
TEST(FarFromOrigin, RoomAt1e5RendersLikeAtTheOrigin) {
    const RenderResult a = render(room(0.f), basic_params(24, 18, 64, 6));
    const RenderResult b = render(room(1e5f), basic_params(24, 18, 64, 6));
    EXPECT_NEAR(a.mean_rgb, b.mean_rgb, 4.0 * std::hypot(a.standard_error, b.standard_error));
    // Per pixel: no speckle or leak (a leak would make pixels black or blow them up).
    size_t outliers = 0;
    for (size_t i = 0; i < a.rgba.size() / 4; ++i)
        outliers += std::fabs(a.rgba[4 * i] - b.rgba[4 * i]) > 5.f * std::hypot(a.noise[i], b.noise[i]) + 1e-3f;
    EXPECT_LE(outliers, a.rgba.size() / 4 / 100);
}

// Albedo 1 in a closed box never loses energy, so roulette never ends paths: max_bounces must.
TEST(Energy, ClosedWhiteBoxTerminates) {
    MeshBuilder b;
    b.add_instance(b.add_sphere(1.f, 32, 16, b.add_material(Color(1.f), Color(0.f))));
    b.add_point_light(Vec3(0.f), Color(1.f));
    const RenderResult r = render(b.arrays(), basic_params(8, 6, 2, 1024));
    for (float v : r.rgba) ASSERT_TRUE(std::isfinite(v));
    EXPECT_GT(r.mean_rgb, 0.0);
}

// A tiny, extremely bright emitter: huge but finite values, nothing dropped.
TEST(Energy, TinyMillionStrengthEmitterStaysFinite) {
    MeshBuilder b;
    b.add_instance(b.add_sphere(1.f, 32, 16, b.add_material(Color(0.8f), Color(0.f))));
    b.add_instance(b.add_quad_z(-1e-4f, 1e-4f, -1e-4f, 1e-4f, -0.5f, b.add_material(Color(0.f), Color(1e6f))));
    b.add_point_light(Vec3(0.f, 0.f, 0.9f), Color(1e6f), 1e-5f);
    Params p = basic_params(16, 12, 16, 8);
    Session s(b.arrays(), p);
    s.start();
    s.join();
    int channels;
    for (float v : s.get_pass("Combined", &channels)) ASSERT_TRUE(std::isfinite(v) && v >= 0.f);
    EXPECT_EQ(s.stats().nan_samples, 0u);
}

}  // namespace
}  // namespace candela::test
