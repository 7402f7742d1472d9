// Published settings several integrators share (core/param_spec.h): one definition each, so the add-on's one
// property per key means the same thing for every integrator that reads it.
#pragma once

#include "core/param_spec.h"
#include "integrators/common/roulette.h"

namespace candela {

inline ParamSpec max_bounces_spec() {
    return int_param("max_bounces", "Max Bounces", 12, 0, 1024, "Maximum path length; 0 = direct light only",
                     "Light Paths");
}

inline ParamSpec rr_mode_spec() {
    return enum_param("rr_mode", "Russian Roulette", "THROUGHPUT",
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

}  // namespace candela
