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
                  "Continuation rays at the first surface (stochastic ray tracing); 1 is path tracing", "Light Paths"),
        enum_param("hemisphere_sampling", "Hemisphere Sampling", "BSDF",
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
        active_if(enum_param("mis_heuristic", "MIS Heuristic", "POWER",
                             {{"BALANCE", "Balance", "Balance heuristic (Veach 1997, eq. 9.12)"},
                              {"POWER", "Power", "Power heuristic with exponent 2 (Veach 1997, eq. 9.13)"}},
                             "How the two estimators of direct light are weighted", "Light Sampling"),
                  "light_sampling==MIS"),
        enum_param("light_selection", "Light Selection", "TREE",
                   {{"ALL", "All", "Estimate every light at every vertex (one shadow ray per light)"},
                    {"UNIFORM", "Uniform", "Teaching option: pick one light uniformly"},
                    {"AREA", "Area", "Teaching option: pick one light in proportion to its emitting area"},
                    {"POWER", "Power", "Pick one light in proportion to its power (Cycles 3.4's rule)"},
                    {"TREE", "Light Tree",
                     "Pick one light by a light hierarchy with bounds and orientation cones (favours nearby, facing, "
                     "bright lights; scales to thousands of emitters)"},
                    {"WARD", "Ward",
                     "Pick lights in proportion to their maximum possible contribution at the point (Ward 1991)"}},
                   "How next-event estimation chooses among many lights", "Light Sampling"),
        active_if(float_param("ward_threshold", "Ward Threshold", 0.05, 0.0, 1e9,
                              "Light Selection WARD: shadow-test lights in order of their largest possible "
                              "contribution until the untested lights could add at most this fraction of the light "
                              "found; the rest is estimated by one sampled light (unbiased). 0 tests every light",
                              "Light Sampling", 1.0),
                  "light_selection==WARD"),
        enum_param("light_pdf", "Light PDF", "SOLID_ANGLE",
                   {{"AREA", "Area", "Teaching option: sample points uniformly on the emitter's area"},
                    {"SOLID_ANGLE", "Solid Angle",
                     "Sample directions uniformly in the solid angle the emitter covers (spherical triangles and "
                     "rectangles), with area sampling for tiny and huge solid angles"}},
                   "How a point on an area light or emissive triangle is chosen", "Light Sampling"),
        int_param("light_samples", "Light Samples", 1, 1, 256, "Shadow rays per path vertex (stratified)",
                  "Light Sampling"),
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
    s.hemisphere_sampling = hs == "UNIFORM" ? HemisphereSampling::Uniform
                            : hs == "COSINE" ? HemisphereSampling::Cosine : HemisphereSampling::Bsdf;
    const std::string ls = read.get_enum("light_sampling");
    s.direct.light_sampling = ls == "BSDF_ONLY" ? LightSampling::BsdfOnly
                              : ls == "LIGHT_ONLY" ? LightSampling::LightOnly : LightSampling::Mis;
    s.direct.mis_heuristic = read.get_enum("mis_heuristic") == "BALANCE" ? MisHeuristic::Balance : MisHeuristic::Power;
    s.direct.light_pdf = parse_light_pdf_mode(read.get_enum("light_pdf"));
    s.direct.light_samples = read.get_int("light_samples");
    s.direct.ward_threshold = read.get_float("ward_threshold");
    s.light_selection = read.get_enum("light_selection");
    s.branching_factor = read.get_int("branching_factor");
    return s;
}

}  // namespace candela
