#include "integrators/mlt/bootstrap.h"

#include <algorithm>
#include <atomic>

#include "integrators/mlt/markov_chain.h"

namespace candela {

std::vector<double> Bootstrap::b_depth() const {
    std::vector<double> b(size_t(depths), 0.0);
    for (size_t e = 0; e < importance.size(); ++e) b[e % size_t(depths)] += importance[e];
    for (double& v : b) v /= double(std::max(1, paths));
    return b;
}

uint64_t bootstrap_state_key(uint64_t seed, int population, uint64_t index, int depth) {
    return hash_values(seed ^ 0x6d6c74626f6f74ULL, index, uint64_t(depth + 1) | (uint64_t(population) << 32));
}

std::vector<Bootstrap> run_bootstraps(const PathSpace& space, const MltSettings& s, bool multiplexed, uint64_t seed,
                                      int threads, RenderCounters& counters, const CancelToken* cancel) {
    std::vector<Bootstrap> boots(k_mlt_populations);
    for (Bootstrap& boot : boots) {
        boot.multiplexed = multiplexed;
        boot.depths = multiplexed ? space.max_depth() + 1 : 1;
        boot.paths = (s.bootstrap + 1) / 2;
        boot.importance.assign(size_t(boot.paths) * size_t(boot.depths), 0.f);
    }
    const size_t per = boots[0].importance.size(), n = per * size_t(k_mlt_populations);
    constexpr size_t k_chunk = 1024;
    const size_t chunks_per = (per + k_chunk - 1) / k_chunk;
    counters.stage.begin("Bootstrap paths", int64_t(n));
    std::atomic<int64_t> done{0};
    parallel_for(
        threads, chunks_per * size_t(k_mlt_populations),
        [&](size_t chunk) {
            const int pop = int(chunk / chunks_per);
            Bootstrap& boot = boots[size_t(pop)];
            const size_t lo = (chunk % chunks_per) * k_chunk, hi = std::min(per, lo + k_chunk);
            PrimarySampleSampler u(s.sigma, s.large_step);
            MltSample sample;
            PathStats stats;
            for (size_t e = lo; e < hi; ++e) {
                bootstrap_sample(space, bootstrap_state_key(seed, pop, boot.index_of(e), boot.depth_of(e)),
                                 boot.depth_of(e), u, stats, sample);
                boot.importance[e] = sample.importance;
            }
            stats.flush(counters);
            const int64_t now = done.fetch_add(int64_t(hi - lo)) + int64_t(hi - lo);
            counters.stage.set_done(std::min(int64_t(n), now));
        },
        cancel);
    counters.stage.end();
    return boots;
}

std::vector<ChainStart> resample_chain_starts(const Bootstrap& boot, int n, uint64_t seed, int population) {
    // Depth-major order: the cumulative importance passes depth 0's states, then depth 1's, ...
    const size_t D = size_t(boot.depths), paths = size_t(boot.paths);
    std::vector<double> depth_sum(D, 0.0);
    for (size_t e = 0; e < boot.importance.size(); ++e) depth_sum[e % D] += boot.importance[e];
    double total = 0.0;
    for (double v : depth_sum) total += v;
    std::vector<ChainStart> starts;
    if (!(total > 0.0) || n <= 0) return starts;
    Pcg32 rng(mix64(hash_values(seed ^ 0x6d6c747374726174ULL, uint64_t(population), 11u)), 0x737973ULL);
    const double xi = double(rng.next_float());
    std::vector<int> count(D, 0);
    std::vector<int> depth_of_start;
    size_t d = 0, i = 0;
    double cum = 0.0;  // importance of the entries before (d, i)
    for (int c = 0; c < n; ++c) {
        const double x = (double(c) + xi) / double(n) * total;
        // The first entry whose cumulative importance passes x (zero-importance entries are never chosen).
        while (d < D) {
            const double I = boot.importance[i * D + d];
            if (cum + I > x) break;
            cum += I;
            if (++i == paths) i = 0, ++d;
        }
        if (d == D) {  // rounding past the end: the last entry with importance
            d = D - 1, i = paths - 1;
            while (!(boot.importance[i * D + d] > 0.f)) {
                if (i == 0) i = paths, --d;
                --i;
            }
        }
        starts.push_back({i * D + d, 0.0});
        depth_of_start.push_back(int(d));
        ++count[d];
    }
    const double b = total / double(paths);
    for (size_t c = 0; c < starts.size(); ++c) {
        const size_t k = size_t(depth_of_start[c]);
        const double expected = double(n) * depth_sum[k] / total;
        starts[c].weight = expected >= 1.0 ? depth_sum[k] / double(paths) * double(n) / double(count[k]) : b;
    }
    return starts;
}

}  // namespace candela
