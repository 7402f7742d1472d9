// The primary-sample-space sampler of Metropolis light transport (sampling/primary_sample_sampler.h): large steps are
// uniform (Kolmogorov–Smirnov), a rejection restores the state bit for bit, the small step is a symmetric wrapped
// Gaussian of the documented σ (and of σ·√n after n lazy steps), and a Metropolis chain driven by it has the target
// density as its stationary distribution (χ² on a known 2-D density: detailed balance of the whole mutation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sampling/primary_sample_sampler.h"

namespace candela::test {
namespace {

/// The Kolmogorov–Smirnov statistic of `x` against U[0, 1).
double ks_uniform(std::vector<double> x) {
    std::sort(x.begin(), x.end());
    double d = 0.0;
    const double n = double(x.size());
    for (size_t i = 0; i < x.size(); ++i) d = std::max({d, double(i + 1) / n - x[i], x[i] - double(i) / n});
    return d;
}

TEST(PrimarySampleSampler, ErfInvInvertsErf) {
    for (float x = -0.999f; x < 1.f; x += 0.037f) EXPECT_NEAR(std::erf(erf_inv(x)), x, 2e-6f) << x;
}

TEST(PrimarySampleSampler, LargeStepsAreUniform) {
    // KS at n = 20000: the critical value 1.95/√n has a false-alarm rate of 1e-3 per coordinate.
    PrimarySampleSampler u(0.01f, 1.f);
    u.seed(7);
    std::vector<double> first, later;
    for (int i = 0; i < 20000; ++i) {
        u.start_iteration();
        ASSERT_TRUE(u.large_step());
        first.push_back(u.sample_1d(0));
        if (i % 2 == 0) later.push_back(u.sample_2d(40).y);  // a coordinate read every other iteration
        if (i % 3 == 0)
            u.accept();
        else
            u.reject();
    }
    EXPECT_LT(ks_uniform(first), 1.95 / std::sqrt(double(first.size())));
    EXPECT_LT(ks_uniform(later), 1.95 / std::sqrt(double(later.size())));
}

TEST(PrimarySampleSampler, RejectionRestoresTheStateExactly) {
    for (float p_large : {0.f, 0.5f, 1.f}) {
        PrimarySampleSampler u(0.05f, p_large);
        u.seed(11);
        for (uint32_t d = 0; d < 12; ++d) u.sample_1d(d);  // the initial state
        for (int it = 0; it < 200; ++it) {
            std::vector<float> before;
            for (uint32_t d = 0; d < 12; ++d) before.push_back(u.value(d));
            u.start_iteration();
            // Every coordinate of the state is read (a coordinate left unread across an accepted large step is
            // drawn afresh when next read: part of the state, not of a proposal — the other tests cover that).
            bool changed = false;
            for (uint32_t d = 0; d < 12; ++d) changed |= u.sample_1d(d) != before[d];
            EXPECT_TRUE(changed) << it;
            if (it % 2 == 0) {
                u.reject();
                for (uint32_t d = 0; d < 12; ++d)
                    ASSERT_EQ(u.value(d), before[d]) << "p_large " << p_large << ", it " << it;
            } else {
                u.accept();
            }
        }
    }
}

TEST(PrimarySampleSampler, SmallStepsAreSymmetricGaussiansOfSigmaRootN) {
    // Wrapped differences of one coordinate after a small step (n = 1) and after four missed ones (read every
    // fifth iteration: σ·√5). σ = 0.02 keeps the wrap out of the way. Mean within 5 standard errors of 0, standard
    // deviation within 3 % (its relative standard error at n = 40000 is 0.35 %; the erf_inv clamp at 3.1σ removes
    // 0.2 % of the variance); the differences' third moment (symmetry) within 5 standard errors of 0.
    const float sigma = 0.02f;
    for (int every : {1, 5}) {
        PrimarySampleSampler u(sigma, 0.f);
        u.seed(3);
        float prev = u.sample_1d(0);
        std::vector<double> d;
        for (int it = 1; it <= 40000 * every; ++it) {
            u.start_iteration();
            if (it % every == 0) {
                const float v = u.sample_1d(0);
                double diff = double(v) - double(prev);
                diff -= std::round(diff);
                d.push_back(diff);
                prev = v;
            }
            u.accept();
        }
        double m = 0.0, m2 = 0.0, m3 = 0.0;
        for (double x : d) m += x;
        m /= double(d.size());
        for (double x : d) m2 += (x - m) * (x - m), m3 += std::pow(x - m, 3);
        m2 /= double(d.size());
        m3 /= double(d.size());
        const double expected = sigma * std::sqrt(double(every)), n = double(d.size());
        EXPECT_LT(std::fabs(m), 5.0 * expected / std::sqrt(n)) << every;
        EXPECT_NEAR(std::sqrt(m2), expected, 0.03 * expected) << every;
        EXPECT_LT(std::fabs(m3), 5.0 * std::sqrt(15.0) * std::pow(expected, 3) / std::sqrt(n)) << every;
    }
}

TEST(PrimarySampleSampler, MetropolisChainHasTheTargetAsStationaryDistribution) {
    // Target f(x, y) = (1 + 6x²)·(0.2 + sin²(πy)) on the unit square (coordinates 0 and 1). A chain of 2·10⁶ mutations
    // (p_large 0.3, σ 0.05), thinned to every 40th state (correlation between kept states well under 0.1), binned
    // 8 × 8; χ² against the bins' exact probabilities with 63 degrees of freedom: 115 has a false-alarm rate of 1e-4
    // for independent draws (the residual correlation raises it slightly).
    auto f = [](double x, double y) { return (1.0 + 6.0 * x * x) * (0.2 + std::pow(std::sin(M_PI * y), 2)); };
    // Exact bin masses: ∫(1 + 6x²) = x + 2x³, ∫(0.2 + sin²πy) = 0.7y − sin(2πy)/(4π).
    auto Fx = [](double x) { return x + 2.0 * x * x * x; };
    auto Fy = [](double y) { return 0.7 * y - std::sin(2.0 * M_PI * y) / (4.0 * M_PI); };
    const double total = Fx(1.0) * Fy(1.0);
    for (float p_large : {0.3f, 1.f}) {
        PrimarySampleSampler u(0.05f, p_large);
        u.seed(5);
        Pcg32 rng(17, 1);
        double fx = f(u.sample_1d(0), u.sample_1d(1));
        std::vector<double> counts(64, 0.0);
        double kept = 0.0;
        for (int it = 1; it <= 2000000; ++it) {
            u.start_iteration();
            const double fp = f(u.sample_1d(0), u.sample_1d(1));
            if (rng.next_float() < std::min(1.0, fp / fx)) {
                u.accept();
                fx = fp;
            } else {
                u.reject();
            }
            if (it % 40 == 0) {
                const int bx = std::min(7, int(u.value(0) * 8.f)), by = std::min(7, int(u.value(1) * 8.f));
                counts[size_t(by * 8 + bx)] += 1.0;
                kept += 1.0;
            }
        }
        double chi2 = 0.0;
        for (int by = 0; by < 8; ++by)
            for (int bx = 0; bx < 8; ++bx) {
                const double p = (Fx((bx + 1) / 8.0) - Fx(bx / 8.0)) * (Fy((by + 1) / 8.0) - Fy(by / 8.0)) / total;
                const double e = p * kept;
                chi2 += (counts[size_t(by * 8 + bx)] - e) * (counts[size_t(by * 8 + bx)] - e) / e;
            }
        EXPECT_LT(chi2, 115.0) << "p_large " << p_large;
    }
}

}  // namespace
}  // namespace candela::test
