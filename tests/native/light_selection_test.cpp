// light_selection strategies (ALL, UNIFORM, AREA, POWER, TREE, WARD): sampled pmf == evaluated pmf exactly,
// Σ pmf = 1, empirical frequencies (χ² over lights), Σ 1/(pmf·N) ≈ 1 with stratified u (pbrt-v4
// lightsamplers_test.cpp), the light BVH on 10,000 triangles, Ward's sorted bounds, k samples per vertex.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "chi2.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/math.h"
#include "core/rng.h"
#include "lights/light.h"
#include "lights/light_sampler.h"

namespace candela {
namespace {

TriangleLight tri_light(Vec3 a, Vec3 b, Vec3 c, float L) {
    TriangleLight t;
    t.p0 = a;
    t.p1 = b;
    t.p2 = c;
    const Vec3 n = cross(b - a, c - a);
    t.area = 0.5f * length(n);
    t.normal = normalize(n);
    t.radiance = Color(L);
    return t;
}

AreaLight rect_light(Vec3 center, Vec3 u, Vec3 v, Vec3 normal, float L) {
    AreaLight a;
    a.center = center;
    a.u = u;
    a.v = v;
    a.normal = normal;
    a.area = length(u) * length(v);
    a.radiance = Color(L);
    return a;
}

/// A mixed scene: point and spot lights, area lights both ways, triangles, a sun and the world.
LightSet mixed_lights() {
    LightSet set;
    Pcg32 rng(3, 5);
    auto rnd = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    for (int i = 0; i < 6; ++i) {
        PointLight p;
        p.position = Vec3(rnd(-5, 5), rnd(-5, 5), rnd(-5, 5));
        p.intensity = Color(rnd(0.1f, 10.f));
        if (i % 3 == 1) {
            p.spot.direction = normalize(Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)));
            p.spot.cos_half = std::cos(0.6f);
            p.spot.smooth = 0.1f;
            p.spot.cycles34_cosine = true;
        }
        if (i % 3 == 2) p.radius = 0.3f;
        set.add(p);
    }
    for (int i = 0; i < 5; ++i) {
        const Vec3 n = normalize(Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)));
        const Frame f(n);
        set.add(rect_light(Vec3(rnd(-5, 5), rnd(-5, 5), rnd(-5, 5)), f.s * rnd(0.2f, 2.f), f.t * rnd(0.2f, 2.f), n,
                           rnd(0.5f, 5.f)));
    }
    for (int i = 0; i < 12; ++i) {
        const Vec3 c(rnd(-5, 5), rnd(-5, 5), rnd(-5, 5));
        set.add(tri_light(c, c + Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)), c + Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)),
                          rnd(0.5f, 5.f)));
    }
    SunLight sun;
    sun.to_sun = normalize(Vec3(0.2f, 0.3f, 1.f));
    sun.irradiance = Color(3.f);
    sun.tan_half_angle = 0.02f;
    set.add(sun);
    WorldLight world;
    world.radiance = Color(0.2f);
    set.add(world);
    set.finalize(10.f);
    return set;
}

std::vector<LightSampleContext> shading_points() {
    std::vector<LightSampleContext> out;
    Pcg32 rng(71, 2);
    auto rnd = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    for (int i = 0; i < 6; ++i)
        out.push_back({Vec3(rnd(-6, 6), rnd(-6, 6), rnd(-6, 6)), normalize(Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)))});
    out.push_back({Vec3(12, -15, 9), Vec3(0, 0, 1)});    // far away
    out.push_back({Vec3(0.5f, 0.5f, 0.5f), Vec3(0.f)});  // in a medium: no normal
    return out;
}

const std::vector<std::string> k_strategies = {"ALL", "UNIFORM", "AREA", "POWER", "TREE", "WARD"};

TEST(LightSelection, RegistryKnowsEveryName) {
    const LightSet set = mixed_lights();
    EXPECT_EQ(light_selection_names(), k_strategies);
    for (const auto& name : k_strategies) {
        const LightSampler s = make_light_sampler(name, set);
        EXPECT_EQ(s.name(), name);
        EXPECT_EQ(s.size(), set.size());
    }
    EXPECT_THROW(make_light_sampler("BOGUS", set), InvalidScene);
}

TEST(LightSelection, SampledPmfEqualsEvaluatedPmfAndSumsToOne) {
    const LightSet set = mixed_lights();
    for (const auto& name : k_strategies) {
        const LightSampler s = make_light_sampler(name, set);
        for (const auto& ctx : shading_points()) {
            double sum = 0;
            for (uint32_t i = 0; i < set.size(); ++i) sum += s.pmf(ctx, i);
            EXPECT_NEAR(sum, 1.0, 1e-5) << name;
            for (int k = 0; k < 2000; ++k) {
                const float u = (k + 0.5f) / 2000.f;
                float pmf;
                const uint32_t i = s.select(ctx, u, &pmf);
                ASSERT_GT(pmf, 0.f) << name;
                ASSERT_EQ(pmf, s.pmf(ctx, i)) << name << " light " << i;
            }
            float pmf;
            s.select(ctx, 0.f, &pmf);
            EXPECT_GT(pmf, 0.f);
            s.select(ctx, k_one_minus_epsilon, &pmf);
            EXPECT_GT(pmf, 0.f);
        }
    }
}

TEST(LightSelection, StratifiedInverseWeightsAverageToOne) {
    // pbrt-v4 BVHLightSampling.Point: per light Σ 1/(pmf·N) over N stratified u. Each strategy maps u to
    // lights by intervals of length pmf, so a light's count is within ±2 of pmf·N.
    const LightSet set = mixed_lights();
    const int n = 100000;
    for (const auto& name : k_strategies) {
        const LightSampler s = make_light_sampler(name, set);
        for (const auto& ctx : shading_points()) {
            std::vector<double> sum(set.size(), 0.0);
            Pcg32 rng(9, 9);
            for (int k = 0; k < n; ++k) {
                float pmf;
                const uint32_t i = s.select(ctx, (k + rng.next_float()) / n, &pmf);
                if (pmf > 0.f) sum[i] += 1.0 / (double(pmf) * n);
            }
            for (uint32_t i = 0; i < set.size(); ++i) {
                const double p = s.pmf(ctx, i);
                if (p == 0.0) {
                    EXPECT_EQ(sum[i], 0.0);
                    continue;
                }
                EXPECT_NEAR(sum[i], 1.0, 2.0 / (p * n) + 1e-4) << name << " light " << i << " pmf " << p;
            }
        }
    }
}

TEST(LightSelection, EmpiricalFrequenciesMatchPmf) {
    const LightSet set = mixed_lights();
    const int n = 1000000;
    const auto points = shading_points();
    const double alpha = test::sidak_alpha(0.01, int(k_strategies.size() * 3));
    for (const auto& name : k_strategies) {
        const LightSampler s = make_light_sampler(name, set);
        for (size_t c = 0; c < 3; ++c) {
            const auto& ctx = points[c];
            std::vector<double> count(set.size(), 0.0);
            Pcg32 rng(100 + c, 1);
            for (int k = 0; k < n; ++k) {
                float pmf;
                const uint32_t i = s.select(ctx, rng.next_float(), &pmf);
                count[i] += 1;
            }
            // χ² over lights, pooling those expected below 5 counts.
            double stat = 0, pooled_obs = 0, pooled_exp = 0;
            int dof = -1;
            for (uint32_t i = 0; i < set.size(); ++i) {
                const double e = s.pmf(ctx, i) * n;
                if (e == 0.0) {
                    EXPECT_EQ(count[i], 0.0) << name;
                    continue;
                }
                if (e < 5) {
                    pooled_obs += count[i];
                    pooled_exp += e;
                    continue;
                }
                stat += (count[i] - e) * (count[i] - e) / e;
                ++dof;
            }
            if (pooled_exp > 0) {
                stat += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
                ++dof;
            }
            const double p = test::chi2_survival(stat, std::max(dof, 1));
            std::printf("%-8s point %zu: chi2 %.1f dof %d p %.3f\n", name.c_str(), c, stat, dof, p);
            EXPECT_GT(p, alpha) << name;
        }
    }
}

TEST(LightSelection, AllEstimatesEveryLightOnce) {
    const LightSet set = mixed_lights();
    const LightSampler s = make_light_sampler("ALL", set);
    EXPECT_TRUE(s.exhaustive());
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    for (uint32_t i = 0; i < set.size(); ++i) EXPECT_EQ(s.nee_pmf(ctx, i), 1.f);
    const LightSampler p = make_light_sampler("POWER", set);
    EXPECT_FALSE(p.exhaustive());
    for (uint32_t i = 0; i < set.size(); ++i) {
        EXPECT_EQ(p.nee_pmf(ctx, i), p.pmf(ctx, i));
        EXPECT_FLOAT_EQ(p.pmf(ctx, i), set.selection_pmf(i));  // POWER is the LightSet's distribution
    }
}

TEST(LightSelection, AreaUsesAreaAndAStandInForPointLights) {
    LightSet set;
    set.add(tri_light(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1.f));                       // A = 0.5
    set.add(rect_light(Vec3(0, 0, 3), Vec3(2, 0, 0), Vec3(0, 0.75f, 0), Vec3(0, 0, -1), 1.f));  // A = 1.5
    PointLight p;
    p.position = Vec3(1, 1, 1);
    p.intensity = Color(100.f);
    set.add(p);  // stand-in: mean area 1
    set.finalize(5.f);
    const LightSampler s = make_light_sampler("AREA", set);
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    EXPECT_FLOAT_EQ(s.pmf(ctx, 0), 0.5f / 3.f);
    EXPECT_FLOAT_EQ(s.pmf(ctx, 1), 1.5f / 3.f);
    EXPECT_FLOAT_EQ(s.pmf(ctx, 2), 1.f / 3.f);
}

// ---- TREE ---------------------------------------------------------------------------------------------

TEST(LightSelectionTree, TenThousandTrianglesGiveAValidPointDependentPmf) {
    LightSet set;
    Pcg32 rng(1234, 7);
    auto rnd = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    for (int i = 0; i < 10000; ++i) {
        const Vec3 c(rnd(-50, 50), rnd(-50, 50), rnd(-50, 50));
        const float s = rnd(0.05f, 0.5f);
        set.add(tri_light(c, c + Vec3(rnd(-s, s), rnd(-s, s), rnd(-s, s)), c + Vec3(rnd(-s, s), rnd(-s, s), rnd(-s, s)),
                          rnd(0.5f, 2.f)));
    }
    set.finalize(100.f);
    const LightSampler tree = make_light_sampler("TREE", set);
    const LightSampler power = make_light_sampler("POWER", set);
    ASSERT_NE(tree.tree(), nullptr);
    std::printf("tree: %zu nodes, depth %d\n", tree.tree()->nodes().size(), tree.tree()->depth());
    EXPECT_LE(tree.tree()->depth(), 64);
    for (int q = 0; q < 5; ++q) {
        const LightSampleContext ctx{Vec3(rnd(-40, 40), rnd(-40, 40), rnd(-40, 40)),
                                     normalize(Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)))};
        double sum = 0, near_tree = 0, near_power = 0;
        int zero = 0;
        for (uint32_t i = 0; i < set.size(); ++i) {
            const double p = tree.pmf(ctx, i);
            ASSERT_TRUE(std::isfinite(p) && p >= 0.0);
            sum += p;
            zero += p == 0.0;
            const auto& t = std::get<TriangleLight>(set[i]);
            if (length(t.p0 - ctx.p) < 10.f) {
                near_tree += p;
                near_power += power.pmf(ctx, i);
            }
        }
        EXPECT_NEAR(sum, 1.0, 1e-4);
        EXPECT_EQ(zero, 0);  // two-sided triangles and |cos| at the receiver: every light can contribute
        // Lights within 10 units hold ~0.4% of the power; the tree gives them far more.
        std::printf("tree query %d: mass of lights within 10: tree %.3f vs power %.4f\n", q, near_tree, near_power);
        EXPECT_GT(near_tree, 10 * near_power);
        for (int k = 0; k < 2000; ++k) {
            float pmf;
            const uint32_t i = tree.select(ctx, rng.next_float(), &pmf);
            ASSERT_GT(pmf, 0.f);
            ASSERT_EQ(pmf, tree.pmf(ctx, i));
        }
    }
}

TEST(LightSelectionTree, FavoursFacingLightsAndSkipsBackFacingOnes) {
    // 50 one-sided quads facing the shading point and 50 behind it facing away; then facing vs edge-on
    // triangles at the same distance.
    LightSet set;
    Pcg32 rng(8, 8);
    auto rnd = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    for (int i = 0; i < 100; ++i) {
        const bool facing = i % 2 == 0;
        const Vec3 c(rnd(-3, 3), rnd(-3, 3), facing ? rnd(4, 6) : rnd(-6, -4));
        set.add(rect_light(c, Vec3(0.3f, 0, 0), Vec3(0, 0.3f, 0), Vec3(0, 0, facing ? -1.f : -1.f), 1.f));
    }
    set.finalize(20.f);
    const LightSampler tree = make_light_sampler("TREE", set);
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    double facing = 0, away = 0;
    for (uint32_t i = 0; i < set.size(); ++i) (i % 2 == 0 ? facing : away) += tree.pmf(ctx, i);
    EXPECT_NEAR(facing, 1.0, 1e-5);
    EXPECT_EQ(away, 0.0);  // lights below z = 0 face −z, away from the point: they cannot contribute

    // Twenty triangles: neighbours 2.5 apart, so no node of a facing and an edge-on triangle is small enough as seen
    // from the centre to be a cluster (where the tree picks ∝ flux: ClustersPickByFlux below).
    LightSet tris;
    for (int i = 0; i < 20; ++i) {
        const float a = 2 * k_pi * i / 20.f;
        const Vec3 c = Vec3(std::cos(a), std::sin(a), 0.f) * 8.f;  // a ring around the point
        const Vec3 radial = normalize(c), up(0, 0, 1), tangent = cross(up, radial);
        if (i % 2 == 0)  // facing the point: spanned by the tangent and up
            tris.add(tri_light(c, c + tangent * 0.5f, c + up * 0.5f, 1.f));
        else  // edge-on: spanned by the radial direction and up
            tris.add(tri_light(c, c + radial * 0.5f, c + up * 0.5f, 1.f));
    }
    tris.finalize(20.f);
    const LightSampler t2 = make_light_sampler("TREE", tris);
    const LightSampleContext c2{Vec3(0.f), Vec3(1, 0, 0)};
    double face = 0, edge = 0;
    for (uint32_t i = 0; i < tris.size(); ++i) (i % 2 == 0 ? face : edge) += t2.pmf(c2, i);
    std::printf("tree: facing triangles %.3f, edge-on %.3f\n", face, edge);
    EXPECT_GT(face, 2 * edge);
}

/// A UV sphere of two-sided emissive triangles (an emissive mesh), radius r at c, radiance L.
void add_tessellated_sphere(LightSet& set, Vec3 c, float r, float L, int segments, int rings) {
    auto at = [&](int i, int j) {
        const float phi = 2 * k_pi * float(i) / float(segments), theta = k_pi * float(j) / float(rings);
        return c + Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) * r;
    };
    for (int j = 0; j < rings; ++j)
        for (int i = 0; i < segments; ++i) {
            if (j > 0) set.add(tri_light(at(i, j), at(i, j + 1), at(i + 1, j), L));
            if (j + 1 < rings) set.add(tri_light(at(i + 1, j), at(i, j + 1), at(i + 1, j + 1), L));
        }
}

TEST(LightSelectionTree, ClustersPickByFluxWhereTheyAreSmallAsSeenFromThePoint) {
    // Two tessellated spheres (two-sided triangles of unequal areas: the poles' are small). Seen from afar each
    // sphere is a cluster: within it the tree's pmf is exactly ∝ flux (area × radiance), as POWER's. Seen from close
    // by, the descent goes on and favours the near triangles. Fails without clusters (the far pmf then weighs
    // |cos| and 1/d²) and with clusters that ignore the distance rule (the near pmf would be ∝ flux too).
    LightSet set;
    add_tessellated_sphere(set, Vec3(0.f), 1.f, 2.f, 24, 12);
    const auto first_sphere = uint32_t(set.size());
    add_tessellated_sphere(set, Vec3(30.f, 0.f, 0.f), 1.f, 5.f, 24, 12);
    set.finalize(40.f);
    const LightSampler tree = make_light_sampler("TREE", set);
    auto worst_deviation_from_flux = [&](const LightSampleContext& ctx) {
        double sum_pmf = 0, sum_flux = 0;
        for (uint32_t i = 0; i < first_sphere; ++i) {
            sum_pmf += tree.pmf(ctx, i);
            sum_flux += std::get<TriangleLight>(set[i]).area;
        }
        double worst = 0;
        for (uint32_t i = 0; i < first_sphere; ++i) {
            const double share = tree.pmf(ctx, i) / sum_pmf, flux = std::get<TriangleLight>(set[i]).area / sum_flux;
            worst = std::max(worst, std::fabs(share / flux - 1.0));
        }
        return worst;
    };
    const LightSampleContext far{Vec3(0.f, 12.f, 3.f), normalize(Vec3(0.f, -1.f, 0.f))};   // sphere within 4.6°
    const LightSampleContext near{Vec3(0.f, 2.5f, 0.f), normalize(Vec3(0.f, -1.f, 0.f))};  // within 24°
    const double far_dev = worst_deviation_from_flux(far), near_dev = worst_deviation_from_flux(near);
    std::printf("tree within a sphere: pmf/flux share deviates by %.2g seen from afar, %.2g from close by\n", far_dev,
                near_dev);
    EXPECT_LT(far_dev, 1e-4);
    EXPECT_GT(near_dev, 0.3);
    for (const LightSampleContext& ctx : {far, near}) {  // and still a valid pmf, sampled as evaluated
        double sum = 0;
        for (uint32_t i = 0; i < set.size(); ++i) sum += tree.pmf(ctx, i);
        EXPECT_NEAR(sum, 1.0, 1e-4);
        Pcg32 rng(5, 6);
        for (int k = 0; k < 4000; ++k) {
            float pmf;
            const uint32_t i = tree.select(ctx, rng.next_float(), &pmf);
            ASSERT_GT(pmf, 0.f);
            ASSERT_EQ(pmf, tree.pmf(ctx, i));
        }
    }
}

TEST(LightSelectionTree, InfiniteLightsGetAFixedShare) {
    const LightSet set = mixed_lights();
    const LightSampler s = make_light_sampler("TREE", set);
    const auto* tree = s.tree();
    ASSERT_EQ(tree->infinite_lights().size(), 2u);
    EXPECT_FLOAT_EQ(tree->infinite_share(), 2.f / 3.f);
    for (const auto& ctx : shading_points())
        for (uint32_t i : tree->infinite_lights()) EXPECT_FLOAT_EQ(s.pmf(ctx, i), 1.f / 3.f);
}

// ---- WARD ---------------------------------------------------------------------------------------------

/// Unoccluded irradiance (luminance, |cos|) of one light at ctx by light sampling.
double irradiance(const Light& l, const LightSampleContext& ctx, int n = 20000) {
    Pcg32 rng(5, 5);
    double s = 0;
    for (int i = 0; i < n; ++i) {
        const LightSample ls = light_sample_li(l, ctx, {rng.next_float(), rng.next_float()}, LightPdfMode::SolidAngle);
        if (ls.valid()) s += luminance(ls.Li) * (is_black(ctx.n) ? 1.f : std::fabs(dot(ls.wi, ctx.n))) / ls.pdf;
    }
    return s / n;
}

TEST(LightSelectionWard, CandidatesAreSortedUpperBoundsWithCorrectRemainder) {
    const LightSet set = mixed_lights();
    const LightSampler s = make_light_sampler("WARD", set);
    ASSERT_NE(s.ward(), nullptr);
    for (const auto& ctx : shading_points()) {
        const WardList list = s.ward()->candidates(ctx);
        ASSERT_GT(list.size(), 0u);
        for (size_t k = 1; k < list.size(); ++k) EXPECT_GE(list.candidates()[k - 1].bound, list.candidates()[k].bound);
        for (size_t k = 0; k <= list.size(); ++k) {
            double tail = 0;
            for (size_t j = k; j < list.size(); ++j) tail += list.candidates()[j].bound;
            EXPECT_NEAR(list.remainder(k), tail, 1e-9 * list.total());
        }
        // Every bound is an upper bound of the light's unoccluded irradiance; left-out lights contribute 0.
        std::vector<bool> listed(set.size(), false);
        for (const auto& c : list.candidates()) {
            listed[c.light] = true;
            const double e = irradiance(set[c.light], ctx);
            EXPECT_LE(e, c.bound * 1.02 + 1e-6) << "light " << c.light;
            EXPECT_FLOAT_EQ(s.pmf(ctx, c.light), float(c.bound / list.total()));
        }
        for (uint32_t i = 0; i < set.size(); ++i)
            if (!listed[i]) EXPECT_EQ(irradiance(set[i], ctx, 2000), 0.0) << "light " << i;
        // Ward's rule and the unbiased tail draw.
        EXPECT_TRUE(list.should_stop(list.size(), 0.0, 0.03));
        EXPECT_FALSE(list.should_stop(0, 0.0, 0.03));
        const size_t k0 = list.size() / 2;
        std::vector<double> freq(list.size(), 0.0);
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            float pmf;
            const size_t j = list.select_tail(k0, (i + 0.5f) / n, &pmf);
            ASSERT_GE(j, k0);
            ASSERT_LT(j, list.size());
            ASSERT_FLOAT_EQ(pmf, float(list.candidates()[j].bound / list.remainder(k0)));
            freq[j] += 1.0 / n;
        }
        for (size_t j = k0; j < list.size(); ++j)
            EXPECT_NEAR(freq[j], list.candidates()[j].bound / list.remainder(k0), 2.0 / n);
    }
}

// ---- light_samples: k samples per vertex -----------------------------------------------------------------

TEST(LightSelection, StratifiedKSamplesAreUnbiased) {
    for (uint32_t k : {1u, 2u, 4u, 7u}) {
        for (uint32_t j = 0; j < k; ++j) {
            const float u0 = light_select_u(0.f, j, k), u1 = light_select_u(k_one_minus_epsilon, j, k);
            EXPECT_GE(u0, float(j) / k);
            EXPECT_LT(u1, 1.f);
            EXPECT_LE(u1, float(j + 1) / k);
            const Vec2 v = light_sample_u({0.9f, 0.95f}, j, k);
            EXPECT_TRUE(v.x >= 0.f && v.x < 1.f && v.y >= 0.f && v.y < 1.f);
        }
    }
    // Two triangles (Lambert oracle: 0.302300 each by symmetry) plus a rectangle (1.740840): k = 4 samples per
    // vertex with TREE and POWER, unbiased to 5σ.
    LightSet set;
    set.add(tri_light(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), 1.f));
    set.add(tri_light(Vec3(0, 0, 1), Vec3(0, -1, 1), Vec3(-1, 0, 1), 2.f));
    set.add(rect_light(Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, -1), 0.5f));
    set.finalize(5.f);
    const double exact = 0.302300 + 2 * 0.302300 + 0.5 * 1.740840;
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    for (const std::string name : {"TREE", "POWER", "UNIFORM", "WARD"}) {
        const LightSampler s = make_light_sampler(name, set);
        const uint32_t k = 4;
        Pcg32 rng(2, 2);
        const int n = 100000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            const float u = rng.next_float();
            const Vec2 u2{rng.next_float(), rng.next_float()};
            double est = 0;
            for (uint32_t j = 0; j < k; ++j) {
                float pmf;
                const uint32_t li = s.select(ctx, light_select_u(u, j, k), &pmf);
                if (!(pmf > 0.f)) continue;
                const LightSample ls = set.sample_li(li, ctx, light_sample_u(u2, j, k));
                if (ls.valid()) est += luminance(ls.Li) * std::max(0.f, dot(ls.wi, ctx.n)) / (k * pmf * ls.pdf);
            }
            sum += est;
            sum2 += est * est;
        }
        const double m = sum / n, se = std::sqrt((sum2 / n - m * m) / n);
        std::printf("k=4 %-8s E = %.5f ± %.5f (exact %.5f)\n", name.c_str(), m, se, exact);
        EXPECT_NEAR(m, exact, 5 * se + 1e-6) << name;
    }
    // ALL: each light once (weight 1).
    double all = 0;
    Pcg32 rng(4, 4);
    const int n = 100000;
    for (int i = 0; i < n; ++i)
        for (uint32_t li = 0; li < set.size(); ++li) {
            const LightSample ls = set.sample_li(li, ctx, {rng.next_float(), rng.next_float()});
            if (ls.valid()) all += luminance(ls.Li) * std::max(0.f, dot(ls.wi, ctx.n)) / ls.pdf;
        }
    EXPECT_NEAR(all / n, exact, 3e-3);
}

}  // namespace
}  // namespace candela
