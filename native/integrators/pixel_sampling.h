// Camera-sample settings shared by every integrator: the budget, the sampler, the pixel filter, the film's
// transparency and the stopping rules. Published as common_param_specs() (core/param_spec.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "film/pixel_filter.h"
#include "sampling/sampler.h"

namespace candela {

struct PixelSampling {
    int samples = 64;  // the budget in the integrator's unit (camera samples per pixel for PATH)
    uint64_t seed = 0;
    std::string sampler = "SOBOL";
    PixelFilter filter{"BLACKMAN_HARRIS", 1.5f};
    bool film_transparent = false;
    bool transparent_glass = false;      // Film > Transparent Glass: the background stays transparent through smooth
    float transparent_roughness = 0.1f;  // refractions of α up to this (Cycles' roughness threshold)
    double time_limit = 0.0;             // seconds of rendering (after the scene is built); 0 = no limit
    double noise_threshold = 0.0;        // stop once the estimated relative RMSE is below it; 0 = off

    static PixelSampling from_params(const Params& params);

    /// The sampler of one noise replicate (film/noise_estimate.h): pixel sample s is drawn as sample
    /// index_in_replicate(s) of replicate noise_replicate_of(s), whose randomisation (scrambles, permutations,
    /// jitter) is seeded by (seed, replicate) and whose point set holds that replicate's share of `samples`.
    /// Replicates are thus independent realisations of the sampler, which is what makes the error estimate
    /// honest under stratified and QMC sampling.
    Sampler replicate_sampler(uint32_t replicate) const;
};

/// The settings every integrator reads (PixelSampling's), published beside each integrator's own.
const std::vector<ParamSpec>& common_param_specs();

}  // namespace candela
