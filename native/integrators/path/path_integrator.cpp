#include "integrators/path/path_integrator.h"

#include <cmath>

#include "core/error.h"
#include "integrators/path/path_tracer.h"
#include "integrators/tile_renderer.h"
#include "lights/light_sampler.h"

namespace candela {

PathSettings PathSettings::from_params(const Params& params) {
    PathSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = params.get<int>("max_bounces", 12);
    s.rr_start_bounce = params.get<int>("rr_start_bounce", 3);
    if (s.max_bounces < 0 || s.max_bounces > 1024) throw InvalidParameter("max_bounces must be between 0 and 1024");
    if (s.rr_start_bounce < 0) throw InvalidParameter("rr_start_bounce must not be negative");
    const std::string rr = params.get_enum("rr_mode", "THROUGHPUT", {"OFF", "THROUGHPUT", "ALBEDO", "SQRT_THROUGHPUT"});
    s.rr_mode = rr == "OFF"               ? RouletteMode::Off
                : rr == "ALBEDO"          ? RouletteMode::Albedo
                : rr == "SQRT_THROUGHPUT" ? RouletteMode::SqrtThroughput
                                          : RouletteMode::Throughput;
    const std::string hs = params.get_enum("hemisphere_sampling", "BSDF", {"UNIFORM", "COSINE", "BSDF"});
    s.hemisphere_sampling = hs == "UNIFORM" ? HemisphereSampling::Uniform
                            : hs == "COSINE" ? HemisphereSampling::Cosine : HemisphereSampling::Bsdf;
    const std::string ls = params.get_enum("light_sampling", "MIS", {"BSDF_ONLY", "LIGHT_ONLY", "MIS"});
    s.light_sampling = ls == "BSDF_ONLY" ? LightSampling::BsdfOnly
                       : ls == "LIGHT_ONLY" ? LightSampling::LightOnly : LightSampling::Mis;
    s.mis_heuristic = params.get_enum("mis_heuristic", "POWER", {"BALANCE", "POWER"}) == "BALANCE"
                          ? MisHeuristic::Balance : MisHeuristic::Power;
    s.light_pdf = parse_light_pdf_mode(params.get_enum("light_pdf", "SOLID_ANGLE", {"AREA", "SOLID_ANGLE"}));
    s.light_selection = params.get_enum("light_selection", "TREE", light_selection_names());
    s.light_samples = params.get<int>("light_samples", 1);
    s.branching_factor = params.get<int>("branching_factor", 1);
    s.clamp_indirect = params.get<float>("clamp_indirect", 0.f);
    s.ward_threshold = params.get<float>("ward_threshold", 0.05f);
    if (s.light_samples < 1 || s.light_samples > 256) throw InvalidParameter("light_samples must be between 1 and 256");
    if (s.branching_factor < 1 || s.branching_factor > 256)
        throw InvalidParameter("branching_factor must be between 1 and 256");
    if (s.clamp_indirect < 0.f) throw InvalidParameter("clamp_indirect must not be negative (0 = off)");
    if (!(s.ward_threshold >= 0.f) || !std::isfinite(s.ward_threshold))
        throw InvalidParameter("ward_threshold must be a finite number ≥ 0 (0 = shadow-test every light)");
    return s;
}

namespace {

class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(const Params& params) : m_settings(PathSettings::from_params(params)) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        const LightSampler light_sampler = make_light_sampler(m_settings.light_selection, scene.lights());
        const PathTracer tracer(scene, m_settings, light_sampler);
        render_progressive(scene, film, ctx, m_settings.pixel, tracer);
    }
    int samples_per_pixel() const override { return m_settings.pixel.samples; }

private:
    PathSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator(const Params& params) {
    return std::make_unique<PathIntegrator>(params);
}

}  // namespace candela
