#include "integrators/path/path_settings.h"

#include "integrators/common/path_specs.h"
#include "lights/light_sampler.h"

namespace candela {

const std::vector<ParamSpec>& PathSettings::specs() {
    static const std::vector<ParamSpec> specs = [] {
        std::vector<ParamSpec> own = {
            max_bounces_spec(),
            rr_mode_spec(),
            rr_start_bounce_spec(),
            int_param("branching_factor", "Branching Factor", 1, 1, 256,
                      "Continuation rays at the first surface (stochastic ray tracing); 1 is path tracing",
                      "Light Paths"),
            enum_param(
                "hemisphere_sampling", "Hemisphere Sampling", "BSDF",
                {{"UNIFORM", "Uniform",
                  "Teaching option: continue paths in uniformly distributed directions over the hemisphere "
                  "(noisier than BSDF sampling)"},
                 {"COSINE", "Cosine",
                  "Teaching option: continue paths cosine-weighted over the hemisphere (noisier than BSDF sampling "
                  "on glossy surfaces)"},
                 {"BSDF", "BSDF", "Continue paths proportionally to the BSDF times the cosine (importance sampling)"}},
                "How continuation directions are drawn (delta lobes always use the BSDF)", "Light Paths"),
            enum_param("light_sampling", "Light Sampling", "MIS",
                       {{"BSDF_ONLY", "BSDF Only",
                         "Teaching option: direct light only where continuation rays hit emitters (point, spot and sun "
                         "lights are still light-sampled: no ray can hit them)"},
                        {"LIGHT_ONLY", "Light Only",
                         "Teaching option: direct light only by next-event estimation (shadow rays to sampled lights)"},
                        {"MIS", "Multiple Importance", "Both, combined by multiple importance sampling"}},
                       "Which estimators of direct light are used", "Light Sampling"),
            mis_heuristic_spec("light_sampling==MIS"),
            light_selection_spec(),
            ward_threshold_spec(),
            light_pdf_spec(),
            light_samples_spec(),
        };
        for (ParamSpec& p : LightPathSettings::specs()) own.push_back(std::move(p));
        return own;
    }();
    return specs;
}

PathSettings PathSettings::from_params(const Params& params) {
    const ParamReader read(params, specs());
    PathSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.paths = LightPathSettings::read(read);
    s.max_bounces = s.paths.max_bounces;
    s.rr_start_bounce = read.get_int("rr_start_bounce");
    s.rr_mode = parse_rr_mode(read.get_enum("rr_mode"));
    const std::string hs = read.get_enum("hemisphere_sampling");
    s.hemisphere_sampling = hs == "UNIFORM"  ? HemisphereSampling::Uniform
                            : hs == "COSINE" ? HemisphereSampling::Cosine
                                             : HemisphereSampling::Bsdf;
    const std::string ls = read.get_enum("light_sampling");
    s.direct.light_sampling = ls == "BSDF_ONLY"    ? LightSampling::BsdfOnly
                              : ls == "LIGHT_ONLY" ? LightSampling::LightOnly
                                                   : LightSampling::Mis;
    s.direct.mis_heuristic = read.get_enum("mis_heuristic") == "BALANCE" ? MisHeuristic::Balance : MisHeuristic::Power;
    read_light_sampling_specs(read, &s.direct, &s.light_selection);
    s.branching_factor = read.get_int("branching_factor");
    return s;
}

}  // namespace candela
