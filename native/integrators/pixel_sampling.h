// Camera-sample settings shared by every integrator that traces from the camera.
#pragma once

#include <cstdint>
#include <string>

#include "core/params.h"
#include "film/pixel_filter.h"

namespace candela {

struct PixelSampling {
    int samples = 64;
    uint64_t seed = 0;
    std::string sampler = "SOBOL";
    PixelFilter filter{"BLACKMAN_HARRIS", 1.5f};
    bool film_transparent = false;
    double time_limit = 0.0;       // seconds of rendering (after the scene is built); 0 = no limit
    double noise_threshold = 0.0;  // stop once the estimated relative RMSE is below it; 0 = off

    static PixelSampling from_params(const Params& params);
};

}  // namespace candela
