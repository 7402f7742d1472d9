// Settings of the path tracer (plain struct, read once from params). Names are the add-on's identifiers.
#pragma once

#include <string>
#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/light_paths.h"
#include "integrators/common/roulette.h"
#include "integrators/pixel_sampling.h"

namespace candela {

/// How the continuation direction is drawn for non-delta BSDFs (delta lobes are always sampled exactly).
enum class HemisphereSampling { Uniform, Cosine, Bsdf };

struct PathSettings {
    PixelSampling pixel;
    LightPathSettings paths;  // bounce budget (max_bounces: 0 = direct lighting only), clamps, caustics
    int max_bounces = 12;     // = paths.max_bounces
    int rr_start_bounce = 3;  // Russian roulette from this bounce on
    RouletteMode rr_mode = RouletteMode::Throughput;
    HemisphereSampling hemisphere_sampling = HemisphereSampling::Bsdf;
    DirectLightRules direct;               // light sampling, MIS heuristic, light pdf, light samples, Ward's threshold
    std::string light_selection = "TREE";  // registry name of the light-selection strategy
    int branching_factor = 1;              // continuation rays at the first surface (stochastic ray tracing)

    static PathSettings from_params(const Params& params);
    /// The PATH integrator's own settings (besides common_param_specs()), as the add-on draws them.
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
