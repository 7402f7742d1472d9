#include "integrators/pixel_sampling.h"

#include "core/error.h"
#include "sampling/sampler.h"

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

}  // namespace candela
