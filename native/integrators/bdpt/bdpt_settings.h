// Settings of the bidirectional path tracer (plain struct, read once from params). Names are the add-on's.
#pragma once

#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/common/mis.h"
#include "integrators/common/roulette.h"
#include "integrators/pixel_sampling.h"

namespace candela {

struct BdptSettings {
    PixelSampling pixel;
    int max_bounces = 12;  // a path has at most max_bounces + 1 scattering vertices, as PATH's
    RouletteMode rr_mode = RouletteMode::Throughput;
    int rr_start_bounce = 3;
    MisHeuristic heuristic = MisHeuristic::Power;
    bool strategy_images = false;  // bdpt_strategy_images (strategy_images.h)
    int strategy_depth = 2;        // the deepest path depth with strategy images

    static BdptSettings from_params(const Params& params);
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
