// Settings of the irradiance cache integrator (plain struct, read once from params). Names are the add-on's
// identifiers; docs/irradiance_cache.md explains each.
#pragma once

#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/common/direct_light.h"
#include "integrators/pixel_sampling.h"

namespace candela {

struct IcSettings {
    PixelSampling pixel;
    int max_bounces = 12;      // path length, counted from the camera for camera paths, from the record for gathers
    float error = 0.2f;        // Ward's a
    int gather_rays = 1024;    // M × N ≈ this, N ≈ πM
    float min_spacing = 1.5f;  // validity radius a·R_i clamped to [min, max] pixel footprints (Tabellion &
    float max_spacing = 20.f;  // Lamorlette 2004); min 0 = no lower clamp
    bool gradients = true;     // Ward & Heckbert's gradients in the interpolation
    bool neighbour_clamping = true;  // Křivánek et al. 2006
    bool reuse_at_bounces = true;    // Radiance's way: gather paths read the cache at their diffuse vertices
    // Fixed rules (not published): next-event estimation as PATH's defaults, roulette THROUGHPUT from bounce 3.
    DirectLightRules direct;
    int rr_start_bounce = 3;

    static IcSettings from_params(const Params& params);
    /// The IRRADIANCE_CACHE integrator's own settings (besides common_param_specs()).
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
