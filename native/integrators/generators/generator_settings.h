// Settings of the course's indirect path generators (plain struct, read once from params). Names are the add-on's
// identifiers: the three integrators SURFACE_SAMPLING, SOURCE_SHOOTING and RECEIVER_GATHERING share these settings
// and differ in `generator`.
#pragma once

#include <string>
#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/roulette.h"
#include "integrators/pixel_sampling.h"

namespace candela {

/// How the indirect light at a visible point is found (docs/path-generators.md): a point on a light and a point on
/// any surface joined by two visibility checks, a ray from the light whose hits are connected to the receiver, or a
/// ray from the receiver whose hit is connected to a point on a light.
enum class PathGenerator { SurfaceSampling, SourceShooting, ReceiverGathering };

/// The registry name of a generator (its add-on identifier).
const char* path_generator_name(PathGenerator g);

struct GeneratorSettings {
    PathGenerator generator = PathGenerator::ReceiverGathering;
    PixelSampling pixel;
    int max_bounces = 12;
    RouletteMode rr_mode = RouletteMode::Throughput;
    int rr_start_bounce = 3;
    DirectLightRules direct;  // next-event estimation at receivers (always with MIS) and gathered points
    std::string light_selection = "TREE";
    bool combine = false;  // generators_mis: the one-bounce term by all three generators, with MIS
    MisHeuristic combine_heuristic = MisHeuristic::Balance;

    static GeneratorSettings from_params(const Params& params, PathGenerator generator);
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
