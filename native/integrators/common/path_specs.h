// Published settings several integrators share (core/param_spec.h): one definition each, so the add-on's one
// property per key means the same thing for every integrator that reads it.
#pragma once

#include <string>

#include "core/param_spec.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/roulette.h"
#include "lights/light_sample.h"

namespace candela {

inline ParamSpec max_bounces_spec() {
    return int_param("max_bounces", "Max Bounces", 12, 0, 1024, "Maximum path length; 0 = direct light only",
                     "Light Paths");
}

inline ParamSpec rr_mode_spec() {
    return enum_param(
        "rr_mode", "Russian Roulette", "THROUGHPUT",
        {{"OFF", "Off", "No Russian roulette: paths end at Max Bounces only"},
         {"THROUGHPUT", "Throughput", "Survival probability from the path throughput"},
         {"ALBEDO", "Albedo", "Survival probability from the surface's reflectance"},
         {"SQRT_THROUGHPUT", "Square Root Throughput",
          "Cycles' rule: on arrival at a vertex, continue with probability √(max throughput); paths live "
          "longer than with Throughput. Cycles' Min Light Bounces m matches Russian Roulette From m + 2"}},
        "How paths are ended before Max Bounces without bias", "Light Paths");
}

inline ParamSpec rr_start_bounce_spec() {
    return active_if(int_param("rr_start_bounce", "Russian Roulette From", 3, 0, 1024,
                               "Russian roulette from this bounce on", "Light Paths"),
                     "rr_mode!=OFF");
}

inline RouletteMode parse_rr_mode(const std::string& rr) {
    return rr == "OFF"               ? RouletteMode::Off
           : rr == "ALBEDO"          ? RouletteMode::Albedo
           : rr == "SQRT_THROUGHPUT" ? RouletteMode::SqrtThroughput
                                     : RouletteMode::Throughput;
}

/// The MIS heuristic of direct light (next-event estimation against BSDF sampling), active under `condition`.
inline ParamSpec mis_heuristic_spec(const char* condition) {
    return active_if(enum_param("mis_heuristic", "MIS Heuristic", "POWER",
                                {{"BALANCE", "Balance", "Balance heuristic (Veach 1997, eq. 9.12)"},
                                 {"POWER", "Power", "Power heuristic with exponent 2 (Veach 1997, eq. 9.13)"}},
                                "How the two estimators of direct light are weighted", "Light Sampling"),
                     condition);
}

inline ParamSpec light_selection_spec() {
    return enum_param(
        "light_selection", "Light Selection", "TREE",
        {{"ALL", "All", "Estimate every light at every vertex (one shadow ray per light)"},
         {"UNIFORM", "Uniform", "Teaching option: pick one light uniformly"},
         {"AREA", "Area", "Teaching option: pick one light in proportion to its emitting area"},
         {"POWER", "Power", "Pick one light in proportion to its power (Cycles 3.4's rule)"},
         {"TREE", "Light Tree",
          "Pick one light by a light hierarchy with bounds and orientation cones (favours nearby, facing, "
          "bright lights; scales to thousands of emitters)"},
         {"WARD", "Ward", "Pick lights in proportion to their maximum possible contribution at the point (Ward 1991)"}},
        "How next-event estimation chooses among many lights", "Light Sampling");
}

inline ParamSpec ward_threshold_spec() {
    return active_if(float_param("ward_threshold", "Ward Threshold", 0.05, 0.0, 1e9,
                                 "Light Selection WARD: shadow-test lights in order of their largest possible "
                                 "contribution until the untested lights could add at most this fraction of the light "
                                 "found; the rest is estimated by one sampled light (unbiased). 0 tests every light",
                                 "Light Sampling", 1.0),
                     "light_selection==WARD");
}

inline ParamSpec light_pdf_spec() {
    return enum_param("light_pdf", "Light PDF", "SOLID_ANGLE",
                      {{"AREA", "Area", "Teaching option: sample points uniformly on the emitter's area"},
                       {"SOLID_ANGLE", "Solid Angle",
                        "Sample directions uniformly in the solid angle the emitter covers (spherical triangles and "
                        "rectangles), with area sampling for tiny and huge solid angles"}},
                      "How a point on an area light or emissive triangle is chosen", "Light Sampling");
}

inline ParamSpec light_samples_spec() {
    return int_param("light_samples", "Light Samples", 1, 1, 256, "Shadow rays per path vertex (stratified)",
                     "Light Sampling");
}

/// Reads the next-event settings of the specs above (light_pdf, light_samples, ward_threshold, light_selection)
/// into `direct` and `selection`; light_sampling and mis_heuristic are the caller's.
inline void read_light_sampling_specs(const ParamReader& read, DirectLightRules* direct, std::string* selection) {
    direct->light_pdf = parse_light_pdf_mode(read.get_enum("light_pdf"));
    direct->light_samples = read.get_int("light_samples");
    direct->ward_threshold = read.get_float("ward_threshold");
    *selection = read.get_enum("light_selection");
}

}  // namespace candela
