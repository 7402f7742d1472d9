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
    std::string sampler = "RANDOM";
    PixelFilter filter{"BLACKMAN_HARRIS", 1.5f};
    bool film_transparent = false;

    static PixelSampling from_params(const Params& params);
};

}  // namespace candela
