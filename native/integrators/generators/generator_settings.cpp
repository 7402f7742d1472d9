#include "integrators/generators/generator_settings.h"

#include "integrators/common/path_specs.h"

namespace candela {

const char* path_generator_name(PathGenerator g) {
    switch (g) {
    case PathGenerator::SurfaceSampling: return "SURFACE_SAMPLING";
    case PathGenerator::SourceShooting: return "SOURCE_SHOOTING";
    case PathGenerator::ReceiverGathering: return "RECEIVER_GATHERING";
    }
    return "?";
}

const std::vector<ParamSpec>& GeneratorSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        max_bounces_spec(),
        rr_mode_spec(),
        rr_start_bounce_spec(),
        bool_param("generators_mis", "Combine Generators", false,
                   "Estimate the one-bounce indirect light (light → surface → visible point) by all three path "
                   "generators and weight them by multiple importance sampling; longer paths stay this generator's",
                   "Path Generator"),
        active_if(
            enum_param("generators_heuristic", "Generator Weights", "BALANCE",
                       {{"BALANCE", "Balance", "Balance heuristic over the three generators (Veach 1997, eq. 9.12)"},
                        {"POWER", "Power", "Power heuristic with exponent 2 over the three generators"}},
                       "How the three generators' estimates of a one-bounce path are weighted", "Path Generator"),
            "generators_mis==True"),
        light_selection_spec(),
        ward_threshold_spec(),
        light_pdf_spec(),
        light_samples_spec(),
    };
    return specs;
}

GeneratorSettings GeneratorSettings::from_params(const Params& params, PathGenerator generator) {
    const ParamReader read(params, specs());
    GeneratorSettings s;
    s.generator = generator;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = read.get_int("max_bounces");
    s.rr_mode = parse_rr_mode(read.get_enum("rr_mode"));
    s.rr_start_bounce = read.get_int("rr_start_bounce");
    s.combine = read.get_bool("generators_mis");
    s.combine_heuristic =
        read.get_enum("generators_heuristic") == "POWER" ? MisHeuristic::Power : MisHeuristic::Balance;
    s.direct.light_sampling = LightSampling::Mis;
    read_light_sampling_specs(read, &s.direct, &s.light_selection);
    s.direct.mis_heuristic = MisHeuristic::Power;  // the path tracer's default (its setting is PATH's own)
    return s;
}

}  // namespace candela
