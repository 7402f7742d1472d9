// Scenes of the irradiance cache tests (docs/irradiance_cache.md, "How it is tested").
#pragma once

#include "core/params.h"
#include "input/scene_arrays.h"
#include "test_helpers.h"

namespace candela::test {

/// The Cornell box (the official data, as examples/cornell_box.py builds it: metres, Z up, the camera at
/// (0, −0.8, 0.273) looking +Y with a 35 mm lens on a 25 mm sensor; Bitterli's reflectances, Lambertian; the light an
/// emissive quad of radiance (17, 12, 4) 0.5 mm below the ceiling). `world`: the constant world's radiance, seen
/// through the open front (a light no next-event estimation samples).
SceneArrays cornell_box_arrays(Color world = Color(0.f));
/// Params for a w × h render of it (box filter).
Params cornell_box_params(int w, int h, int samples, const std::string& integrator);

}  // namespace candela::test
