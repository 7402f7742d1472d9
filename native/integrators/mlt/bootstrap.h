// The Metropolis bootstrap (Veach 1997, §11.3.3; Kelemen et al. 2002; Hachisuka et al. 2014, §4): n independent
// primary-sample states per path depth (PSSMLT: one "depth", −1) estimate the normalisation b = ∫ I(u) du by the
// mean of I, and the chains' starting states are resampled from them ∝ I, so they start (approximately) in the
// stationary distribution.
//
// Two populations. The chains fall into two independent populations (chain c in population c mod 2, the film's
// noise replicate c mod 2), and each population has its own bootstrap (its own states, its own b): the two
// replicate images then differ by the error of b too, so the noise estimate from their difference includes it.
//
// Stratified resampling. A population's N chains take the bootstrap states at the N evenly spaced positions
// (i + ξ)/N of the cumulative importance (systematic resampling, one uniform ξ), the states ordered depth-major:
// depth k gets n_k = ⌊N·b_k/b⌋ or ⌈N·b_k/b⌉ chains instead of a multinomial count. A chain at depth k splats with
// weight w_k = b_k·N/n_k when its expected count e_k = N·b_k/b is at least 1 (then n_k ≥ 1 always, and depth k's
// image is b_k times the mean of its chains, without the rounding of n_k), else w_k = b (n_k ∈ {0, 1} with
// P(n_k = 1) = e_k: unbiased over ξ). For PSSMLT every chain splats with b.
#pragma once

#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "integrators/mlt/mlt_settings.h"
#include "integrators/mlt/path_space.h"
#include "integrators/render_context.h"

namespace candela {

inline constexpr int k_mlt_populations = 2;

/// One population's bootstrap: `paths` independent states per depth, their importances in index order (entry
/// i·D + d for path i at depth d), so b and the resampling are the same for any thread count.
struct Bootstrap {
    std::vector<float> importance;
    int depths = 1;  // D
    int paths = 0;   // n per depth
    bool multiplexed = false;
    int depth_of(size_t entry) const { return multiplexed ? int(entry % size_t(depths)) : -1; }
    uint64_t index_of(size_t entry) const { return uint64_t(entry / size_t(depths)); }
    /// b_k: the mean importance at depth k (PSSMLT: one entry).
    std::vector<double> b_depth() const;
};

/// The key of bootstrap state (population, index, depth): the state is a function of it.
uint64_t bootstrap_state_key(uint64_t seed, int population, uint64_t index, int depth);

/// The bootstraps of both populations: the `settings.bootstrap` paths (per depth) split between them, each
/// population ⌈n/2⌉. Cancel leaves the remaining importances 0.
std::vector<Bootstrap> run_bootstraps(const PathSpace& space, const MltSettings& settings, bool multiplexed,
                                      uint64_t seed, int threads, RenderCounters& counters, const CancelToken* cancel);

/// A chain's start: its bootstrap entry and the weight its splats get (the b of the note above).
struct ChainStart {
    size_t entry = 0;
    double weight = 0.0;
};
/// Population `population`'s `n` chain starts by stratified resampling (none if its b is 0).
std::vector<ChainStart> resample_chain_starts(const Bootstrap& boot, int n, uint64_t seed, int population);

}  // namespace candela
