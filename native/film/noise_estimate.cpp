#include "film/noise_estimate.h"

#include <algorithm>
#include <cmath>

#include "film/film.h"

namespace candela {

double replicate_variance_of_mean(const PixelAccum& p) {
    for (uint32_t r = 0; r < k_noise_replicates; ++r)
        if (p.rep_n[r] == 0) return -1.0;
    const double mean = p.lum_sum() / p.n;
    double between = 0.0;  // Σ n_r (m_r − m)²
    for (uint32_t r = 0; r < k_noise_replicates; ++r) {
        const double d = p.rep_lum[r] / p.rep_n[r] - mean;
        between += p.rep_n[r] * d * d;
    }
    return between / (double(k_noise_replicates - 1) * p.n);
}

double replicate_variance_of_mean(const PixelAccum& p, const SplatAccum& s,
                                  const double (&splat_samples)[k_noise_replicates]) {
    double m[k_noise_replicates], w[k_noise_replicates], weight = 0.0, mean = 0.0;
    for (uint32_t r = 0; r < k_noise_replicates; ++r) {
        if (!(splat_samples[r] > 0.0) || (p.n > 0 && p.rep_n[r] == 0)) return -1.0;
        m[r] = (p.rep_n[r] ? p.rep_lum[r] / p.rep_n[r] : 0.0) + s.rep_lum[r] / splat_samples[r];
        w[r] = p.n > 0 ? double(p.rep_n[r]) : splat_samples[r];
        weight += w[r];
        mean += w[r] * m[r];
    }
    mean /= weight;
    double between = 0.0;
    for (uint32_t r = 0; r < k_noise_replicates; ++r) between += w[r] * (m[r] - mean) * (m[r] - mean);
    return between / (double(k_noise_replicates - 1) * weight);
}

double moment_variance_of_mean(const PixelAccum& p) {
    if (p.n < 2) return 0.0;
    const double mean = p.lum_sum() / p.n;
    const double s2 = std::max(0.0, (p.lum_sq - p.n * mean * mean) / (p.n - 1));
    return s2 / p.n;
}

void NoiseTally::add(const PixelAccum& p) {
    ++m_pixels;
    if (p.n) m_lum += p.lum_sum() / p.n;
    m_moment_var += moment_variance_of_mean(p);
    const double v = replicate_variance_of_mean(p);
    if (v < 0.0) {
        m_complete = false;
        return;
    }
    m_var += v;
    m_var_sq += v * v;
}

void NoiseTally::add(const PixelAccum& p, const SplatAccum& s, const double (&splat_samples)[k_noise_replicates]) {
    ++m_pixels;
    double total = 0.0;
    for (double n : splat_samples) total += n;
    const double splat_lum = total > 0.0 ? (0.2126 * s.r + 0.7152 * s.g + 0.0722 * s.b) / total : 0.0;
    m_lum += (p.n ? p.lum_sum() / p.n : 0.0) + splat_lum;
    const double v = replicate_variance_of_mean(p, s, splat_samples);
    // Splats have no per-sample moments: the moment figure falls back on the replicate estimate.
    m_moment_var += p.n ? moment_variance_of_mean(p) : std::max(v, 0.0);
    if (v < 0.0) {
        m_complete = false;
        return;
    }
    m_var += v;
    m_var_sq += v * v;
}

NoiseEstimate NoiseTally::result() const {
    NoiseEstimate e;
    if (m_pixels == 0) return e;
    const double pixels = double(m_pixels);
    e.mean_luminance = m_lum / pixels;
    if (!(e.mean_luminance > 0.0)) return e;  // black image: no relative error to speak of
    auto relative = [&](double var_sum) { return std::sqrt(var_sum / pixels) / e.mean_luminance; };
    e.moment_relative_rmse = relative(m_moment_var);
    if (!m_complete) return e;
    e.relative_rmse = relative(m_var);
    // Spread of Σ v: pixels are independent, and for Gaussian replicate means v_p·(B−1)/Var_p is χ² with B − 1
    // degrees of freedom, so Var(v_p) = 2 Var_p²/(B−1) and E[v_p²] = Var_p² (B+1)/(B−1): 2 v_p²/(B+1) estimates
    // Var(v_p) without bias. Heavier tails than Gaussian show up as a few large v_p, which this sum weights by
    // their square, so the bound widens exactly when the estimate is shaky. z = 2: one-sided 97.7 %.
    const double spread = std::sqrt(2.0 * m_var_sq / (k_noise_replicates + 1));
    e.relative_rmse_bound = relative(m_var + 2.0 * spread);
    if (m_moment_var > 0.0) e.calibration = m_var / m_moment_var;
    return e;
}

}  // namespace candela
