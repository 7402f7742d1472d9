// Sampling points on all surfaces by area (scene/surface_sampler.h): the distribution over triangles (χ² against
// the claimed density times each triangle's world area, computed here from the input arrays), the density
// formula for instances (object-space areas within an instance, any transform), uniformity where it is promised,
// pdf(hit) against the sample's pdf, the points on the surfaces (a ray along −ng finds the same hit), and shade().
// Statistics: one χ² test at p ≥ 1e-4 (its false-alarm rate); everything else is exact up to float rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi2.h"
#include "core/error.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "scene/surface_sampler.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// Row-major object → world: translate · rotate(axis, angle) · scale.
std::vector<float> trs(Vec3 t, Vec3 axis, float angle, Vec3 s) {
    const Vec3 a = normalize(axis);
    const float c = std::cos(angle), sn = std::sin(angle), k = 1.f - c;
    const float r[3][3] = {{c + a.x * a.x * k, a.x * a.y * k - a.z * sn, a.x * a.z * k + a.y * sn},
                           {a.y * a.x * k + a.z * sn, c + a.y * a.y * k, a.y * a.z * k - a.x * sn},
                           {a.z * a.x * k - a.y * sn, a.z * a.y * k + a.x * sn, c + a.z * a.z * k}};
    const float sc[3] = {s.x, s.y, s.z};
    std::vector<float> m(16, 0.f);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m[4 * i + j] = r[i][j] * sc[j];
        m[4 * i + 3] = (&t.x)[i];
    }
    m[15] = 1.f;
    return m;
}

struct TestScene {
    MeshBuilder b;
    std::vector<std::vector<float>> transforms;  // per instance
    uint32_t emissive_material = 0, hidden_instance = 0, degenerate_instance = 0;
    std::vector<bool> similarity;  // per instance: rotation, mirror, uniform scale
};

/// A flattened emissive quad, a box instanced three times (rotation with uniform scale, non-uniform scale, mirror),
/// a flattened sphere under a non-uniform scale, a triangle visible only to shadow rays and a zero-area triangle.
TestScene make_scene() {
    TestScene s;
    const uint32_t grey = s.b.add_material(Color(0.5f), Color(0.f));
    s.emissive_material = s.b.add_material(Color(0.2f), Color(3.f));
    const uint32_t quad = s.b.add_quad_z(-1.f, 1.f, -0.5f, 0.5f, 0.f, s.emissive_material);
    const uint32_t box = s.b.add_box({0.5f, 0.3f, 0.2f}, grey);
    const uint32_t sphere = s.b.add_sphere(0.7f, 16, 8, grey);
    const uint32_t hidden = s.b.add_triangle({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, grey);
    const uint32_t flat = s.b.add_triangle({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {2.f, 0.f, 0.f}, grey);
    auto add = [&](uint32_t mesh, std::vector<float> xf, bool sim) {
        s.b.add_instance(mesh, xf.data());
        s.transforms.push_back(std::move(xf));
        s.similarity.push_back(sim);
        return uint32_t(s.transforms.size() - 1);
    };
    add(quad, trs({0.f, 0.f, -6.f}, {1.f, 0.f, 0.f}, 0.3f, {1.f, 1.f, 1.f}), true);
    add(box, trs({-3.f, 1.f, -5.f}, {0.3f, 1.f, 0.2f}, 0.7f, {1.5f, 1.5f, 1.5f}), true);
    add(box, trs({3.f, -1.f, -5.f}, {1.f, 0.2f, 0.4f}, 1.1f, {1.f, 2.5f, 0.4f}), false);
    add(box, trs({0.f, 3.f, -5.f}, {0.f, 0.f, 1.f}, 0.2f, {-1.f, 1.f, 1.f}), true);
    add(sphere, trs({0.f, -3.f, -5.f}, {0.f, 1.f, 0.f}, 0.5f, {2.f, 1.f, 1.f}), false);
    s.hidden_instance = add(hidden, trs({5.f, 5.f, -5.f}, {0.f, 0.f, 1.f}, 0.f, {1.f, 1.f, 1.f}), true);
    s.degenerate_instance = add(flat, trs({-5.f, -5.f, -5.f}, {0.f, 0.f, 1.f}, 0.f, {1.f, 1.f, 1.f}), true);
    return s;
}

SceneArrays scene_arrays(const TestScene& s) {
    SceneArrays a = s.b.arrays();
    std::vector<uint8_t> flags(s.transforms.size(), uint8_t(k_object_default));
    flags[s.hidden_instance] = uint8_t(k_ray_shadow);  // casts shadows, never seen nor scattering
    a.set("instance_flags", ElemType::U8, {flags.size()}, flags.data());
    return a;
}

/// World area of triangle t (of the mesh's own numbering) of instance i, from the input arrays in double.
double world_area(const TestScene& s, uint32_t instance, uint32_t t, bool object_space = false) {
    const uint32_t mesh = s.b.instance_mesh[instance];
    const uint32_t tri = s.b.mesh_tri_start[mesh] + t;
    const float* m = s.transforms[instance].data();
    double v[3][3];
    for (int k = 0; k < 3; ++k) {
        const float* p = &s.b.positions[3 * size_t(s.b.triangles[3 * tri + k])];
        for (int r = 0; r < 3; ++r)
            v[k][r] = object_space ? p[r]
                                   : m[4 * r] * double(p[0]) + m[4 * r + 1] * double(p[1]) +
                                         m[4 * r + 2] * double(p[2]) + m[4 * r + 3];
    }
    const double e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const double e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    return 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

uint32_t triangle_count(const TestScene& s, uint32_t instance) {
    const uint32_t mesh = s.b.instance_mesh[instance];
    return s.b.mesh_tri_start[mesh + 1] - s.b.mesh_tri_start[mesh];
}

TEST(SurfaceSampler, TrianglesAreDrawnWithTheClaimedDensity) {
    const TestScene ts = make_scene();
    const SceneArrays a = scene_arrays(ts);
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    const SurfaceSampler sampler(scene);
    ASSERT_EQ(scene.object_count(), ts.transforms.size());  // one top-level object per instance, in order

    // Cells: every triangle of every object; expected mass pdf·A_world (pdf is constant over a triangle).
    std::vector<uint32_t> first(ts.transforms.size() + 1, 0);
    for (uint32_t i = 0; i < ts.transforms.size(); ++i) first[i + 1] = first[i] + triangle_count(ts, i);
    std::vector<double> mass(first.back(), 0.0);
    double total_mass = 0.0;
    for (uint32_t i = 0; i < ts.transforms.size(); ++i)
        for (uint32_t t = 0; t < triangle_count(ts, i); ++t) {
            const double pdf = sampler.pdf(scene.surface_point(i, t, 0.25f, 0.35f));
            mass[first[i] + t] = pdf * world_area(ts, i, t);
            total_mass += mass[first[i] + t];
        }
    EXPECT_NEAR(total_mass, 1.0, 1e-5);  // the density integrates to 1 over all surfaces
    constexpr int n = 2000000;
    std::vector<double> observed(mass.size(), 0.0);
    Pcg32 rng(41, 1);
    for (int k = 0; k < n; ++k) {
        const float us = rng.next_float();
        const Vec2 u{rng.next_float(), rng.next_float()};
        const SurfaceSample s = sampler.sample(us, u);
        ASSERT_GT(s.pdf_area, 0.f);
        ASSERT_LT(s.hit.object, ts.transforms.size());
        ASSERT_NE(s.hit.object, ts.hidden_instance);
        ASSERT_NE(s.hit.object, ts.degenerate_instance);
        observed[first[s.hit.object] + s.hit.primitive.prim] += 1.0;
    }
    double stat = 0.0;
    int dof = -1;
    for (size_t c = 0; c < mass.size(); ++c) {
        const double e = mass[c] * n;
        if (e <= 0.0) {
            EXPECT_EQ(observed[c], 0.0) << "cell " << c;
            continue;
        }
        ASSERT_GT(e, 5.0) << "cell " << c;  // the scene is small enough that no pooling is needed
        stat += (observed[c] - e) * (observed[c] - e) / e;
        ++dof;
    }
    const double p = chi2_survival(stat, dof);
    EXPECT_GE(p, 1e-4) << "chi2 " << stat << " dof " << dof;
}

TEST(SurfaceSampler, DensityFollowsObjectSpaceAreasWithinAnInstanceAndIsUniformForSimilarities) {
    const TestScene ts = make_scene();
    const SceneArrays a = scene_arrays(ts);
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    const SurfaceSampler sampler(scene);
    double true_total = 0.0;
    for (uint32_t i = 0; i < ts.transforms.size(); ++i)
        if (i != ts.hidden_instance)
            for (uint32_t t = 0; t < triangle_count(ts, i); ++t) true_total += world_area(ts, i, t);
    for (uint32_t i = 0; i < ts.transforms.size(); ++i) {
        const bool instanced = scene.object_triangles(i).instanced;
        double obj_area = 0.0, p_object = 0.0, world_total = 0.0;
        for (uint32_t t = 0; t < triangle_count(ts, i); ++t) {
            obj_area += world_area(ts, i, t, instanced);
            world_total += world_area(ts, i, t);
            p_object += sampler.pdf(scene.surface_point(i, t, 0.3f, 0.3f)) * world_area(ts, i, t);
        }
        if (i == ts.hidden_instance || i == ts.degenerate_instance) {
            EXPECT_EQ(p_object, 0.0) << i;
            continue;
        }
        for (uint32_t t = 0; t < triangle_count(ts, i); ++t) {
            const double pdf = sampler.pdf(scene.surface_point(i, t, 0.3f, 0.3f));
            // P(object) · A_obj(t)/A_obj(mesh) / A_world(t), A_obj in the table's space (world if flattened).
            const double expected = p_object * world_area(ts, i, t, instanced) / obj_area / world_area(ts, i, t);
            EXPECT_NEAR(pdf, expected, 1e-5 * expected) << "object " << i << " triangle " << t;
            if (ts.similarity[i] || !instanced)  // uniform over the object: P(object)/A_world(object)
                EXPECT_NEAR(pdf, p_object / world_total, 1e-5 * pdf) << "object " << i << " triangle " << t;
        }
    }
    // The instance with a non-uniform scale is weighted by an upper bound of its area; everything else exactly.
    EXPECT_GE(sampler.total_area(), true_total * (1.0 - 1e-6));
    EXPECT_LE(sampler.total_area(), true_total * 1.2);
    // A scene of similarities only is sampled uniformly: pdf = 1/total area.
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const uint32_t box = b.add_box({0.5f, 0.3f, 0.2f}, m), quad = b.add_quad_z(0.f, 2.f, 0.f, 1.f, 0.f, m);
    const std::vector<float> x1 = trs({1.f, 0.f, -3.f}, {1.f, 1.f, 0.f}, 0.4f, {2.f, 2.f, 2.f});
    const std::vector<float> x2 = trs({-1.f, 0.f, -3.f}, {0.f, 1.f, 1.f}, 1.4f, {-0.5f, 0.5f, 0.5f});
    b.add_instance(box, x1.data());
    b.add_instance(box, x2.data());
    b.add_instance(quad);
    const SceneArrays a2 = b.arrays();
    const Scene uniform_scene(a2, basic_params(8, 8, 1, 1), nullptr);
    const SurfaceSampler uniform(uniform_scene);
    const double total = 2.0 * (0.6 * 0.4 + 1.0 * 0.4 + 1.0 * 0.6) * (4.0 + 0.25) + 2.0;
    EXPECT_NEAR(uniform.total_area(), total, 1e-5 * total);
    Pcg32 rng(2, 2);
    for (int k = 0; k < 1000; ++k) {
        const SurfaceSample s = uniform.sample(rng.next_float(), {rng.next_float(), rng.next_float()});
        EXPECT_NEAR(s.pdf_area * total, 1.0, 1e-5);
    }
}

TEST(SurfaceSampler, SampledPointsLieOnTheSurfacesAndShade) {
    const TestScene ts = make_scene();
    const SceneArrays a = scene_arrays(ts);
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    const SurfaceSampler sampler(scene);
    Pcg32 rng(9, 9);
    const Vec3 wi_local = normalize(Vec3(0.3f, -0.2f, 0.9f));
    for (int k = 0; k < 5000; ++k) {
        const Vec2 u{rng.next_float(), rng.next_float()};
        const SurfaceSample s = sampler.sample(rng.next_float(), u);
        EXPECT_EQ(sampler.pdf(s.hit), s.pdf_area);
        // A ray toward the point along −ng from just off the surface hits it: same triangle, position, normals.
        const float delta = 1e-3f * (1.f + length(s.hit.p));
        Ray ray;
        ray.o = s.hit.p + s.hit.ng * delta;
        ray.d = -s.hit.ng;
        ray.tmax = 2.f * delta;
        SurfaceHit hit;
        ASSERT_TRUE(scene.intersect(ray, &hit)) << "sample " << k;
        EXPECT_LT(length(hit.p - s.hit.p), 1e-5f * (1.f + length(s.hit.p)));
        EXPECT_EQ(hit.object, s.hit.object);
        const float b0 = 1.f - s.hit.b1 - s.hit.b2;
        if (std::min({b0, s.hit.b1, s.hit.b2}) > 1e-4f) {  // not on an edge shared with a neighbour
            EXPECT_EQ(hit.primitive, s.hit.primitive);
            EXPECT_NEAR(hit.b1, s.hit.b1, 1e-4f);
            EXPECT_NEAR(hit.b2, s.hit.b2, 1e-4f);
            EXPECT_EQ(hit.material, s.hit.material);
            EXPECT_EQ(hit.light, s.hit.light);
            EXPECT_GT(dot(hit.ng, s.hit.ng), 1.f - 1e-5f);
            EXPECT_GT(dot(hit.ns, s.hit.ns), 1.f - 1e-5f);
            // shade() sees the same material.
            const ShadingPoint a_sp = scene.shade(s.hit, s.hit.ng), b_sp = scene.shade(hit, s.hit.ng);
            EXPECT_EQ(a_sp.emission.x, b_sp.emission.x);
            EXPECT_EQ(a_sp.backfacing, b_sp.backfacing);
            const Color fa = a_sp.bsdf().f(wi_local, wi_local), fb = b_sp.bsdf().f(wi_local, wi_local);
            EXPECT_NEAR(fa.x, fb.x, 1e-6f);
            EXPECT_GT(fa.x, 0.f);
        }
        const ShadingPoint sp = scene.shade(s.hit, s.hit.ng);
        const bool emitter = s.hit.material == ts.emissive_material;
        EXPECT_EQ(sp.emission.x, emitter ? 3.f : 0.f);
        EXPECT_EQ(s.hit.light >= 0, emitter);
    }
}

TEST(SurfaceSampler, CancelsEmptyScenesAndMemory) {
    const TestScene ts = make_scene();
    const SceneArrays a = scene_arrays(ts);
    const Scene scene(a, basic_params(8, 8, 1, 1), nullptr);
    CancelToken cancel;
    cancel.cancel();
    EXPECT_THROW(SurfaceSampler(scene, &cancel), Cancelled);
    const SurfaceSampler sampler(scene);
    const size_t triangles = scene.stats().unique_triangles;
    EXPECT_GE(sampler.bytes(), 12 * triangles);
    EXPECT_LE(double(sampler.bytes()), SurfaceSampler::estimate_bytes(double(triangles), scene.object_count()));
    // Hidden and zero-area surfaces have no density.
    EXPECT_EQ(sampler.pdf(scene.surface_point(ts.hidden_instance, 0, 0.3f, 0.3f)), 0.f);
    EXPECT_EQ(sampler.pdf(scene.surface_point(ts.degenerate_instance, 0, 0.3f, 0.3f)), 0.f);
    // A scene whose only object is hidden from every ray that makes a path vertex has nothing to sample.
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_quad_z(-1.f, 1.f, -1.f, 1.f, -2.f, m));
    SceneArrays a2 = b.arrays();
    const uint8_t flags[1] = {uint8_t(k_ray_shadow)};
    a2.set("instance_flags", ElemType::U8, {1}, flags);
    const Scene shadow_only(a2, basic_params(8, 8, 1, 1), nullptr);
    const SurfaceSampler none(shadow_only);
    EXPECT_EQ(none.total_area(), 0.0);
    EXPECT_EQ(none.sample(0.5f, {0.5f, 0.5f}).pdf_area, 0.f);
}

}  // namespace
}  // namespace candela::test
