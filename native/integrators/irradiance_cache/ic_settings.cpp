#include "integrators/irradiance_cache/ic_settings.h"

#include <string>

#include "core/error.h"
#include "integrators/path/path_settings.h"

namespace candela {

namespace {

/// PATH's own spec of a key both integrators read (the add-on makes one property of it: it must be published alike).
ParamSpec path_spec(const char* key) {
    for (const ParamSpec& s : PathSettings::specs())
        if (std::string(s.key) == key) return s;
    throw InternalError(std::string("PATH publishes no '") + key + "'");
}

}  // namespace

const std::vector<ParamSpec>& IcSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        float_param("ic_error", "Error", 0.2, 1e-4, 1.0,
                    "Ward's a: a record is used where its error ‖x − x_i‖/R_i + √(1 − n·n_i) is below this. Smaller: "
                    "more records, less interpolation error (records grow about as 1/a²)",
                    "Irradiance Cache"),
        int_param("ic_gather_rays", "Gather Rays", 1024, 4, 65536,
                  "Rays of each record's stratified hemisphere gather (M × N cells, N ≈ πM); each ray's radiance is "
                  "path traced",
                  "Irradiance Cache", 4096),
        float_param("ic_min_spacing", "Min Spacing", 1.5, 0.0, 1000.0,
                    "Smallest validity radius of a record, in pixels at its distance (Tabellion & Lamorlette): keeps "
                    "corners and contact shadows from taking a record per pixel; 0 = no limit",
                    "Irradiance Cache", 20.0),
        float_param("ic_max_spacing", "Max Spacing", 20.0, 0.01, 100000.0,
                    "Largest validity radius of a record, in pixels at its distance: keeps open areas from being "
                    "covered by a few far-reaching records",
                    "Irradiance Cache", 200.0),
        bool_param("ic_gradients", "Gradients", true,
                   "Interpolate with Ward & Heckbert's rotational and translational irradiance gradients (smoother, "
                   "more accurate for the same records)",
                   "Irradiance Cache"),
        bool_param("ic_neighbour_clamping", "Neighbour Clamping", true,
                   "Limit a record's radius by its neighbours' (R_i ≤ R_j + ‖x_i − x_j‖, Křivánek et al.), so records "
                   "are not too sparse near contact shadows a gather missed",
                   "Irradiance Cache"),
        bool_param("ic_reuse_at_bounces", "Reuse at Later Bounces", true,
                   "Radiance's way: gather paths read the cache at diffuse surfaces instead of tracing on (faster; "
                   "adds the interpolation error of those records to the records that use them)",
                   "Irradiance Cache"),
        path_spec("max_bounces"),
    };
    return specs;
}

IcSettings IcSettings::from_params(const Params& params) {
    const ParamReader read(params, specs());
    IcSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = read.get_int("max_bounces");
    s.error = read.get_float("ic_error");
    s.gather_rays = read.get_int("ic_gather_rays");
    s.min_spacing = read.get_float("ic_min_spacing");
    s.max_spacing = read.get_float("ic_max_spacing");
    s.gradients = read.get_bool("ic_gradients");
    s.neighbour_clamping = read.get_bool("ic_neighbour_clamping");
    s.reuse_at_bounces = read.get_bool("ic_reuse_at_bounces");
    if (s.min_spacing > s.max_spacing)
        throw InvalidParameter("parameter 'ic_min_spacing' (Min Spacing) = " + std::to_string(s.min_spacing) +
                               " is larger than 'ic_max_spacing' (Max Spacing) = " + std::to_string(s.max_spacing));
    return s;
}

}  // namespace candela
