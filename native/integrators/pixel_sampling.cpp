#include "integrators/pixel_sampling.h"

#include <algorithm>

#include "core/error.h"
#include "core/rng.h"
#include "film/noise_estimate.h"

namespace candela {

const std::vector<ParamSpec>& common_param_specs() {
    static const std::vector<ParamSpec> specs = {
        int_param("samples", "Samples", 64, 1, 1 << 24, "Samples per pixel (the integrator's unit of work)", "", 4096),
        int_param("seed", "Seed", 0, 0, 2147483647, "The image depends only on the seed, pixel and sample index"),
        enum_param(
            "sampler", "Sampler", "SOBOL",
            {{"RANDOM", "Random", "Independent uniform random samples"},
             {"STRATIFIED", "Stratified (jittered)", "One jittered sample per stratum, strata shuffled per dimension"},
             {"NROOKS", "N-Rooks", "Latin hypercube: one sample per row and per column of every 2-D dimension"},
             {"HALTON", "Halton", "Halton sequence (prime bases), Owen-scrambled per pixel"},
             {"HAMMERSLEY", "Hammersley", "Hammersley point set for the sample count, Owen-scrambled per pixel"},
             {"SOBOL", "Sobol (Owen)", "Owen-scrambled, shuffled Sobol (0,2)-sequence per dimension pair"}},
            "Pattern of the sample values drawn per pixel"),
        enum_param("pixel_filter", "Pixel Filter", "BLACKMAN_HARRIS",
                   {{"BOX", "Box", "Box filter: every sample counts fully inside one pixel"},
                    {"GAUSSIAN", "Gaussian", "Gaussian filter"},
                    {"BLACKMAN_HARRIS", "Blackman-Harris", "Blackman-Harris filter, Cycles' default"}},
                   "Pixel reconstruction filter, applied by filter importance sampling"),
        float_param("filter_width", "Filter Width", 1.5, 0.01, 64.0, "Pixel filter width in pixels", "", 10.0),
        bool_param("film_transparent", "Transparent", false,
                   "Alpha 0 where the background is seen directly (premultiplied RGBA), as in Cycles"),
        bool_param("film_transparent_glass", "Transparent Glass", false,
                   "With a transparent film, the background seen through smooth glass and refraction stays "
                   "transparent (Cycles' Film > Transparent Glass)"),
        float_param("film_transparent_roughness", "Roughness Threshold", 0.1, 0.0, 1.0,
                    "Transparent Glass: refractions up to this roughness (squared, as Cycles compares it) count as "
                    "smooth"),
        float_param("time_limit", "Time Limit", 0.0, 0.0, 1e9,
                    "Stop rendering after this many seconds (after export and scene build), even if not all samples "
                    "are done; 0 = no limit. Renders then differ between machines",
                    "", 3600.0),
        float_param("noise_threshold", "Image Noise Stop", 0.0, 0.0, 0.5,
                    "Stop the whole render once the estimated relative error (RMSE / mean) of the whole image is below "
                    "this, with a confidence margin; 0 = off. Checked from 16 samples per pixel on. Not Cycles' Noise "
                    "Threshold, which is per-pixel adaptive sampling (typically 0.01): here 0.01 asks for 1 % error "
                    "over the whole image, a long render",
                    "", 0.1),
    };
    return specs;
}

PixelSampling PixelSampling::from_params(const Params& params) {
    const ParamReader read(params, common_param_specs());
    PixelSampling s;
    s.samples = read.get_int("samples");
    s.seed = static_cast<uint64_t>(read.get_int("seed"));
    s.sampler = read.get_enum("sampler");
    s.filter = PixelFilter(read.get_enum("pixel_filter"), read.get_float("filter_width"));
    s.film_transparent = read.get_bool("film_transparent");
    s.transparent_glass = read.get_bool("film_transparent_glass");
    s.transparent_roughness = read.get_float("film_transparent_roughness");
    s.time_limit = read.get_double("time_limit");
    s.noise_threshold = read.get_double("noise_threshold");
    return s;
}

Sampler PixelSampling::replicate_sampler(uint32_t replicate) const {
    // Sample indices s < samples with s mod B = replicate.
    const int share = (samples - int(replicate) + int(k_noise_replicates) - 1) / int(k_noise_replicates);
    return make_sampler(sampler, hash_values(seed, replicate, 0x7265706c6963ULL /* "replic" */), std::max(share, 1));
}

}  // namespace candela
