// Generic χ² goodness-of-fit test for direction samplers (pbrt-v3/v4 bsdfs_test, Mitsuba's chi2.py;
// docs/verification.md §6.1): draw N directions, bin them over (cos θ, φ) on the full sphere, integrate
// the claimed density over every cell, pool cells with small expected counts, and turn the χ² statistic
// into a p-value with the regularised incomplete gamma function. Reusable for warps, BSDFs and lights:
// the sampler and the pdf are std::functions.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/vec.h"

namespace candela::test {

/// Draws one direction from (u, uc) ∈ [0,1)² × [0,1); returns false for "no sample" (lost mass — the pdf
/// must then integrate to less than 1 by the same amount) or for samples the test should ignore
/// (delta samples: their mass must likewise be missing from the pdf).
using DirectionSampler = std::function<bool(Vec2 u, float uc, Vec3* w)>;
/// Solid-angle density of the sampler at the unit direction w.
using DirectionPdf = std::function<double(const Vec3& w)>;

struct Chi2Config {
    int cos_bins = 20;  // cells in cos θ ∈ [−1, 1]
    int phi_bins = 40;  // cells in φ ∈ [0, 2π)
    uint64_t samples = 1000000;
    double min_expected = 5.0;  // cells expected below this are pooled
    uint64_t seed = 1;
    // Absolute tolerance of each cell's adaptive Simpson integral. The counting noise of a cell of mass I is
    // √(I/N) ≳ 3e-5 for I ≥ 1e-3 at N = 10⁶, so 1e-7 keeps quadrature error far below it.
    double integration_eps = 1e-7;
    int integration_pieces = 2;  // initial Simpson panels per cell and axis (raise for very sharp lobes)
};

struct Chi2Result {
    double statistic = 0.0;
    int dof = 0;
    double p_value = 0.0;
    uint64_t valid_samples = 0;
    double pdf_integral = 0.0;               // ∫ pdf over the sphere (quadrature)
    bool rejected_empty_cell = false;        // samples landed where the pdf integrates to 0
    std::vector<double> observed, expected;  // per cell (cos-major), for dumps
    std::string summary() const;
};

/// Regularised upper incomplete gamma function Q(a, x) = Γ(a, x)/Γ(a) (a > 0, x ≥ 0).
double regularized_gamma_q(double a, double x);
/// P(χ²_dof ≥ statistic).
double chi2_survival(double statistic, int dof);
/// Per-test significance level for n independent tests at family-wise level alpha (Šidák).
double sidak_alpha(double alpha, int n);

/// Integral of the pdf over each (cos θ, φ) cell, cos-major, by nested adaptive Simpson quadrature.
std::vector<double> integrate_cells(const DirectionPdf& pdf, const Chi2Config& cfg);

/// Runs the full test. p_value is 0 if a sample fell into a cell of zero expected mass (beyond 1e-5·N).
Chi2Result chi2_test(const DirectionSampler& sample, const DirectionPdf& pdf, const Chi2Config& cfg = {});

}  // namespace candela::test
