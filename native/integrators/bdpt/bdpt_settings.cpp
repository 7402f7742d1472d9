#include "integrators/bdpt/bdpt_settings.h"

#include "integrators/common/path_specs.h"

namespace candela {

const std::vector<ParamSpec>& BdptSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        max_bounces_spec(),
        rr_mode_spec(),
        rr_start_bounce_spec(),
        enum_param("bdpt_mis", "Strategy Weights", "POWER",
                   {{"BALANCE", "Balance", "Balance heuristic over all strategies (Veach 1997, eq. 10.9 with β = 1)"},
                    {"POWER", "Power", "Power heuristic with exponent 2 over all strategies (Veach 1997, ch. 10)"}},
                   "How the estimates of all (s, t) strategies of a path are weighted", "Bidirectional"),
    };
    return specs;
}

BdptSettings BdptSettings::from_params(const Params& params) {
    const ParamReader read(params, specs());
    BdptSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = read.get_int("max_bounces");
    s.rr_mode = parse_rr_mode(read.get_enum("rr_mode"));
    s.rr_start_bounce = read.get_int("rr_start_bounce");
    s.heuristic = read.get_enum("bdpt_mis") == "BALANCE" ? MisHeuristic::Balance : MisHeuristic::Power;
    return s;
}

}  // namespace candela
