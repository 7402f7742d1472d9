// Where Russian roulette starts: the number of rays a path traces under SQRT_THROUGHPUT (Cycles' rule) against
// its exact expectation. A furnace seen from inside (closed sphere, Lambert albedo ρ = 0.5) with BSDF_ONLY light
// sampling traces no shadow rays, and cosine sampling gives every bounce the weight f·cos/pdf = ρ exactly, so a
// path's throughput is deterministic until roulette ends it:
//   vertex v (v = 0: the camera ray's hit) arrives with β_v; roulette runs there when v + 1 >= rr_start_bounce
//   and v <= max_bounces (past that the path ends on arrival), surviving with q_v = min(1, √β_v), after which
//   β becomes β_v/q_v and the next vertex gets β_{v+1} = ρ·β_v/q_v. Vertex v is reached with probability
//   P_v = Π_{j<v} q_j, and each reached vertex cost one ray, so E[rays per path] = Σ_{v=0}^{K+1} P_v
//   (K = max_bounces), and E[n²] = Σ_{k≥1} (2k − 1)·P(n ≥ k) with P(n ≥ k) = P_{k−1}.
// Cycles decides at every vertex whose bounce count exceeds min_light_bounces = m (bounce 0 at the first
// vertex: path_state_continuation_probability, called on arrival), so rr_start_bounce = m + 2 traces Cycles'
// rays: the bench's equal-settings run depends on this pairing. The check: the measured mean over 16,384
// independent paths within 5 standard errors of the expectation, and starts 2 and 3 told apart by far more.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr double k_rho = 0.5;
constexpr int k_max_bounces = 12;

struct RayMoments {
    double mean = 0.0, variance = 0.0;
};

RayMoments expected_rays(int rr_start_bounce) {
    double p = 1.0, beta = 1.0, mean = 0.0, second = 0.0;
    for (int v = 0; v <= k_max_bounces + 1; ++v) {
        mean += p;  // P(n >= v + 1) = P_v
        second += (2.0 * (v + 1) - 1.0) * p;
        if (v > k_max_bounces) break;
        const double q = v + 1 >= rr_start_bounce ? std::fmin(1.0, std::sqrt(beta)) : 1.0;
        p *= q;
        beta = k_rho * beta / q;
    }
    return {mean, second - mean * mean};
}

TEST(Roulette, SqrtThroughputTracesTheExpectedRaysPerPath) {
    const int w = 16, h = 16, spp = 64;
    const double paths = double(w) * h * spp;
    for (int start : {1, 2, 3, 5}) {
        Params p = basic_params(w, h, spp, k_max_bounces);
        p.set("rr_mode", std::string("SQRT_THROUGHPUT"));
        p.set("rr_start_bounce", int64_t(start));
        p.set("light_sampling", std::string("BSDF_ONLY"));
        p.set("sampler", std::string("RANDOM"));  // independent paths: the standard error below is honest
        p.set("seed", int64_t(17 + start));
        Session s(furnace_scene(FurnaceScene::EmissiveSphere, 16, 8), std::move(p));
        s.start();
        s.join();
        ASSERT_FALSE(s.error()) << *s.error();
        const SessionStats st = s.stats();
        ASSERT_EQ(double(st.paths), paths);
        const double measured = double(st.rays) / paths;
        const RayMoments want = expected_rays(start);
        const double se = std::sqrt(want.variance / paths);
        std::printf("rr_start_bounce %d: %.4f rays/path, expected %.4f ± %.4f\n", start, measured, want.mean, se);
        EXPECT_NEAR(measured, want.mean, 5.0 * se) << "rr_start_bounce " << start;
    }
    // The test can tell neighbouring starts apart: their expectations differ by far more than the tolerance.
    const double se = std::sqrt(expected_rays(2).variance / paths);
    EXPECT_GT(expected_rays(3).mean - expected_rays(2).mean, 20.0 * se);
}

}  // namespace
}  // namespace candela::test
