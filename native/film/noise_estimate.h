// What a render's error is, estimated from its own samples (the live "Noise" figures): the variance of
// each pixel's mean luminance, and the image's relative RMSE = √(mean over pixels of that variance) divided
// by the mean pixel luminance — the quantity the accuracy report measures against a converged reference.
//
// Why replicates. The running moments of a pixel's samples (Σ L, Σ L²) give s²/n, the variance of the mean
// of n *independent* samples. Stratified and quasi-Monte Carlo samples are not independent: they are spread
// on purpose, and the error of their mean is smaller than s²/n says (s²/n over-states the RMSE by 10–20 % on
// the room test scene, by 55–75 % on a soft shadow). So each pixel's samples are split into
// k_noise_replicates interleaved replicates (sample s belongs to replicate s mod B), each an independently
// randomised point set of the chosen sampler (its own scramble / permutation seed). Replicate means m_r (n_r samples each) are then independent estimates of the pixel,
// whatever the sampler does inside a replicate, and the pixel's mean is m = Σ n_r m_r / n. The one-way
// analysis of variance
//     v = Σ_r n_r (m_r − m)² / ((B − 1) · n)
// is an unbiased estimate of Var(m): for equal n_r it is the textbook Σ (m_r − m)² / (B (B − 1)), unbiased
// for any sampler because only the replicates' independence is used; for replicate sizes one apart (a render
// stopped mid-pass) it is exact for independent samples and off by O(1/n) otherwise. This is randomised QMC's
// standard variance estimate (Owen; L'Ecuyer & Lemieux): it sees the sampler's convergence gain instead of
// assuming it away.
//
// The price: a pixel's n samples are B point sets of n/B, so a sampler converging as n^(−1/2−δ) in RMSE
// loses a factor B^δ (about 5 % RMSE for B = 2 on the test scenes). B − 1 degrees of freedom per pixel make
// the per-pixel figure noisy (χ² with 1 dof for B = 2), but summed over thousands of pixels the image
// estimate is accurate to a few percent. The per-pixel "Noise" pass therefore keeps the smooth shape of the
// moment estimate s²/n (n − 1 dof) and scales it by the image-wide calibration κ = Σ v / Σ s²/n, so that
// the pass's mean square equals the honest image estimate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

namespace candela {

/// Independent randomisations a pixel's samples are split into (sample s is sample s / B of replicate s mod B).
inline constexpr uint32_t k_noise_replicates = 2;

inline constexpr uint32_t noise_replicate_of(uint32_t sample_index) { return sample_index % k_noise_replicates; }
inline constexpr uint32_t index_in_replicate(uint32_t sample_index) { return sample_index / k_noise_replicates; }

struct NoiseEstimate {
    /// Estimated relative RMSE of the image from the replicates; infinity until every replicate of every
    /// pixel has a sample.
    double relative_rmse = std::numeric_limits<double>::infinity();
    /// One-sided upper confidence bound (about 97.7 %) on the relative RMSE, from the spread of the per-pixel
    /// estimates: what the noise_threshold stopping rule compares, so that a lucky low estimate (few pixels,
    /// heavy-tailed samples) does not stop the render early.
    double relative_rmse_bound = std::numeric_limits<double>::infinity();
    /// The running-moment estimate √(Σ s²/n / pixels) / mean, which assumes independent samples (an upper
    /// bound under stratified / QMC sampling); for diagnostics and the per-pixel calibration.
    double moment_relative_rmse = std::numeric_limits<double>::infinity();
    double mean_luminance = 0.0;
    /// κ = Σ v / Σ s²/n: how much smaller the true variance is than the independent-sample formula says
    /// (1 when unknown).
    double calibration = 1.0;
};

struct PixelAccum;
struct SplatAccum;

/// Var(pixel mean luminance) from the replicates; negative when some replicate has no sample yet.
double replicate_variance_of_mean(const PixelAccum& p);
/// The same for a pixel with splatted contributions too (film.h): replicate r's estimate is its camera samples'
/// mean plus its splats' luminance over its splat samples N_r, m_r = cam_r + S_r/N_r, and the replicates are
/// weighted by their camera sample counts (by N_r where the pixel has no camera samples). Splatted light then
/// counts in the estimate as long as each replicate's splats come only from that replicate's samples.
double replicate_variance_of_mean(const PixelAccum& p, const SplatAccum& s,
                                  const double (&splat_samples)[k_noise_replicates]);
/// s²/n from the running moments (independent-sample formula); 0 below two samples.
double moment_variance_of_mean(const PixelAccum& p);

/// Sums over pixels for NoiseEstimate.
class NoiseTally {
public:
    void add(const PixelAccum& p);
    void add(const PixelAccum& p, const SplatAccum& s, const double (&splat_samples)[k_noise_replicates]);
    NoiseEstimate result() const;

private:
    size_t m_pixels = 0;
    bool m_complete = true;     // every pixel has every replicate
    double m_lum = 0.0;         // Σ pixel mean luminance
    double m_var = 0.0;         // Σ replicate variance of the mean
    double m_var_sq = 0.0;      // Σ (replicate variance of the mean)²
    double m_moment_var = 0.0;  // Σ s²/n
};

}  // namespace candela
