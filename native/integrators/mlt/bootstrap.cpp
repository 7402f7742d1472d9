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

std::vector<int> allocate_chains(const std::vector<double>& depth_sum, int n) {
    const size_t D = depth_sum.size();
    std::vector<int> count(D, 0);
    int lit = 0;
    double total = 0.0;
    for (double v : depth_sum) {
        lit += v > 0.0;
        total += v;
    }
    if (!(total > 0.0) || lit > n) return count;
    // One chain per lit depth, the rest by largest remainder of their quotas ∝ b_k (ties to the lower depth).
    const int rest = n - lit;
    std::vector<double> remainder(D, -1.0);
    int given = 0;
    for (size_t k = 0; k < D; ++k) {
        if (!(depth_sum[k] > 0.0)) continue;
        const double quota = double(rest) * depth_sum[k] / total;
        const int whole = std::min(rest - given, int(quota));
        count[k] = 1 + whole;
        given += whole;
        remainder[k] = quota - double(whole);
    }
    while (given < rest) {
        size_t best = 0;
        for (size_t k = 1; k < D; ++k)
            if (remainder[k] > remainder[best]) best = k;
        ++count[best];
        remainder[best] = -1.0;
        ++given;
    }
    return count;
}

namespace {

/// Systematic resampling: `count` of the entries `first`, `first` + `stride`, … (`n` of them, importance sum `sum` >
/// 0) at the positions (j + ξ)/count of their cumulative importance, each with `weight`.
void systematic(const std::vector<float>& importance, size_t first, size_t stride, size_t n, double sum, int count,
                double xi, double weight, std::vector<ChainStart>& out) {
    size_t i = 0, last = 0;  // last: the last entry with importance (where rounding past the end lands)
    for (size_t j = 0; j < n; ++j)
        if (importance[first + j * stride] > 0.f) last = j;
    double cum = 0.0;  // importance of the entries before i
    for (int c = 0; c < count; ++c) {
        const double x = (double(c) + xi) / double(count) * sum;
        // The first entry whose cumulative importance passes x (zero-importance entries are never chosen).
        while (i < n && !(cum + double(importance[first + i * stride]) > x)) cum += importance[first + i++ * stride];
        out.push_back({first + std::min(i, last) * stride, weight});
    }
}

double uniform_of(uint64_t seed, int population, uint64_t stratum) {
    Pcg32 rng(mix64(hash_values(seed ^ 0x6d6c747374726174ULL, uint64_t(population), stratum)), 0x737973ULL);
    return double(rng.next_float());
}

}  // namespace

std::vector<ChainStart> resample_chain_starts(const Bootstrap& boot, int n, uint64_t seed, int population) {
    const size_t D = size_t(boot.depths), paths = size_t(boot.paths);
    std::vector<double> depth_sum(D, 0.0);
    double total = 0.0;
    for (size_t e = 0; e < boot.importance.size(); ++e) depth_sum[e % D] += boot.importance[e];
    for (double v : depth_sum) total += v;
    std::vector<ChainStart> starts;
    if (!(total > 0.0) || n <= 0) return starts;
    const std::vector<int> count = allocate_chains(depth_sum, n);
    int allocated = 0;
    for (int c : count) allocated += c;
    if (allocated == 0) {  // more lit depths than chains: one systematic resampling over all, weight b
        systematic(boot.importance, 0, 1, boot.importance.size(), total, n, uniform_of(seed, population, D),
                   total / double(paths), starts);
        return starts;
    }
    for (size_t k = 0; k < D; ++k)
        if (count[k] > 0)
            systematic(boot.importance, k, D, paths, depth_sum[k], count[k], uniform_of(seed, population, k),
                       depth_sum[k] / double(paths) * double(n) / double(count[k]), starts);
    return starts;
}

}  // namespace candela
