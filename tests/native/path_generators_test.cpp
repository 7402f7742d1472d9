// The course's indirect path generators (integrators/generators/): SURFACE_SAMPLING, SOURCE_SHOOTING and
// RECEIVER_GATHERING, alone and combined by MIS (generators_mis).
//
// 1. Two facing plates under an area light (reference_scenes.h, docs/verification.md §2.11): the receiver has no
//    direct light, so with max_bounces 1 its image is exactly the one-bounce term each generator estimates in its own
//    way; each must equal the quadrature answer within 4 standard errors (from the spread of 12 seeds: t with 11
//    degrees of freedom, two-sided false alarm 1.6e-3 per comparison). PATH, LIGHT and BDPT are held to it too.
// 2. The MIS combination has the least variance: its per-pixel variance over the seeds, averaged over the image, is
//    at most that of the best single generator at the same sample count, up to 3 standard errors of the paired
//    per-pixel difference (one-sided false alarm 1.3e-3).
// 3. Every light type, glass and a mirror (the room of bdpt_test.cpp): each generator equals PATH within noise
//    (agreement.h: mean within 4, 4×4 blocks within 6, 12 seeds per side).
//    Surface sampling and source shooting join two surface points by the geometry term cos·cos/d², which is unbounded
//    where surfaces meet at a concave edge (the room's corners): their variance there is infinite, the sample mean
//    of a few hundred samples is skewed (low for surface sampling, with rare large excursions for source shooting)
//    and the t statistic is not t-distributed. In the rooms they are therefore tested with max_bounces 2 (fewer such
//    connections per path) and 8× the samples; their exact tests are the plates and the furnaces, where G is
//    bounded. (Measured on the point-light room with 5 bounces and 24 samples: surface sampling 1.7 % low at
//    z = −5.6; with 10× the samples 0.9 % low — the signature of a heavy tail, not of a bias.)
// Over this file's ~30 comparisons and ~500 blocks the family-wise false-alarm rate is about 4 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "agreement.h"
#include "core/math.h"
#include "reference_scenes.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 12;
const char* const k_generators[] = {"SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING"};

Params generator_params(Params p, const std::string& integrator, bool mis) {
    p.set("integrator", integrator);
    if (mis) p.set("generators_mis", true);
    return p;
}

TEST(PathGenerators, FacingPlatesQuadratureIsConverged) {
    // Lambert's formula is exact; the two outer quadratures are of smooth integrands: the answer must be stable.
    const double expected = facing_plates_expected(), finer = facing_plates_expected(12);
    std::printf("facing plates: L = %.7f (twice the quadrature order: %.7f)\n", expected, finer);
    EXPECT_NEAR(expected, finer, 1e-6 * finer);
    // Bounds by hand: E_P ≤ π·L_E·F-free bound (π·10 at most), cos⁴/h² kernel integrating to < π over P.
    EXPECT_GT(expected, 0.0);
    EXPECT_LT(expected, 0.5 / k_pi * 0.8 / k_pi * k_pi * 10.0 * k_pi);
}

TEST(PathGenerators, EachEqualsTheOneBounceAnswerBetweenFacingPlates) {
    const double expected = facing_plates_expected();
    const PreparedScene scene(facing_plates(), facing_plates_params(8, 8, 0));
    struct Run {
        std::string integrator;
        bool mis;
    };
    std::vector<Run> runs = {{"PATH", false}, {"LIGHT", false}, {"BDPT", false}};
    for (const char* g : k_generators) runs.push_back({g, false}), runs.push_back({g, true});
    for (const Run& r : runs) {
        std::vector<RenderResult> set;
        for (int seed = 1; seed <= k_seeds; ++seed) {
            Params p = generator_params(Params(), r.integrator, r.mis);
            p.set("seed", int64_t(seed));
            p.set("samples", int64_t(r.integrator == "LIGHT" ? 128 : 32));
            set.push_back(scene.render(p));
        }
        const SeedMean m = seed_mean(set);
        std::printf("%s%s: %.5f ± %.5f (exact %.5f)\n", r.integrator.c_str(), r.mis ? " + MIS" : "", m.mean,
                    m.standard_error, expected);
        EXPECT_GT(m.standard_error, 0.0) << r.integrator;
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error)
            << r.integrator << (r.mis ? " + MIS" : "") << ": σ " << m.standard_error;
    }
}

/// Per-pixel variance of the luminance over a seed set.
std::vector<double> pixel_variances(const std::vector<RenderResult>& set) {
    const size_t n = set[0].rgba.size() / 4;
    std::vector<double> out(n);
    for (size_t i = 0; i < n; ++i) {
        double s = 0.0, s2 = 0.0;
        for (const RenderResult& r : set) {
            const double v = (r.rgba[4 * i] + r.rgba[4 * i + 1] + r.rgba[4 * i + 2]) / 3.0;
            s += v, s2 += v * v;
        }
        const double m = s / double(set.size());
        out[i] = (s2 - double(set.size()) * m * m) / double(set.size() - 1);
    }
    return out;
}

TEST(PathGenerators, TheMisCombinationHasTheLeastVariance) {
    const PreparedScene scene(facing_plates(), facing_plates_params(12, 12, 0));
    auto variances = [&](const std::string& integrator, bool mis) {
        std::vector<RenderResult> set;
        for (int seed = 1; seed <= k_seeds; ++seed) {
            Params p = generator_params(Params(), integrator, mis);
            p.set("seed", int64_t(seed));
            p.set("samples", int64_t(16));
            set.push_back(scene.render(p));
        }
        return pixel_variances(set);
    };
    std::vector<std::vector<double>> single;
    double best_mean = 1e300;
    size_t best = 0;
    for (const char* g : k_generators) {
        single.push_back(variances(g, false));
        double m = 0.0;
        for (double v : single.back()) m += v;
        m /= double(single.back().size());
        std::printf("%s: mean pixel variance %.4g\n", g, m);
        if (m < best_mean) best_mean = m, best = single.size() - 1;
    }
    for (const char* g : k_generators) {
        const std::vector<double> mis = variances(g, true);
        const size_t n = mis.size();
        double d = 0.0, d2 = 0.0, m = 0.0;
        for (size_t i = 0; i < n; ++i) {
            const double di = mis[i] - single[best][i];
            d += di, d2 += di * di, m += mis[i];
        }
        const double mean_d = d / double(n),
                     sd = std::sqrt(std::max(0.0, (d2 - double(n) * mean_d * mean_d) / (n - 1.0)));
        std::printf("%s + MIS: mean pixel variance %.4g (%.2f× the best single, %s)\n", g, m / double(n),
                    m / double(n) / best_mean, k_generators[best]);
        EXPECT_LE(mean_d, 3.0 * sd / std::sqrt(double(n))) << g << " + MIS against " << k_generators[best];
    }
}

Params room_params(int w, int h) {
    Params p = basic_params(w, h, 0, 5);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("rr_start_bounce", int64_t(2));
    return p;
}

void expect_room_agrees(const SceneArrays& arrays, const std::string& what) {
    std::vector<RenderResult> reference[2];  // PATH with 5 and with 2 bounces
    for (int k = 0; k < 2; ++k) {
        Params path = room_params(24, 18);
        path.set("integrator", std::string("PATH"));
        path.set("samples", int64_t(48));
        path.set("max_bounces", int64_t(k == 0 ? 5 : 2));
        reference[k] = render_seeds(arrays, path, k_seeds);
    }
    for (const char* g : k_generators)
        for (bool mis : {false, true}) {
            const bool unbounded_g = std::string(g) != "RECEIVER_GATHERING";
            Params p = generator_params(room_params(24, 18), g, mis);
            p.set("samples", int64_t((mis ? 12 : 24) * (unbounded_g ? 8 : 1)));
            if (unbounded_g) p.set("max_bounces", int64_t(2));
            const Agreement a = compare_seed_sets(render_seeds(arrays, p, k_seeds), reference[unbounded_g], 4);
            const std::string name = what + ", " + g + (mis ? " + MIS" : "");
            EXPECT_GT(a.mean_b, 0.0) << name;
            EXPECT_LT(std::fabs(a.mean_z), 4.0) << name << ": mean " << a.mean_a << ", PATH " << a.mean_b;
            EXPECT_LT(std::fabs(a.worst_block_z), 6.0) << name << ": block " << a.worst_block << " of " << a.blocks;
        }
}

TEST(PathGenerators, EqualPathTracingWithPointSpotAndSunLights) {
    expect_room_agrees(lit_room(1 | 2 | 4 | 8 | 16 | 256, false), "point, soft point, spot, suns, world");
}

TEST(PathGenerators, EqualPathTracingWithAreaLightsGlassAndAMirror) {
    expect_room_agrees(lit_room(32 | 64 | 128 | 256, true), "area lights, a triangle, glass, a mirror");
}

TEST(PathGenerators, AnUnknownHeuristicIsRefusedByName) {
    Params p = generator_params(facing_plates_params(4, 4, 1), "SOURCE_SHOOTING", true);
    p.set("generators_heuristic", std::string("MAXIMUM"));
    try {
        render(facing_plates(), p);
        FAIL() << "an unknown heuristic rendered";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("generators_heuristic"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace candela::test
