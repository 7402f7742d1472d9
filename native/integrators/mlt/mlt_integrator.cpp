#include "integrators/mlt/mlt_integrator.h"

#include "core/error.h"
#include "scene/camera.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <string>

#include "core/parallel.h"
#include "core/parallel_ordered.h"
#include "integrators/mlt/bootstrap.h"
#include "integrators/mlt/markov_chain.h"
#include "integrators/mlt/mlt_settings.h"

namespace candela {

namespace {

static_assert(k_mlt_populations == int(k_noise_replicates), "a chain population per noise replicate");

uint64_t chain_key(uint64_t seed, uint64_t chain) { return hash_values(seed ^ 0x6d6c74636861ULL, chain, 7u); }

/// What the tests and the log see: the populations' b and b_k averaged (each is an estimate from half the paths).
MltBootstrap summarise(const std::vector<Bootstrap>& boots) {
    MltBootstrap out;
    for (const Bootstrap& boot : boots) {
        const std::vector<double> bk = boot.b_depth();
        out.b_depth.resize(bk.size(), 0.0);
        double b = 0.0;
        for (size_t k = 0; k < bk.size(); ++k) {
            out.b_depth[k] += bk[k] / double(boots.size());
            b += bk[k];
        }
        out.b_population.push_back(b);
        out.b += b / double(boots.size());
    }
    return out;
}

class MltIntegrator final : public Integrator {
public:
    MltIntegrator(const Params& params, bool multiplexed)
        : m_settings(MltSettings::from_params(params, multiplexed)), m_multiplexed(multiplexed) {
        // The chains run BDPT's strategies, whose t = 1 connections invert a perspective or orthographic viewplane.
        if (params.get<std::string>("camera_type", "PERSP") == "PANO")
            throw InvalidParameter(std::string("integrator ") + (multiplexed ? "MMLT" : "MLT") + ": " +
                                   Camera::panoramic_not_connectable_message(
                                       params.get<std::string>("panorama_type", "FISHEYE_EQUISOLID")));
    }

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        const char* name = m_multiplexed ? "MMLT" : "MLT";
        const EmitterSet emitters(scene.lights(), scene.bounds());
        const PixelSampling& ps = m_settings.bdpt.pixel;
        if (ps.film_transparent) ctx.log(std::string(name) + ": the film is rendered opaque (no transparent film)");
        if (scene.hidden_ray_types() & (k_ray_diffuse | k_ray_glossy | k_ray_transmission))
            ctx.log(std::string(name) +
                    ": objects hidden from diffuse, glossy or transmission rays are visible to "
                    "light subpaths and connections (only camera and shadow visibility are honoured)");
        const PathSpace space(scene, m_settings.bdpt, emitters);
        const std::vector<Bootstrap> boots =
            run_bootstraps(space, m_settings, m_multiplexed, ps.seed, ctx.threads, ctx.counters, &ctx.cancel);
        if (ctx.cancel.cancelled()) {  // cancelled during the bootstrap: no chain, an empty image
            ctx.counters.work_total = ps.samples;
            ctx.counters.stop_reason = int(StopReason::Cancelled);
            return;
        }
        const MltBootstrap summary = summarise(boots);

        // The chains' starting states and splat weights (bootstrap.h): chain c = p + 2i is start i of population
        // p. A population whose bootstrap found no light has no chains: its mutations count, black.
        std::vector<std::unique_ptr<MarkovChain>> chains(size_t(m_settings.chains));
        std::vector<double> weight(chains.size(), 0.0);
        {
            PathStats stats;
            const int per = m_settings.chains / k_mlt_populations;
            for (int pop = 0; pop < k_mlt_populations; ++pop) {
                const Bootstrap& boot = boots[size_t(pop)];
                const std::vector<ChainStart> starts = resample_chain_starts(boot, per, ps.seed, pop);
                for (size_t i = 0; i < starts.size(); ++i) {
                    const size_t c = size_t(pop) + size_t(k_mlt_populations) * i;
                    const size_t e = starts[i].entry;
                    chains[c] = std::make_unique<MarkovChain>(
                        space, m_settings.sigma, m_settings.large_step,
                        bootstrap_state_key(ps.seed, pop, boot.index_of(e), boot.depth_of(e)), boot.depth_of(e),
                        chain_key(ps.seed, uint64_t(c)), stats);
                    weight[c] = starts[i].weight;
                }
            }
            stats.flush(ctx.counters);
        }
        if (!(summary.b > 0.0))
            ctx.log(std::string(name) + ": no bootstrap path carries light (b = 0): the image is black");

        const double frame_pixels = double(scene.camera().full_width()) * scene.camera().full_height();
        const uint64_t n_chains = uint64_t(m_settings.chains);
        // Mutations with global index j in [0, x) that chain c makes (j ≡ c mod the chain count).
        auto share = [&](uint64_t x, uint64_t c) { return x > c ? (x - c - 1) / n_chains + 1 : 0; };
        struct ChainPass {
            SplatBuffer buffer;
            int64_t done = 0;
            ChainCounts counts;
        };
        ChainCounts total;
        ProgressivePlan plan;
        plan.total = ps.samples;
        plan.max_pass = 16;
        plan.time_limit = ps.time_limit;
        plan.noise_threshold = ps.noise_threshold;
        run_progressive(
            ctx, plan,
            [&](int64_t begin, int64_t end) {
                const uint64_t lo = uint64_t(double(begin) * frame_pixels), hi = uint64_t(double(end) * frame_pixels);
                parallel_ordered(
                    ctx.threads, chains.size(), size_t(2 * resolve_thread_count(ctx.threads)),
                    [&](size_t c) {
                        ChainPass out;
                        PathStats stats;
                        const int64_t n = int64_t(share(hi, c) - share(lo, c));
                        out.done = chains[c] ? chains[c]->run(n, weight[c], uint32_t(c % k_noise_replicates),
                                                              out.buffer, stats, out.counts, &ctx.cancel)
                                             : n;
                        stats.flush(ctx.counters);
                        return out;
                    },
                    [&](size_t c, ChainPass&& pass) {
                        double samples[k_noise_replicates] = {};
                        samples[c % k_noise_replicates] = double(pass.done) / space.raster_area();
                        film.add_splats(pass.buffer, ps.filter, samples);
                        total.accepted += pass.counts.accepted;
                        total.rejected += pass.counts.rejected;
                        total.large_steps += pass.counts.large_steps;
                    },
                    &ctx.cancel);
            },
            [&] { return film.noise_estimate(); });
        const uint64_t mutations = total.accepted + total.rejected;
        char line[256];
        std::snprintf(line, sizeof line,
                      "%s: b = %.6g (populations %.6g, %.6g) from %d bootstrap paths%s, %d chains, %llu mutations, "
                      "%.1f %% accepted "
                      "(%llu accepted, %llu rejected, %.1f %% large steps)",
                      name, summary.b, summary.b_population[0], summary.b_population[1], m_settings.bootstrap,
                      m_multiplexed ? " per depth" : "", m_settings.chains, (unsigned long long)mutations,
                      mutations ? 100.0 * double(total.accepted) / double(mutations) : 0.0,
                      (unsigned long long)total.accepted, (unsigned long long)total.rejected,
                      mutations ? 100.0 * double(total.large_steps) / double(mutations) : 0.0);
        ctx.info(line);
    }
    WorkBudget budget() const override { return {m_settings.bdpt.pixel.samples, "mutation"}; }
    // Motion blur: the shutter time is a coordinate of the chain's state (PathSpace::shutter_dim).
    uint32_t honoured_features() const override { return k_feature_motion_blur; }

private:
    MltSettings m_settings;
    bool m_multiplexed;
};

}  // namespace

std::unique_ptr<Integrator> make_mlt_integrator(const Params& params) {
    return std::make_unique<MltIntegrator>(params, false);
}
std::unique_ptr<Integrator> make_mmlt_integrator(const Params& params) {
    return std::make_unique<MltIntegrator>(params, true);
}

double mlt_integrator_memory(const Params& params, double film_pixels) {
    const double chains = double(params.get<int64_t>("mlt_chains", 1000));
    const double bootstrap = double(params.get<int64_t>("mlt_bootstrap", 100000));
    const double depths = params.get<std::string>("integrator", "MLT") == "MMLT"
                              ? double(params.get<int64_t>("max_bounces", 12) + 2)
                              : 1.0;
    // The film's splat accumulators, the bootstrap's importances (and their sampling tables), each chain's state
    // (primary samples with backups, two evaluated samples: ~8 KB), the splat buffers of the chains in flight.
    return film_pixels * double(sizeof(SplatAccum)) + bootstrap * depths * 4.0 * sizeof(float) + chains * 8192.0 +
           64.0 * 16.0 * film_pixels / std::max(1.0, chains) * double(sizeof(SplatBuffer::Entry));
}

MltBootstrap mlt_bootstrap(const Scene& scene, const Params& params, int threads) {
    const bool multiplexed = params.get<std::string>("integrator", "MLT") == "MMLT";
    const MltSettings s = MltSettings::from_params(params, multiplexed);
    const EmitterSet emitters(scene.lights(), scene.bounds());
    const PathSpace space(scene, s.bdpt, emitters);
    RenderCounters counters;
    return summarise(run_bootstraps(space, s, multiplexed, s.bdpt.pixel.seed, threads, counters, nullptr));
}

}  // namespace candela
