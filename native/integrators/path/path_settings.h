// Settings of the path tracer (plain struct, read once from params).
#pragma once

#include "core/params.h"
#include "integrators/pixel_sampling.h"

namespace candela {

struct PathSettings {
    PixelSampling pixel;
    int max_bounces = 12;      // 0 = direct lighting only
    int rr_start_bounce = 3;   // Russian roulette from this bounce on

    static PathSettings from_params(const Params& params);
};

}  // namespace candela
