// BDPT's multiple-importance weights (integrators/bdpt/strategy.h): for sampled paths, the weights of all the
// strategies (s, t) that can produce the same path sum to 1 — delta lights, delta lobes and the orthographic
// pinhole camera included (the strategies through a delta vertex are not counted, and the weights of the others
// still sum to 1) — and the densities a subpath stores equal the ones recomputed from the path's vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/rng.h"
#include "integrators/bdpt/strategy.h"
#include "lights/light.h"
#include "sampling/sampler.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// An open room (floor, back and left walls) with a glass and a glossy sphere, a mirror and an emissive triangle, every kind of
/// light (point, soft point, rectangle, sun, soft sun, a constant world).
SceneArrays mis_scene(const float* camera_rows16 = nullptr) {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    const uint32_t rough = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(rough, "GLOSSY", {{"color_r", 0.8f}, {"color_g", 0.8f}, {"color_b", 0.8f}, {"roughness", 0.3f}});
    const uint32_t lamp = b.add_material(Color(0.f), Color(3.f));
    b.add_instance(b.add_quad_z(-2.f, 2.f, -1.5f, 1.5f, -3.f, wall));
    const std::vector<float> floor = {1, 0, 0, 0, 0, 0, 1, -1.4f, 0, -1, 0, -1.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-2.f, 2.f, -1.5f, 1.5f, 0.f, wall), floor.data());
    const std::vector<float> left = {0, 0, 1, -1.8f, 0, 1, 0, 0, -1, 0, 0, -1.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-1.5f, 1.5f, -1.5f, 1.5f, 0.f, wall), left.data());
    const std::vector<float> g = {1, 0, 0, 0.5f, 0, 1, 0, -0.9f, 0, 0, 1, -1.6f, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(0.4f, 16, 8, glass), g.data());
    const std::vector<float> r = {1, 0, 0, -0.6f, 0, 1, 0, -1.f, 0, 0, 1, -2.f, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(0.4f, 16, 8, rough), r.data());
    const uint32_t mirror = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(mirror, "GLOSSY", {{"color_r", 0.9f}, {"color_g", 0.9f}, {"color_b", 0.9f}, {"roughness", 0.f}});
    const std::vector<float> mm = {0.7f, 0, 0.7f, -1.3f, 0, 1, 0, 0.3f, -0.7f, 0, 0.7f, -2.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-0.4f, 0.4f, -0.4f, 0.4f, 0.f, mirror), mm.data());
    b.add_instance(b.add_triangle(Vec3(-0.3f, 1.45f, -1.5f), Vec3(0.3f, 1.45f, -1.5f), Vec3(0.f, 1.45f, -2.1f), lamp));
    b.add_point_light(Vec3(1.f, 0.8f, -1.f), Color(5.f));
    b.add_point_light(Vec3(-1.f, 0.8f, -1.f), Color(5.f), 0.1f);
    b.add_area_light(Vec3(0.8f, 1.45f, -2.5f), Vec3(0.6f, 0.f, 0.f), Vec3(0.f, 0.f, 0.4f), Vec3(0.f, -1.f, 0.f),
                     Color(8.f), false);
    for (float angle : {0.f, 0.2f}) {
        std::vector<float> sun(light_columns().size(), 0.f);
        for (int c = 0; c < 3; ++c) sun[c] = 2.f;
        const Vec3 d = normalize(Vec3(-0.6f + angle, -0.7f, -0.3f));
        sun[6] = d.x, sun[7] = d.y, sun[8] = d.z;
        sun[18] = angle;
        b.add_light(2, sun);
    }
    b.world_color = {0.2f, 0.2f, 0.25f};
    return b.arrays(camera_rows16);
}

/// Fills v (cleared) as vertex i of the full path x (light end first) for a subpath from `light_side`.
struct FullPath {
    const BdptContext& c;
    std::vector<const PathVertex*> x;  // x[0] the light end, x.back() the camera
};

/// Builds the subpaths of split s of path x: y = x[0 .. s), z = x[k .. s] reversed, with their densities computed
/// from the vertices as the subpaths' own sampling would have stored them.
void split(const FullPath& path, int s, std::vector<PathVertex>& y, std::vector<PathVertex>& z) {
    const Densities d(path.c);
    const int n = int(path.x.size()), t = n - s;
    auto copy = [&](PathVertex& out, const PathVertex& in, const Vec3& w) {
        out.clear();
        out.kind = in.kind;
        out.p = in.p;
        out.ng = in.ng;
        out.infinite = in.infinite;
        out.emitter = in.emitter;
        out.Le = in.Le;
        out.delta_light = in.delta_light;
        out.delta = in.delta;
        out.hit = in.hit;
        out.w = in.infinite ? in.w : w;
        if (in.kind == VertexKind::Surface)
            out.bsdf.emplace(path.c.scene, out.hit, out.w, path.c.scene.shade(out.hit, out.w));
    };
    auto dir = [&](int from, int to) { return normalize(path.x[size_t(to)]->p - path.x[size_t(from)]->p); };
    for (int i = 0; i < s; ++i) copy(y[size_t(i)], *path.x[size_t(i)], i > 0 ? dir(i, i - 1) : Vec3(0.f));
    for (int j = 0; j < t; ++j)
        copy(z[size_t(j)], *path.x[size_t(n - 1 - j)], j > 0 ? dir(n - 1 - j, n - j) : Vec3(0.f));
    // Light side: forward densities from the light; reverse from the camera side.
    for (int i = 0; i < s; ++i) {
        y[size_t(i)].pdf_fwd =
            i == 0 ? d.origin(y[0], *path.x[1])
                   : d.light_side(*path.x[size_t(i - 1)], i > 1 ? path.x[size_t(i - 2)] : nullptr, *path.x[size_t(i)]);
    }
    for (int j = 0; j < t; ++j) {
        const int i = n - 1 - j;
        z[size_t(j)].pdf_fwd = j == 0 ? path.x.back()->pdf_fwd
                                      : d.camera_side(*path.x[size_t(i + 1)],
                                                      i + 2 < n ? path.x[size_t(i + 2)] : nullptr, *path.x[size_t(i)]);
    }
    // Reverse densities of interior vertices (the connection's four are recomputed by the weight itself).
    for (int i = 0; i + 2 < s; ++i)
        y[size_t(i)].pdf_rev = d.camera_side(*path.x[size_t(i + 1)], path.x[size_t(i + 2)], *path.x[size_t(i)]);
    for (int j = 0; j + 2 < t; ++j) {
        const int i = n - 1 - j;
        z[size_t(j)].pdf_rev = d.light_side(*path.x[size_t(i - 1)], path.x[size_t(i - 2)], *path.x[size_t(i)]);
    }
}

TEST(BdptMis, TheWeightsOfAllStrategiesOfAPathSumToOne) {
    const SceneArrays arrays = mis_scene();
    Params p = basic_params(16, 12, 1, 4);
    BdptSettings settings;
    settings.max_bounces = 4;
    settings.rr_mode = RouletteMode::Off;
    for (const std::string camera : {"PERSP", "ORTHO"}) {
        Params q = p;
        q.set("camera_type", camera);
        const Scene scene(arrays, q, nullptr);
        const EmitterSet emitters(scene.lights(), scene.bounds());
        const BdptContext c{scene, emitters, settings};
        for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
            settings.heuristic = h;
            std::vector<PathVertex> z(size_t(c.max_camera())), y(size_t(c.max_light()));
            std::vector<VertexNumbers> zn(z.size()), yn(y.size());
            std::vector<AreaLightHit> area;
            std::vector<PathVertex> ys(y.size() + z.size()), zs(y.size() + z.size());
            int checked = 0;
            Sampler sampler = make_sampler("RANDOM", 5, 1);
            for (int k = 0; k < 3000; ++k) {
                std::visit([&](auto& s) { s.start_pixel_sample(uint32_t(k % 16), uint32_t(k / 16 % 12), uint32_t(k)); },
                           sampler);
                const Ray ray = scene.camera().generate_ray({float(k % 16) + 0.5f, float(k / 16 % 12) + 0.5f},
                                                            get_2d(sampler, Dim::Lens));
                PathStats stats;
                float alpha = 1.f;
                const int nz = camera_subpath(c, ray, sampler, z, zn, area, stats, &alpha, nullptr);
                const int ny = light_subpath(c, sampler, y, yn, stats);
                // Every full path (s light, t camera vertices) joined at non-delta vertices.
                for (int s = 1; s <= ny; ++s)
                    for (int t = 2; t <= nz; ++t) {
                        if (y[size_t(s - 1)].delta || z[size_t(t - 1)].delta ||
                            z[size_t(t - 1)].kind != VertexKind::Surface)
                            continue;
                        if (s >= 2 && y[size_t(s - 1)].kind != VertexKind::Surface) continue;
                        if (s + t - 2 > settings.max_bounces + 1) continue;
                        FullPath path{c, {}};
                        for (int i = 0; i < s; ++i) path.x.push_back(&y[size_t(i)]);
                        for (int j = t - 1; j >= 0; --j) path.x.push_back(&z[size_t(j)]);
                        const int n = int(path.x.size());
                        double sum = 0.0;
                        for (int s2 = 0; s2 < n; ++s2) {
                            const int t2 = n - s2;
                            // Skip the splits that join at a delta vertex or would hit an unhittable light.
                            const PathVertex& pt = *path.x[size_t(s2)];
                            if (t2 >= 2 && pt.delta) continue;
                            if (s2 >= 1 && path.x[size_t(s2 - 1)]->delta) continue;
                            if (s2 == 0 && (path.x[0]->delta_light || path.x[0]->kind != VertexKind::Light)) continue;
                            if (t2 == 1 && !scene.camera().connectable()) continue;
                            if (s2 == 1 && t2 == 1) continue;  // left to (0, 2) by the tracer
                            split(path, s2, ys, zs);
                            sum += strategy_weight(c, ys, s2, zs, t2, nullptr, nullptr);
                        }
                        ASSERT_NEAR(sum, 1.0, 1e-3)
                            << camera << " path of " << n << " vertices (" << s << ", " << t << ")";
                        ++checked;
                    }
            }
            EXPECT_GT(checked, 500) << camera;
        }
    }
}

// A path of two vertices, an emitter point the camera sees, has the strategies (0, 2) and (1, 1) (strategy.h). Their
// weights sum to 1 where lens_strategy allows (1, 1) — the emissive triangle, for the perspective camera — and (0, 2)
// weighs 1 alone elsewhere (the orthographic pinhole cannot be connected to). (1, 1)'s weight must be substantial: light tracing makes W·H splats per pass, and its density at a
// point of the triangle is P(triangle)/A against the camera ray's ~N_e/(W·H·A) for a triangle covering N_e pixels.
TEST(BdptMis, TheTwoStrategiesOfAnEmitterSeenDirectlySumToOne) {
    // Looking up at the lamp triangle and the area light beside it, 64 × 48 pixels.
    const std::vector<float> up_view = look_at(Vec3(0.3f, -0.6f, 0.f), Vec3(0.5f, 1.45f, -2.3f), Vec3(0.f, 0.f, -1.f));
    const SceneArrays arrays = mis_scene(up_view.data());
    constexpr int W = 64, H = 48;
    Params p = basic_params(W, H, 1, 4);
    BdptSettings settings;
    settings.max_bounces = 4;
    settings.rr_mode = RouletteMode::Off;
    for (const std::string camera : {"PERSP", "ORTHO"}) {
        Params q = p;
        q.set("camera_type", camera);
        const Scene scene(arrays, q, nullptr);
        const EmitterSet emitters(scene.lights(), scene.bounds());
        const BdptContext c{scene, emitters, settings};
        for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
            settings.heuristic = h;
            std::vector<PathVertex> z(size_t(c.max_camera())), y(size_t(c.max_light()));
            std::vector<VertexNumbers> zn(z.size()), yn(y.size());
            std::vector<AreaLightHit> area;
            std::vector<PathVertex> ys(y.size() + z.size()), zs(y.size() + z.size());
            Sampler sampler = make_sampler("RANDOM", 7, 1);
            int alone_triangle = 0, alone_area = 0, both = 0;
            double lens_weight = 0.0;
            for (int k = 0; k < 20000; ++k) {
                std::visit([&](auto& s) { s.start_pixel_sample(uint32_t(k % W), uint32_t(k / W % H), uint32_t(k)); },
                           sampler);
                const Ray ray = scene.camera().generate_ray({float(k % W) + 0.5f, float(k / W % H) + 0.5f},
                                                            get_2d(sampler, Dim::Lens));
                PathStats stats;
                float alpha = 1.f;
                camera_subpath(c, ray, sampler, z, zn, area, stats, &alpha, nullptr);
                if (light_subpath(c, sampler, y, yn, stats) < 1) continue;
                const PathVertex& y0 = y[0];
                if (y0.delta_light || y0.infinite) continue;
                // A point with the lens strategy must be in view for both strategies to exist.
                CameraConnection conn;
                if (lens_strategy(c, y0) && !scene.camera().connect(y0.p, {0.5f, 0.5f}, &conn)) continue;
                FullPath path{c, {&y[0], &z[0]}};
                split(path, 0, ys, zs);
                double sum = strategy_weight(c, ys, 0, zs, 2, nullptr, nullptr);
                const bool triangle = std::holds_alternative<TriangleLight>(emitters[size_t(y0.emitter)]);
                if (lens_strategy(c, y0)) {
                    split(path, 1, ys, zs);
                    const float w11 = strategy_weight(c, ys, 1, zs, 1, nullptr, nullptr);
                    lens_weight += w11;
                    sum += w11;
                    ++both;
                } else {
                    ASSERT_EQ(sum, 1.0) << camera;
                    ++(triangle ? alone_triangle : alone_area);
                }
                ASSERT_NEAR(sum, 1.0, 1e-4) << camera << " emitter " << y0.emitter;
            }
            if (camera == "PERSP") {
                EXPECT_GT(both, 200) << "emissive-triangle points in view";
                EXPECT_EQ(alone_triangle, 0);
                // The suns take most of the emitted power, so P(triangle) is small and so is (1, 1)'s density.
                EXPECT_GT(lens_weight / std::max(both, 1), 0.2) << "the mean weight of (1, 1)";
            } else {
                EXPECT_EQ(both, 0);
                EXPECT_GT(alone_triangle + alone_area, 200);
            }
        }
    }
}

// The densities stored on a sampled subpath are those of the right vertices, sides and directions: each forward
// density is the one its subpath's sampling gives the vertex from its predecessor, each reverse density the other
// direction's from its successor (recomputed here from the vertices; the walk stores them from the positions too,
// so that the connections' recomputed ones match them and the weights sum to 1 exactly). The samplers' densities
// themselves are checked by χ² in vertex_bsdf_test.cpp and camera_importance_mc_test.cpp.
TEST(BdptMis, StoredDensitiesEqualTheRecomputedOnes) {
    const SceneArrays arrays = mis_scene();
    const Scene scene(arrays, basic_params(16, 12, 1, 4), nullptr);
    const EmitterSet emitters(scene.lights(), scene.bounds());
    BdptSettings settings;
    settings.max_bounces = 4;
    settings.rr_mode = RouletteMode::Off;
    const BdptContext c{scene, emitters, settings};
    const Densities d(c);
    std::vector<PathVertex> z(size_t(c.max_camera())), y(size_t(c.max_light()));
    std::vector<VertexNumbers> zn(z.size()), yn(y.size());
    std::vector<AreaLightHit> area;
    Sampler sampler = make_sampler("RANDOM", 9, 1);
    int checked = 0;
    for (int k = 0; k < 500; ++k) {
        std::visit([&](auto& s) { s.start_pixel_sample(0, 0, uint32_t(k)); }, sampler);
        const Ray ray = scene.camera().generate_ray({8.f, 6.f}, {0.5f, 0.5f});
        PathStats stats;
        float alpha = 1.f;
        const int nz = camera_subpath(c, ray, sampler, z, zn, area, stats, &alpha, nullptr);
        const int ny = light_subpath(c, sampler, y, yn, stats);
        for (int i = 1; i + 1 < nz; ++i) {
            if (z[size_t(i)].delta || z[size_t(i)].kind != VertexKind::Surface || z[size_t(i + 1)].infinite) continue;
            EXPECT_NEAR(z[size_t(i + 1)].pdf_fwd, d.camera_side(z[size_t(i)], &z[size_t(i - 1)], z[size_t(i + 1)]),
                        1e-2f * z[size_t(i + 1)].pdf_fwd);
            EXPECT_NEAR(z[size_t(i - 1)].pdf_rev, d.light_side(z[size_t(i)], &z[size_t(i + 1)], z[size_t(i - 1)]),
                        1e-2f * z[size_t(i - 1)].pdf_rev + 1e-9f);
            ++checked;
        }
        for (int i = 1; i + 1 < ny; ++i) {
            if (y[size_t(i)].delta || y[size_t(i)].kind != VertexKind::Surface) continue;
            EXPECT_NEAR(y[size_t(i + 1)].pdf_fwd, d.light_side(y[size_t(i)], &y[size_t(i - 1)], y[size_t(i + 1)]),
                        1e-2f * y[size_t(i + 1)].pdf_fwd);
            EXPECT_NEAR(y[size_t(i - 1)].pdf_rev, d.camera_side(y[size_t(i)], &y[size_t(i + 1)], y[size_t(i - 1)]),
                        1e-2f * y[size_t(i - 1)].pdf_rev + 1e-9f);
            ++checked;
        }
    }
    EXPECT_GT(checked, 200);
}

}  // namespace
}  // namespace candela::test
