#include "integrators/mlt/markov_chain.h"

#include <algorithm>

namespace candela {

void bootstrap_sample(const PathSpace& space, uint64_t key, int depth, PrimarySampleSampler& u, PathStats& stats,
                      MltSample& out) {
    u = PrimarySampleSampler(u.sigma(), u.p_large());
    u.seed(key);
    space.evaluate(u, depth, stats, out);
}

MarkovChain::MarkovChain(const PathSpace& space, float sigma, float p_large, uint64_t state_key, int depth,
                         uint64_t chain_key, PathStats& stats)
    : m_space(space), m_u(sigma, p_large), m_rng(mix64(chain_key), chain_key), m_depth(depth) {
    bootstrap_sample(space, state_key, depth, m_u, stats, m_current);
    // The mutations' own stream: chains that start from the same bootstrap path still diverge.
    m_u.seed(hash_combine(chain_key, 0x636861696eULL));
}

void MarkovChain::splat(const MltSample& s, double scale, uint32_t replicate, SplatBuffer& out) const {
    if (!(scale > 0.0) || !(s.importance > 0.f)) return;
    const float k = float(scale / double(s.importance));
    for (const BdptTracer::Contribution& c : s.contributions) out.add(c.raster, c.L * k, replicate);
}

int64_t MarkovChain::run(int64_t mutations, double b, uint32_t replicate, SplatBuffer& out, PathStats& stats,
                         ChainCounts& counts, const CancelToken* cancel) {
    constexpr int64_t k_cancel_check = 256;
    int64_t done = 0;
    for (; done < mutations; ++done) {
        if (done % k_cancel_check == 0 && cancel && cancel->cancelled()) break;
        m_u.start_iteration();
        if (m_u.large_step()) ++counts.large_steps;
        m_space.evaluate(m_u, m_depth, stats, m_proposal);
        const float I = m_current.importance, Ip = m_proposal.importance;
        const double a = I > 0.f ? std::min(1.0, double(Ip) / double(I)) : 1.0;
        splat(m_proposal, a * b, replicate, out);
        m_current_weight += 1.0 - a;
        if (m_rng.next_float() < a) {
            splat(m_current, m_current_weight * b, replicate, out);
            std::swap(m_current, m_proposal);
            m_current_weight = 0.0;
            m_u.accept();
            ++counts.accepted;
        } else {
            m_u.reject();
            ++counts.rejected;
        }
    }
    // The pass's splats are complete: the current state's gathered weight goes with them.
    splat(m_current, m_current_weight * b, replicate, out);
    m_current_weight = 0.0;
    return done;
}

}  // namespace candela
