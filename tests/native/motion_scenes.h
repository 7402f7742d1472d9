// Scenes and comparisons the motion blur tests share (motion_blur_test.cpp, motion_blur_integrators_test.cpp).
#pragma once

#include <string>
#include <vector>

#include "core/motion_transform.h"
#include "test_helpers.h"

namespace candela::test {

/// The 4×4 rows of an affine transform (the scene arrays' layout).
std::vector<float> rows_of(const Affine& a);
/// A rotation about y by `angle`, then a translation by t.
Affine rotation_y(float angle, Vec3 t = Vec3(0.f));
Affine translation(Vec3 t);

/// A black box (half size 0.5; diffuse of `albedo` if given, and so is the emitting backdrop) 5 units in front of
/// the camera against a white world, moving from x0 to x1 over the shutter (a 2-step instance_motion), or still at
/// x0 when `moves` is false.
SceneArrays moving_box(float x0, float x1, bool moves, bool emitter_backdrop = false, float albedo = 0.f);

/// Per-block means (b×b blocks, RGB mean) and their standard errors from the per-pixel noise estimates.
struct Blocks {
    std::vector<double> mean, sigma;
};
Blocks blocks_of(const RenderResult& r, int b);
/// Every block agrees within 4.5 σ of the difference (two-sided false alarm ≈ 7e-6 per block, under 1e-3 for
/// the 64 blocks), plus `quadrature` (the still average's midpoint-rule error, motion_blur_test.cpp).
void expect_blocks_agree(const Blocks& a, const Blocks& b, double quadrature, const std::string& what);

/// 32 × 32 pixels, `samples`, RANDOM sampler, no bounces.
Params motion_params(const std::string& integrator, int samples, int threads = 2);

/// The grey box before the grey emitting wall that the integrator comparisons use, moving 2 units over the
/// shutter, and the params of `integrator` there: two bounces (motion_params has none), so paths wall → box → wall
/// (the indirect light between them) exist and every integrator's indirect estimate runs.
SceneArrays grey_moving_box();
Params grey_box_params(const std::string& integrator, int samples, int threads = 2);

}  // namespace candela::test
