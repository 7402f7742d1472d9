#include "integrators/light/light_settings.h"

#include "core/error.h"
#include "integrators/common/path_specs.h"
#include "scene/camera.h"

namespace candela {

const std::vector<ParamSpec>& LightSettings::specs() {
    static const std::vector<ParamSpec> specs = {max_bounces_spec(), rr_mode_spec(), rr_start_bounce_spec()};
    return specs;
}

LightSettings LightSettings::from_params(const Params& params) {
    const ParamReader read(params, specs());
    LightSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = read.get_int("max_bounces");
    s.rr_mode = parse_rr_mode(read.get_enum("rr_mode"));
    s.rr_start_bounce = read.get_int("rr_start_bounce");
    return s;
}

}  // namespace candela
