#include "integrators/photon_map/photon_settings.h"

#include <algorithm>

#include "integrators/common/path_specs.h"

namespace candela {

namespace {

ParamSpec traced_roughness_spec() {
    return float_param("traced_roughness", "Traced Roughness", k_default_traced_roughness, 0.0, 1.0,
                       "Glossy lobes with a roughness below this are ray traced instead of estimated from photons "
                       "(mirrors and smooth glass always are)",
                       "Photons");
}

}  // namespace

const std::vector<ParamSpec>& PhotonSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        max_bounces_spec(),
        int_param("global_photons", "Global Photons", 0, 0, 2000000000,
                  "Photon paths emitted for the global map; 0 = automatic (4 per pixel, at least 200 000)", "Photons",
                  10000000),
        int_param("caustic_photons", "Caustic Photons", 0, 0, 2000000000,
                  "Photon paths aimed at mirrors and glass for the caustic map; 0 = automatic (as many as global)",
                  "Photons", 10000000),
        int_param("photon_k", "Nearest Photons", 50, 1, 10000, "Photons per density estimate (k nearest)", "Photons",
                  500),
        float_param("photon_max_radius", "Max Radius", 0.0, 0.0, 1e9,
                    "Largest radius of a density estimate; 0 = automatic (2 % of the scene's size)", "Photons", 1.0),
        enum_param("photon_kernel", "Kernel", "CONE",
                   {{"BOX", "Box", "Uniform weight over the disc (bias −(3/4)(r/h)² under a point light)"},
                    {"CONE", "Cone", "Jensen's cone filter, weight 1 − d/r (bias −(9/20)(r/h)²)"},
                    {"GAUSSIAN", "Gaussian", "Jensen's Gaussian filter (bias −0.457(r/h)²)"}},
                   "How photons are weighted by their distance in a density estimate", "Photons"),
        int_param("final_gather_rays", "Final Gather Rays", 16, 1, 4096,
                  "Rays per camera sample that read the global map at their hits (indirect diffuse light)", "Photons",
                  256),
        float_param("gather_distance", "Gather Distance", 2.0, 0.0, 1e6,
                    "A final-gather hit closer than this many max radii is path traced one bounce further instead of "
                    "read from the global map (corners, close hits); 0 = never",
                    "Photons", 10.0),
        traced_roughness_spec(),
    };
    return specs;
}

PhotonSettings PhotonSettings::from_params(const Params& params) {
    const ParamReader read(params, specs());
    PhotonSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = read.get_int("max_bounces");
    s.global_photons = read.get_int("global_photons");
    s.caustic_photons = read.get_int("caustic_photons");
    s.k = read.get_int("photon_k");
    s.max_radius = read.get_float("photon_max_radius");
    s.kernel = parse_density_kernel(read.get_enum("photon_kernel"));
    s.final_gather_rays = read.get_int("final_gather_rays");
    s.gather_distance = read.get_float("gather_distance");
    s.traced_roughness = read.get_float("traced_roughness");
    return s;
}

int64_t PhotonSettings::resolve_global(double frame_pixels) const {
    return global_photons > 0 ? global_photons : std::max<int64_t>(200000, int64_t(4.0 * frame_pixels));
}
int64_t PhotonSettings::resolve_caustic(double frame_pixels) const {
    return caustic_photons > 0 ? caustic_photons : resolve_global(frame_pixels);
}

const std::vector<ParamSpec>& SppmSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        max_bounces_spec(),
        int_param("sppm_photons", "Photons per Iteration", 0, 0, 2000000000,
                  "Photon paths per iteration; 0 = automatic (one per pixel, at least 100 000)", "Photons", 10000000),
        float_param("sppm_radius", "Initial Radius", 0.0, 0.0, 1e9,
                    "Search radius of the first iteration; 0 = automatic (1 % of the scene's size)", "Photons", 1.0),
        float_param("sppm_alpha", "Alpha", 2.0 / 3.0, 0.01, 1.0,
                    "Share of new photons kept per iteration: the radius shrinks as iterations^((α−1)/2); 2/3 "
                    "balances bias and variance",
                    "Photons"),
        float_param("sppm_traced_roughness", "Traced Roughness", 0.0, 0.0, 1.0,
                    "Glossy lobes with a roughness below this are ray traced instead of estimated from photons; 0 "
                    "traces only mirrors and smooth glass (every other lobe then converges with the radius)",
                    "Photons"),
    };
    return specs;
}

SppmSettings SppmSettings::from_params(const Params& params) {
    const ParamReader read(params, specs());
    SppmSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = read.get_int("max_bounces");
    s.photons_per_iteration = read.get_int("sppm_photons");
    s.initial_radius = read.get_float("sppm_radius");
    s.alpha = read.get_float("sppm_alpha");
    s.traced_roughness = read.get_float("sppm_traced_roughness");
    return s;
}

int64_t SppmSettings::resolve_photons(double frame_pixels) const {
    return photons_per_iteration > 0 ? photons_per_iteration : std::max<int64_t>(100000, int64_t(frame_pixels));
}

}  // namespace candela
