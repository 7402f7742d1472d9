#include "integrators/pixel_sampling.h"

#include <algorithm>

#include "core/error.h"
#include "core/rng.h"
#include "film/noise_estimate.h"

namespace candela {

PixelSampling PixelSampling::from_params(const Params& params) {
    PixelSampling s;
    s.samples = params.get<int>("samples", 64);
    if (s.samples < 1 || s.samples > (1 << 24)) throw InvalidParameter("samples must be between 1 and 16777216");
    s.seed = static_cast<uint64_t>(params.get<int64_t>("seed", 0));
    s.sampler = params.get_enum("sampler", "SOBOL", sampler_names());
    s.filter = PixelFilter(params.get_enum("pixel_filter", "BLACKMAN_HARRIS", PixelFilter::names()),
                           params.get<float>("filter_width", 1.5f));
    s.film_transparent = params.get<bool>("film_transparent", false);
    s.time_limit = params.get<double>("time_limit", 0.0);
    s.noise_threshold = params.get<double>("noise_threshold", 0.0);
    if (s.time_limit < 0.0) throw InvalidParameter("time_limit must not be negative (0 = no limit)");
    if (s.noise_threshold < 0.0 || s.noise_threshold >= 1.0)
        throw InvalidParameter("noise_threshold must be in [0, 1) (a relative error; 0 = off)");
    return s;
}

Sampler PixelSampling::replicate_sampler(uint32_t replicate) const {
    // Sample indices s < samples with s mod B = replicate.
    const int share = (samples - int(replicate) + int(k_noise_replicates) - 1) / int(k_noise_replicates);
    return make_sampler(sampler, hash_values(seed, replicate, 0x7265706c6963ULL /* "replic" */), std::max(share, 1));
}

}  // namespace candela
