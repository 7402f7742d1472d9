// Settings of the light tracer (plain struct, read once from params). Names are the add-on's identifiers.
#pragma once

#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/common/roulette.h"
#include "integrators/pixel_sampling.h"

namespace candela {

struct LightSettings {
    PixelSampling pixel;  // samples: light paths per pixel (and camera samples of the specular pass)
    int max_bounces = 12;
    RouletteMode rr_mode = RouletteMode::Throughput;
    int rr_start_bounce = 3;

    static LightSettings from_params(const Params& params);
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
