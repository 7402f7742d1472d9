#include "integrators/photon_map/photon_integrator.h"

#include <cstdio>
#include <string>

#include "core/error.h"
#include "integrators/camera_tiles.h"
#include "integrators/photon_map/caustic_emission.h"
#include "integrators/photon_map/photon_camera.h"
#include "integrators/photon_map/photon_settings.h"
#include "integrators/photon_map/photon_shooting.h"
#include "integrators/photon_map/sppm.h"
#include "lights/light_sampler.h"

namespace candela {

namespace {

std::string millions(double n) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f M", n / 1e6);
    return buf;
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
        std::unique_ptr<CausticEmission> aimed;
        if (analysis.any_traced_material && !analysis.targets.empty()) {
            aimed = std::make_unique<CausticEmission>(emitters, analysis.targets);
            if (aimed->empty()) aimed.reset();
        }
        PhotonMap global, caustic;
        try {
            const PhotonTracer tracer(scene, emitters, rules, aimed.get());
            const int64_t n_global = cfg.resolve_global(frame_pixels);
            global = build_photon_map(shoot_photons(tracer, emitters, PhotonStore::Global, n_global, cfg.pixel.seed, 0,
                                                    ctx, "Tracing photons"),
                                      ctx, "Building photon map");
            ctx.log("PHOTON: global map of " + millions(double(global.size())) + " photons from " +
                    millions(double(n_global)) + " paths (" + std::to_string(int(global.memory_bytes() / 1e6)) +
                    " MB)");
            if (aimed) {
                const int64_t n_caustic = cfg.resolve_caustic(frame_pixels);
                caustic = build_photon_map(shoot_photons(tracer, emitters, PhotonStore::Caustic, n_caustic,
                                                         cfg.pixel.seed, 1, ctx, "Tracing caustic photons"),
                                           ctx, "Building caustic map");
                ctx.log("PHOTON: caustic map of " + millions(double(caustic.size())) + " photons from " +
                        millions(double(n_caustic)) + " paths aimed at " + std::to_string(analysis.targets.size()) +
                        (analysis.merged ? " merged" : "") + " specular object bound(s)");
            } else {
                ctx.log(std::string("PHOTON: no caustic map: ") +
                        (analysis.any_traced_material ? "no object uses the mirror, glass or narrow glossy materials"
                                                      : "no mirror, glass or narrow glossy material in the scene"));
            }
        } catch (const Cancelled&) {
            ctx.counters.stage.end();
            ctx.counters.stop_reason = int(StopReason::Cancelled);
            return;
        }
        ctx.counters.stage.end();
        const LightSampler light_sampler = make_light_sampler("TREE", scene.lights());
        const PhotonCameraTracer tracer(scene, cfg, light_sampler, global, caustic, radius);
        render_camera_progressive(scene, film, ctx, cfg.pixel, tracer);
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "sample"}; }

private:
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
    return photons + film_pixels * sppm_bytes_per_pixel();
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
