// One Metropolis chain in primary sample space (Kelemen et al. 2002; Veach 1997, §11.3): the state u with its
// evaluated sample, mutated by the primary-sample sampler's small and large steps (symmetric proposals, so the
// acceptance is a = min(1, I(u')/I(u))). Each mutation splats both the proposal, with weight a, and the current state,
// with weight 1 − a (Veach's expected-value improvement, §11.3.5): a state's accumulated weight is splatted once, when
// it is left or at the end of a pass. A splat of contribution c of a state with importance I lands with value
// c·(b/I)·weight; the film divides by the mutations per pixel of the spread area (path_space.h), so that the image
// is A·(b/M)·Σ g(u_k)/I(u_k), the Metropolis estimate of A·∫ g du.
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "film/film.h"
#include "integrators/mlt/path_space.h"

namespace candela {

struct ChainCounts {
    uint64_t accepted = 0, rejected = 0, large_steps = 0;
};

class MarkovChain {
public:
    /// A chain whose state is bootstrap path `state_key` (evaluated again from that key: the state is a function
    /// of it) at depth `depth` (MMLT; −1: PSSMLT), mutating with its own stream `chain_key`.
    MarkovChain(const PathSpace& space, float sigma, float p_large, uint64_t state_key, int depth, uint64_t chain_key,
                PathStats& stats);

    /// `mutations` mutations, splatting into `out` (noise replicate `replicate`) with scale b; stops early (returning
    /// the mutations done) once `cancel` fires, checked every few hundred mutations.
    int64_t run(int64_t mutations, double b, uint32_t replicate, SplatBuffer& out, PathStats& stats,
                ChainCounts& counts, const CancelToken* cancel);

    float importance() const { return m_current.importance; }
    const PrimarySampleSampler& sampler() const { return m_u; }

private:
    void splat(const MltSample& s, double scale, uint32_t replicate, SplatBuffer& out) const;

    const PathSpace& m_space;
    PrimarySampleSampler m_u;
    Pcg32 m_rng;  // the acceptance decisions
    int m_depth;
    MltSample m_current, m_proposal;
    double m_current_weight = 0.0;  // expected-value weight the current state has gathered but not splatted
};

/// The primary-sample state of bootstrap path `key`: a fresh sampler, seeded by it, at iteration 0 (every value
/// a fresh uniform on first read), evaluated.
void bootstrap_sample(const PathSpace& space, uint64_t key, int depth, PrimarySampleSampler& u, PathStats& stats,
                      MltSample& out);

}  // namespace candela
