// The Metropolis bootstrap (Veach 1997, §11.3.3; Kelemen et al. 2002; Hachisuka et al. 2014, §4): n independent
// primary-sample states per path depth (PSSMLT: one "depth", −1) estimate the normalisation b = ∫ I(u) du by the
// mean of I, and the chains' starting states are resampled from them ∝ I, so they start (approximately) in the
// stationary distribution.
//
// Two populations. The chains fall into two independent populations (chain c in population c mod 2, the film's
// noise replicate c mod 2), and each population has its own bootstrap (its own states, its own b): the two
// replicate images then differ by the error of b too, so the noise estimate from their difference includes it.
//
// Stratified resampling. A population's N chains are shared among the depths with light by a fixed allocation: one
// chain each, the rest in proportion to b_k (largest remainder), so depth k gets n_k ≥ 1 chains, about N·b_k/b,
// instead of a multinomial count whose error no number of mutations would reduce. Within depth k the n_k chains
// take the states at the evenly spaced positions (j + ξ_k)/n_k of depth k's cumulative importance (systematic
// resampling, one uniform ξ_k), and a chain at depth k splats with weight w_k = b_k·N/n_k: depth k's image is b_k
// times the mean over its chains, and since each of them starts at a state distributed ∝ I over depth k's bootstrap
// states (marginally, over ξ_k) and that b_k is their mean importance, the image is unbiased from the first mutation
// (Veach 1997, §11.3.3, per depth). For PSSMLT (one depth) every chain splats with b. With more lit depths than chains
// (not with the defaults) one systematic resampling over all states, in index order, and weight b
// (unbiased over ξ, but each depth's chain count is random).
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
/// The chains per depth: n_k of `n` for the depths' importance sums `depth_sum` (all 0 when b = 0 or there are
/// more lit depths than chains).
std::vector<int> allocate_chains(const std::vector<double>& depth_sum, int n);
/// Population `population`'s `n` chain starts by stratified resampling, in depth order (none if its b is 0).
std::vector<ChainStart> resample_chain_starts(const Bootstrap& boot, int n, uint64_t seed, int population);

}  // namespace candela
