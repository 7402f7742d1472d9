#include "integrators/photon_map/photon_integrator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "integrators/camera_tiles.h"
#include "integrators/photon_map/caustic_emission.h"
#include "integrators/photon_map/photon_camera.h"
#include "integrators/photon_map/photon_settings.h"
#include "integrators/photon_map/photon_shooting.h"
#include "integrators/photon_map/sppm.h"
#include "integrators/photon_map/sppm_gather.h"
#include "integrators/progressive_driver.h"
#include "lights/light_sampler.h"
#include "scene/shutter_time.h"

namespace candela {

namespace {

std::string millions(double n) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f M", n / 1e6);
    return buf;
}

/// The maps of one render (still) or of one shutter pass (motion blur), shot and built at the thread's shutter time.
struct PhotonMaps {
    PhotonMap global, caustic;
};

/// The aimed caustic emission toward the analysis' targets (null if there is none to aim at).
std::unique_ptr<CausticEmission> aim(const EmitterSet& emitters, const CausticAnalysis& analysis) {
    if (!analysis.any_traced_material || analysis.targets.empty()) return nullptr;
    auto aimed = std::make_unique<CausticEmission>(emitters, analysis.targets);
    return aimed->empty() ? nullptr : std::move(aimed);
}

/// Shoots `n_global` photon paths into the global map and, if `aimed`, `n_caustic` aimed ones into the caustic map,
/// from streams `stream` and `stream` + 1 of the seed. Throws Cancelled.
PhotonMaps shoot_maps(const PhotonTracer& tracer, const EmitterSet& emitters, bool aimed, int64_t n_global,
                      int64_t n_caustic, uint64_t seed, uint32_t stream, RenderContext& ctx) {
    PhotonMaps maps;
    maps.global = build_photon_map(
        shoot_photons(tracer, emitters, PhotonStore::Global, n_global, seed, stream, ctx, "Tracing photons"), ctx,
        "Building photon map");
    if (aimed)
        maps.caustic = build_photon_map(shoot_photons(tracer, emitters, PhotonStore::Caustic, n_caustic, seed,
                                                      stream + 1, ctx, "Tracing caustic photons"),
                                        ctx, "Building caustic map");
    return maps;
}

/// What each shutter pass of a moving scene shoots and estimates with (render_moving). T passes, one camera sample
/// per pixel each (T = Samples), each with maps of its own time. The still render's k nearest of N photon paths
/// give a radius r with πr² ∝ k/N, which sets the density estimate's bias (docs/photon-mapping.md, "Kernels and
/// their bias"), and a noise of one k-photon estimate frozen into the image. A pass with N_t paths and k_t nearest
/// keeps r — so the bias law — wherever k_t/N_t = k/N, and the T independent passes' average holds T·k_t photons'
/// worth of noise. So k_t = ⌈k/T⌉ and N_t = N/T while that is at least k_min = 8 (the k-nearest estimate's relative
/// variance is 1/(k − 2): 1/6 at 8, against 1/48 at the default 50; averaging passes divides it by T): the same
/// photon paths, bias and map noise as the still render. More passes keep k_t = k_min and N_t = N·k_min/k, so the
/// bias law still holds and the map noise only falls (T·k_min > k), at T·k_min/k times the still render's photon
/// paths. k ≤ k_min is kept for every pass (N_t = N).
struct ShutterPassBudget {
    int k = 0;
    int64_t global = 0, caustic = 0;  // photon paths per pass
    double photon_cost = 1.0;         // the passes' photon paths over the still render's
};
ShutterPassBudget shutter_pass_budget(const PhotonSettings& cfg, int64_t passes, double frame_pixels) {
    constexpr int k_min = 8;
    ShutterPassBudget b;
    const int64_t k_share = (int64_t(cfg.k) + passes - 1) / passes;
    b.k = cfg.k <= k_min ? cfg.k : int(std::max<int64_t>(k_min, k_share));
    const double share = double(b.k) / double(cfg.k);
    b.global = std::max<int64_t>(1, int64_t(std::ceil(double(cfg.resolve_global(frame_pixels)) * share)));
    b.caustic = std::max<int64_t>(1, int64_t(std::ceil(double(cfg.resolve_caustic(frame_pixels)) * share)));
    b.photon_cost = double(passes) * share;
    return b;
}

class PhotonIntegrator final : public Integrator {
public:
    explicit PhotonIntegrator(const Params& params) : m_settings(PhotonSettings::from_params(params)) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        const PhotonSettings& cfg = m_settings;
        const EmitterSet emitters(scene.lights(), scene.bounds());
        const double frame_pixels = double(scene.camera().full_width()) * scene.camera().full_height();
        const float radius = cfg.resolve_radius(scene.bounds().radius);
        PhotonRules rules;
        rules.max_bounces = cfg.max_bounces;
        rules.alpha_threshold = cfg.alpha_threshold();

        // Only what the scene calls for: a caustic map only if some surface has traced lobes.
        const CausticAnalysis analysis = analyse_caustics(scene, cfg.alpha_threshold());
        if (scene.has_motion()) return render_moving(scene, film, ctx, emitters, rules, analysis, radius);
        const std::unique_ptr<CausticEmission> aimed = aim(emitters, analysis);
        PhotonMaps maps;
        try {
            const PhotonTracer tracer(scene, emitters, rules, aimed.get());
            const int64_t n_global = cfg.resolve_global(frame_pixels), n_caustic = cfg.resolve_caustic(frame_pixels);
            maps = shoot_maps(tracer, emitters, aimed != nullptr, n_global, n_caustic, cfg.pixel.seed, 0, ctx);
            ctx.info("PHOTON: global map of " + millions(double(maps.global.size())) + " photons from " +
                     millions(double(n_global)) + " paths (" + std::to_string(int(maps.global.memory_bytes() / 1e6)) +
                     " MB)");
            if (aimed)
                ctx.info("PHOTON: caustic map of " + millions(double(maps.caustic.size())) + " photons from " +
                         millions(double(n_caustic)) + " paths aimed at " + std::to_string(analysis.targets.size()) +
                         (analysis.merged ? " merged" : "") + " specular object bound(s)");
            else
                log_no_caustic_map(analysis, ctx);
        } catch (const Cancelled&) {
            ctx.counters.stage.end();
            ctx.counters.stop_reason = int(StopReason::Cancelled);
            return;
        }
        ctx.counters.stage.end();
        const LightSampler light_sampler = make_light_sampler("TREE", scene.lights());
        const PhotonCameraTracer tracer(scene, cfg, light_sampler, maps.global, maps.caustic, radius);
        render_camera_progressive(scene, film, ctx, cfg.pixel, tracer);
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "sample"}; }
    // Motion blur: one shutter time per pass, with maps of that time (render_moving).
    uint32_t honoured_features() const override { return k_feature_motion_blur; }

private:
    static void log_no_caustic_map(const CausticAnalysis& analysis, RenderContext& ctx) {
        ctx.info(std::string("PHOTON: no caustic map: ") +
                 (analysis.any_traced_material ? "no object uses the mirror, glass or narrow glossy materials"
                                               : "no mirror, glass or narrow glossy material in the scene"));
    }

    /// Motion blur: the samples are rendered as T = Samples shutter passes. Pass j sees the scene at one time τ_j
    /// (stratified_shutter_time: one τ in each 1/T of the shutter), shoots its maps then (shutter_pass_budget; the
    /// caustic targets too if a traced object moves) and renders sample j of every pixel then, so no photon is
    /// gathered at a camera vertex of another time; the film's mean over the passes is the time average. One
    /// pass's maps exist at a time (memory: at most the still render's).
    void render_moving(const Scene& scene, Film& film, RenderContext& ctx, const EmitterSet& emitters,
                       const PhotonRules& rules, const CausticAnalysis& analysis, float radius) const {
        const PhotonSettings& cfg = m_settings;
        const int64_t passes = cfg.pixel.samples;
        const ShutterPassBudget budget =
            shutter_pass_budget(cfg, passes, double(scene.camera().full_width()) * scene.camera().full_height());
        PhotonSettings pass_cfg = cfg;
        pass_cfg.k = budget.k;
        const std::unique_ptr<CausticEmission> still_aimed = analysis.moving ? nullptr : aim(emitters, analysis);
        const bool caustics = analysis.moving ? aim(emitters, analysis) != nullptr : still_aimed != nullptr;
        char cost[32];
        std::snprintf(cost, sizeof cost, "%.2f", budget.photon_cost);
        ctx.info("PHOTON: motion blur: " + std::to_string(passes) +
                 " shutter passes of one sample per pixel, each with maps of its own time from " +
                 millions(double(budget.global)) + " global" +
                 (caustics ? " and " + millions(double(budget.caustic)) + " caustic" : std::string()) +
                 " photon paths, estimates of the " + std::to_string(budget.k) + " nearest (photon paths " + cost +
                 "x the still render's)");
        if (!caustics) log_no_caustic_map(analysis, ctx);
        const LightSampler light_sampler = make_light_sampler("TREE", scene.lights());
        const uint64_t time_key = hash_combine(cfg.pixel.seed, 0x70686f746f6d62ULL);
        ProgressivePlan plan;
        plan.total = passes;
        plan.max_pass = camera_max_pass(film, cfg.pixel);
        plan.time_limit = cfg.pixel.time_limit;
        plan.noise_threshold = cfg.pixel.noise_threshold;
        run_progressive(
            ctx, plan,
            [&](int64_t begin, int64_t end) {
                for (int64_t j = begin; j < end && !ctx.cancel.cancelled(); ++j) {
                    const float time = stratified_shutter_time(time_key, uint64_t(j), uint64_t(passes));
                    PhotonMaps maps;
                    try {
                        const ShutterScope scope(time);
                        std::unique_ptr<CausticEmission> moved_aimed;
                        if (analysis.moving)
                            moved_aimed = aim(emitters, analyse_caustics(scene, cfg.alpha_threshold()));
                        const CausticEmission* aimed = analysis.moving ? moved_aimed.get() : still_aimed.get();
                        const PhotonTracer tracer(scene, emitters, rules, aimed);
                        maps = shoot_maps(tracer, emitters, aimed != nullptr, budget.global, budget.caustic,
                                          cfg.pixel.seed, 2 + 2 * uint32_t(j), ctx);
                    } catch (const Cancelled&) {
                        ctx.counters.stage.end();
                        return;  // the driver sees the cancel
                    }
                    ctx.counters.stage.end();
                    const PhotonCameraTracer tracer(scene, pass_cfg, light_sampler, maps.global, maps.caustic, radius);
                    const CameraTilePass<PhotonCameraTracer> tiles(scene, film, ctx, cfg.pixel, tracer);
                    parallel_for(
                        ctx.threads, film.tiles().size(),
                        [&](size_t t) {
                            const ShutterScope scope(time);
                            tiles.render_tile(t, int(j), int(j) + 1);
                        },
                        &ctx.cancel);
                }
            },
            [&] { return film.noise_estimate(); });
    }

    PhotonSettings m_settings;
};

class SppmIntegrator final : public Integrator {
public:
    explicit SppmIntegrator(const Params& params) : m_settings(SppmSettings::from_params(params)) {}
    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        render_sppm(m_settings, scene, film, ctx);
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "iteration"}; }
    // Motion blur: one shutter time per iteration, shared by its camera pass and photons (sppm.cpp).
    uint32_t honoured_features() const override { return k_feature_motion_blur; }

private:
    SppmSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_sppm_integrator(const Params& params) {
    return std::make_unique<SppmIntegrator>(params);
}

double sppm_integrator_memory(const Params& params, double film_pixels) {
    const SppmSettings s = SppmSettings::from_params(params);
    const double photons = double(s.resolve_photons(film_pixels)) * k_stored_per_path * k_photon_bytes;
    const double limit_mb = params.get<double>("memory_limit_mb", 0.0);
    if (limit_mb > 0.0 && photons > limit_mb * 1e6)
        throw InvalidParameter(
            "integrator SPPM: the photon map of sppm_photons = " + std::to_string(s.resolve_photons(film_pixels)) +
            " per iteration needs about " + std::to_string(int(photons / 1e6)) +
            " MB, more than memory_limit_mb = " + std::to_string(int(limit_mb)) + ": lower Photons per Iteration");
    return photons + film_pixels * sppm_bytes_per_pixel() + k_gather_round_bytes;
}

std::unique_ptr<Integrator> make_photon_integrator(const Params& params) {
    return std::make_unique<PhotonIntegrator>(params);
}

double photon_integrator_memory(const Params& params, double film_pixels) {
    const PhotonSettings s = PhotonSettings::from_params(params);
    const double global = double(s.resolve_global(film_pixels)) * k_stored_per_path * k_photon_bytes;
    const double caustic = double(s.resolve_caustic(film_pixels)) * k_photon_bytes;  // at most one per path, mostly
    const double limit_mb = params.get<double>("memory_limit_mb", 0.0);
    if (limit_mb > 0.0 && global + caustic > limit_mb * 1e6)
        throw InvalidParameter(
            "integrator PHOTON: the photon maps of global_photons = " + std::to_string(s.resolve_global(film_pixels)) +
            " and caustic_photons = " + std::to_string(s.resolve_caustic(film_pixels)) + " need about " +
            std::to_string(int((global + caustic) / 1e6)) + " MB, more than memory_limit_mb = " +
            std::to_string(int(limit_mb)) + ": lower Global Photons or Caustic Photons");
    return global + caustic;
}

}  // namespace candela
