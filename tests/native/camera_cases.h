// Camera models shared by the camera-importance tests (camera_importance_test.cpp: exact inverses;
// camera_importance_mc_test.cpp: Monte Carlo checks): every projection, sensor fit, shift, pixel aspect and lens the
// importance must invert, each on a rotated and translated camera, all with the clip range [1, 6].
#pragma once

#include <string>
#include <vector>

#include "core/params.h"
#include "core/rng.h"
#include "core/transform.h"
#include "scene/camera.h"

namespace candela::test {

struct CameraCase {
    std::string name;
    Params params;
    Affine to_world;
};

/// perspective, wide_shifted_aspect, vertical_fit_portrait, horizontal_fit_portrait, thin_lens,
/// thin_lens_blades_ratio, ortho (the pinhole orthographic camera), ortho_dof, ortho_dof_blades_ratio.
std::vector<CameraCase> camera_cases();
/// All but the pinhole orthographic camera.
std::vector<CameraCase> connectable_cases();
const CameraCase& case_named(const std::vector<CameraCase>& cases, const std::string& name);

inline Vec2 rand2(Pcg32& rng) {
    const float x = rng.next_float();
    return {x, rng.next_float()};
}

/// The point generate_ray's ray of raster (x, y) and lens sample u passes at view-axis depth `depth`.
Vec3 point_at_depth(const Camera& cam, Vec2 raster, Vec2 u, float depth);

}  // namespace candela::test
