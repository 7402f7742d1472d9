#include "integrators/bdpt/bdpt_settings.h"

#include "integrators/common/path_specs.h"

namespace candela {

ParamSpec BdptSettings::mis_spec() {
    return enum_param(
        "bdpt_mis", "Strategy Weights", "POWER",
        {{"BALANCE", "Balance", "Balance heuristic over all strategies (Veach 1997, eq. 10.9 with β = 1)"},
         {"POWER", "Power", "Power heuristic with exponent 2 over all strategies (Veach 1997, ch. 10)"}},
        "How the estimates of all (s, t) strategies of a path are weighted", "Bidirectional");
}

const std::vector<ParamSpec>& BdptSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        max_bounces_spec(),
        rr_mode_spec(),
        rr_start_bounce_spec(),
        mis_spec(),
        bool_param("bdpt_strategy_images", "Strategy Images", false,
                   "Also write, for every path depth up to Strategy Depth and every (s, t) strategy, its weighted and "
                   "unweighted contribution as render passes (BDPT d1 s1 t2, ...): which strategy carries which light",
                   "Bidirectional"),
        active_if(int_param("bdpt_strategy_depth", "Strategy Depth", 2, 0, 4,
                            "The deepest path depth (bounces) with strategy images; depth d has d + 2 strategies, two "
                            "images each, 48 bytes per pixel per strategy",
                            "Bidirectional"),
                  "bdpt_strategy_images==True"),
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
    s.strategy_images = read.get_bool("bdpt_strategy_images");
    s.strategy_depth = read.get_int("bdpt_strategy_depth");
    return s;
}

}  // namespace candela
