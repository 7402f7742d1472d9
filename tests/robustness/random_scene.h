// A randomised scene generator for robustness tests: random triangles at scales from 1e-4 to 1e4
// (degenerate ones included), random instancing with negative and non-uniform scales, every material type,
// every Blender light type at strengths up to 1e6, a random world and a random camera. Deterministic per seed.
#pragma once

#include <cstdint>

#include "core/params.h"
#include "input/scene_arrays.h"

namespace candela::test {

struct RandomScene {
    SceneArrays arrays;
    Params params;
};

RandomScene make_random_scene(uint64_t seed);

}  // namespace candela::test
