// Sampler quality: 2-D L2-star discrepancy (Warnock's formula) against docs/verification.md §4.6, and the
// convergence rate of the MSE on the analytic integrands of §4.7 (pbrt-v4's "function" integrator: each pixel
// is one independent randomisation of the sampler).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "core/math.h"
#include "sampling/low_discrepancy.h"
#include "sampling/sampler.h"

namespace candela {
namespace {

/// Warnock: T² = 1/9 − (2/N)Σᵢ Πₖ (1 − xᵢₖ²)/2 + (1/N²)ΣᵢΣⱼ Πₖ (1 − max(xᵢₖ, xⱼₖ)).
double l2_star_squared(const std::vector<std::array<double, 2>>& p) {
    const double n = double(p.size());
    double a = 0.0, b = 0.0;
    for (const auto& x : p) a += (1.0 - x[0] * x[0]) * (1.0 - x[1] * x[1]) / 4.0;
    for (const auto& x : p)
        for (const auto& y : p) b += (1.0 - std::max(x[0], y[0])) * (1.0 - std::max(x[1], y[1]));
    return 1.0 / 9.0 - 2.0 / n * a + b / (n * n);
}

std::vector<std::array<double, 2>> pixel_set(const std::string& name, int n, uint32_t px, uint32_t py,
                                             Dim dim = Dim::Filter, int bounce = 0) {
    Sampler s = make_sampler(name, 17, n);
    std::vector<std::array<double, 2>> pts;
    for (int i = 0; i < n; ++i) {
        start_pixel_sample(s, px, py, uint32_t(i));
        const Vec2 v = get_2d(s, dim, bounce);
        pts.push_back({double(v.x), double(v.y)});
    }
    return pts;
}

TEST(SamplerDiscrepancy, UnscrambledSetsMatchTable) {
    // docs/verification.md §4.6 table (4 significant digits).
    const int ns[3] = {16, 64, 256};
    const double hammersley_t[3] = {6.929e-2, 2.121e-2, 6.277e-3};
    const double halton0_t[3] = {6.825e-2, 1.641e-2, 5.306e-3};
    const double halton1_t[3] = {4.614e-2, 1.397e-2, 4.277e-3};
    for (int k = 0; k < 3; ++k) {
        const int n = ns[k];
        std::vector<std::array<double, 2>> ham, h0, h1;
        for (int i = 0; i < n; ++i) {
            ham.push_back({hammersley(0, uint64_t(i), uint64_t(n)), hammersley(1, uint64_t(i), uint64_t(n))});
            h0.push_back({halton(0, uint64_t(i)), halton(1, uint64_t(i))});
            h1.push_back({halton(0, uint64_t(i + 1)), halton(1, uint64_t(i + 1))});
        }
        EXPECT_NEAR(std::sqrt(l2_star_squared(ham)), hammersley_t[k], 6e-4 * hammersley_t[k]) << n;
        EXPECT_NEAR(std::sqrt(l2_star_squared(h0)), halton0_t[k], 6e-4 * halton0_t[k]) << n;
        EXPECT_NEAR(std::sqrt(l2_star_squared(h1)), halton1_t[k], 6e-4 * halton1_t[k]) << n;
    }
}

TEST(SamplerDiscrepancy, RandomisedSamplersOrdering) {
    const int pixels = 40;
    const int ns[3] = {16, 64, 256};
    // docs/verification.md §4.6: jittered (a ten-seed estimate, within 1.2 % of the exact RMS) and Hammersley
    // (unscrambled, exact).
    const double jittered_t[3] = {4.94e-2, 1.80e-2, 6.36e-3};
    const double hammersley_t[3] = {6.929e-2, 2.121e-2, 6.277e-3};
    for (int k = 0; k < 3; ++k) {
        const int n = ns[k];
        std::map<std::string, double> rms;
        for (const auto& name : sampler_names()) {
            double sum = 0.0, sum2 = 0.0;
            for (int p = 0; p < pixels; ++p) {
                const double t2 = l2_star_squared(pixel_set(name, n, uint32_t(p), 9));
                sum += t2;
                sum2 += t2 * t2;
            }
            const double mean = sum / pixels, sd = std::sqrt(std::max(0.0, sum2 / pixels - mean * mean));
            rms[name] = std::sqrt(mean);
            std::printf("[ discrepancy ] N=%4d %-10s RMS T = %.4e\n", n, name.c_str(), rms[name]);
            if (name == "RANDOM") {
                // Independent uniform points: E[T²] = (1/4 − 1/9)/N exactly.
                const double expected = (0.25 - 1.0 / 9.0) / n;
                EXPECT_NEAR(mean, expected, 4.0 * sd / std::sqrt(double(pixels))) << n;
            }
        }
        for (const auto& name : sampler_names()) {
            if (name == "RANDOM") continue;
            EXPECT_LT(rms[name], 0.75 * rms["RANDOM"]) << name << " N=" << n;
        }
        // The (0,m,2)-nets: at most the unscrambled Hammersley value and the jittered value of the table.
        for (const char* name : {"HAMMERSLEY", "SOBOL"}) {
            EXPECT_LT(rms[name], 1.1 * hammersley_t[k]) << name << " N=" << n;
            EXPECT_LT(rms[name], 1.1 * jittered_t[k]) << name << " N=" << n;
            EXPECT_LT(rms[name], rms["NROOKS"]) << name << " N=" << n;
        }
        EXPECT_NEAR(rms["STRATIFIED"], jittered_t[k], 0.25 * jittered_t[k]) << "N=" << n;
    }
}

// ---- MSE vs N ----

double disk(double x, double y) {
    const double dx = x - 0.5, dy = y - 0.5;
    return dx * dx + dy * dy < 0.25 ? 1.0 / (k_pi * 0.25) : 0.0;
}

double gaussian(double x, double y) {
    const double s = 0.25;
    static const double z = s * std::sqrt(2.0 * 3.14159265358979323846) * std::erf(0.5 / (s * std::sqrt(2.0)));
    const double gx = std::exp(-(x - 0.5) * (x - 0.5) / (2 * s * s)),
                 gy = std::exp(-(y - 0.5) * (y - 0.5) / (2 * s * s));
    return gx * gy / (z * z);
}

struct SlopeFit {
    double slope, se;
    std::vector<double> mse;
};

/// Least-squares slope of log MSE vs log N; its standard error from each MSE's sampling error (delta method).
SlopeFit mse_slope(const std::string& name, double (*f)(double, double), Dim dim, int bounce, int pixels) {
    const int ns[4] = {16, 64, 256, 1024};
    std::vector<double> lx, ly, var;
    SlopeFit fit{};
    for (int n : ns) {
        Sampler s = make_sampler(name, 5, n);
        double sum = 0.0, sum2 = 0.0;
        for (int p = 0; p < pixels; ++p) {
            double est = 0.0;
            for (int i = 0; i < n; ++i) {
                start_pixel_sample(s, uint32_t(p % 64), uint32_t(p / 64), uint32_t(i));
                const Vec2 u = get_2d(s, dim, bounce);
                est += f(u.x, u.y);
            }
            const double e2 = (est / n - 1.0) * (est / n - 1.0);
            sum += e2;
            sum2 += e2 * e2;
        }
        const double mse = sum / pixels, sd = std::sqrt(std::max(0.0, sum2 / pixels - mse * mse));
        fit.mse.push_back(mse);
        lx.push_back(std::log(double(n)));
        ly.push_back(std::log(mse));
        const double rel = sd / std::sqrt(double(pixels)) / mse;
        var.push_back(rel * rel);
    }
    double mx = 0, my = 0;
    for (size_t k = 0; k < lx.size(); ++k) mx += lx[k] / lx.size(), my += ly[k] / ly.size();
    double sxx = 0, sxy = 0;
    for (size_t k = 0; k < lx.size(); ++k) sxx += (lx[k] - mx) * (lx[k] - mx), sxy += (lx[k] - mx) * (ly[k] - my);
    fit.slope = sxy / sxx;
    double v = 0;
    for (size_t k = 0; k < lx.size(); ++k) v += (lx[k] - mx) * (lx[k] - mx) / (sxx * sxx) * var[k];
    fit.se = std::sqrt(v);
    return fit;
}

void print_fit(const char* what, const std::string& name, const SlopeFit& f) {
    std::printf("[ mse slope ] %-9s %-10s slope %+.3f ± %.3f  MSE(16..1024) %.3e %.3e %.3e %.3e\n", what, name.c_str(),
                f.slope, f.se, f.mse[0], f.mse[1], f.mse[2], f.mse[3]);
}

const int k_pixels = 384;

TEST(SamplerConvergence, RandomSlopeIsMinusOne) {
    for (auto [what, f] : {std::pair{"disk", &disk}, {"gaussian", &gaussian}}) {
        const SlopeFit fit = mse_slope("RANDOM", f, Dim::Filter, 0, k_pixels);
        print_fit(what, "RANDOM", fit);
        EXPECT_NEAR(fit.slope, -1.0, std::max(4.0 * fit.se, 0.05)) << what;
    }
}

TEST(SamplerConvergence, StratifiedAndQmcSlopesAreSteeper) {
    for (const char* name : {"STRATIFIED", "HALTON", "HAMMERSLEY", "SOBOL"}) {
        for (auto [what, f] : {std::pair{"disk", &disk}, {"gaussian", &gaussian}}) {
            const SlopeFit fit = mse_slope(name, f, Dim::Filter, 0, k_pixels);
            print_fit(what, name, fit);
            EXPECT_LT(fit.slope, -1.3) << name << " " << what;
        }
    }
    // Deeper 2-D requests keep the rate for the samplers that stratify every pair.
    for (const char* name : {"STRATIFIED", "SOBOL"}) {
        for (auto [what, f] : {std::pair{"disk", &disk}, {"gaussian", &gaussian}}) {
            const SlopeFit fit = mse_slope(name, f, Dim::Bsdf, 7, k_pixels);
            print_fit(what, std::string(name) + "@bsdf7", fit);
            EXPECT_LT(fit.slope, -1.3) << name << " " << what;
        }
    }
}

TEST(SamplerConvergence, NRooksBeatsRandomOnSmoothIntegrand) {
    // Latin hypercube removes the additive part of the variance: for a non-additive 2-D integrand the rate
    // stays N^-1 but the constant is smaller (Stein 1987).
    const SlopeFit rooks = mse_slope("NROOKS", &gaussian, Dim::Filter, 0, k_pixels);
    const SlopeFit random = mse_slope("RANDOM", &gaussian, Dim::Filter, 0, k_pixels);
    print_fit("gaussian", "NROOKS", rooks);
    for (size_t k = 0; k < 4; ++k) EXPECT_LT(rooks.mse[k], 0.5 * random.mse[k]) << k;
    const SlopeFit rooks_disk = mse_slope("NROOKS", &disk, Dim::Filter, 0, k_pixels);
    print_fit("disk", "NROOKS", rooks_disk);
    EXPECT_LT(rooks_disk.slope, -0.8);
}

}  // namespace
}  // namespace candela
