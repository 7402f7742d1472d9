// Settings of the path tracer (plain struct, read once from params). Names are the add-on's identifiers.
#pragma once

#include <string>
#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/pixel_sampling.h"
#include "lights/light_sample.h"

namespace candela {

/// How the continuation direction is drawn for non-delta BSDFs (delta lobes are always sampled exactly).
enum class HemisphereSampling { Uniform, Cosine, Bsdf };
/// Which estimators of direct light run: BSDF sampling only (delta lights excepted: nothing can hit them),
/// next-event estimation only, or both combined by multiple importance sampling.
enum class LightSampling { BsdfOnly, LightOnly, Mis };
enum class MisHeuristic { Balance, Power };
/// Russian roulette: off (max_bounces only), survival by path throughput or by the surface's albedo (both
/// decided for the continuation ray leaving a vertex), or Cycles' rule: on arrival at a vertex, before its
/// shadow rays, survival √(max throughput) (Cycles 3.4, path_state_continuation_probability).
enum class RouletteMode { Off, Throughput, Albedo, SqrtThroughput };

struct PathSettings {
    PixelSampling pixel;
    int max_bounces = 12;           // 0 = direct lighting only
    int rr_start_bounce = 3;        // Russian roulette from this bounce on
    RouletteMode rr_mode = RouletteMode::Throughput;
    HemisphereSampling hemisphere_sampling = HemisphereSampling::Bsdf;
    LightSampling light_sampling = LightSampling::Mis;
    MisHeuristic mis_heuristic = MisHeuristic::Power;
    LightPdfMode light_pdf = LightPdfMode::SolidAngle;  // how a point on an area-like emitter is drawn
    std::string light_selection = "TREE";  // registry name of the light-selection strategy
    int light_samples = 1;          // shadow rays per vertex (stratified)
    int branching_factor = 1;       // continuation rays at the first surface (stochastic ray tracing)
    float clamp_indirect = 0.f;     // > 0: clamp indirect contributions' max component (biased); 0 = off
    float ward_threshold = 0.05f;   // WARD: stop shadow-testing once the untested bound ≤ this × the tested light

    static PathSettings from_params(const Params& params);
    /// The PATH integrator's own settings (besides common_param_specs()), as the add-on draws them.
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
