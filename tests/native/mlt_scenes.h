// The scenes and settings the Metropolis tests share (mlt_test.cpp, mlt_estimator_test.cpp).
#pragma once

#include <string>

#include "test_helpers.h"

namespace candela::test {

/// A closed-ish box: white floor, ceiling and back, red left and green right wall, open toward the camera; two
/// blocks. `door`: the box's light is off, its back wall has a slit along the floor, and behind it a second room
/// holds an area light facing away from the slit, so light enters the box only after a bounce, through the slit.
SceneArrays box_scene(bool door);

/// 16 × 12 pixels, max bounces 5, a Blackman–Harris filter of width 1.5, two threads; for MLT and MMLT 32 chains
/// and a bootstrap of 20 000 paths (MLT) or 4 000 per depth (MMLT).
Params base_params(const std::string& integrator, int samples);

/// Renders `a` and `b` with seeds 1..runs each and expects their image means within 4.5 and their 4×4 block means
/// within 6.5 standard errors of the spread over the seeds (agreement.h; t with 2·runs − 2 degrees of freedom: with
/// 8 runs a two-sided false alarm of 5e-4 and 1.5e-5 per comparison).
void expect_agree(const SceneArrays& arrays, const Params& a, const Params& b, const std::string& what, int runs = 8);

}  // namespace candela::test
