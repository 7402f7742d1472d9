// Camera-sample settings shared by every integrator that traces from the camera.
#pragma once

#include <cstdint>
#include <string>

#include "core/params.h"
#include "film/pixel_filter.h"
#include "sampling/sampler.h"

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

    /// The sampler of one noise replicate (film/noise_estimate.h): pixel sample s is drawn as sample
    /// index_in_replicate(s) of replicate noise_replicate_of(s), whose randomisation (scrambles, permutations,
    /// jitter) is seeded by (seed, replicate) and whose point set holds that replicate's share of `samples`.
    /// Replicates are thus independent realisations of the sampler, which is what makes the error estimate
    /// honest under stratified and QMC sampling.
    Sampler replicate_sampler(uint32_t replicate) const;
};

}  // namespace candela
