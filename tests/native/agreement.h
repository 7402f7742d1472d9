// Agreement between two integrators' renders of one scene, judged by statistics: each integrator renders the scene
// with m independent seeds; the image mean and every b×b block mean are compared in units of their standard error
// estimated from the spread over the seeds (so errors correlated between pixels — splats, shared light paths — are
// counted as they are). With m seeds per side the statistic is t-distributed with about 2m − 2 degrees of freedom.
#pragma once

#include <string>
#include <vector>

#include "test_helpers.h"

namespace candela::test {

struct Agreement {
    double mean_a = 0.0, mean_b = 0.0;  // image means (luminance), averaged over the seeds
    double mean_z = 0.0;                // their difference over its standard error
    double worst_block_z = 0.0;         // the largest |z| over the blocks
    int blocks = 0;
    std::string worst_block;  // "x,y" of the worst block
};

/// `mask` (optional, W·H, bottom row first): only pixels with a non-zero entry count; blocks with none are skipped.
Agreement compare_seed_sets(const std::vector<RenderResult>& a, const std::vector<RenderResult>& b, int block,
                            const std::vector<uint8_t>* mask = nullptr);

/// The mean over the seeds of the image mean (luminance) and its standard error from their spread.
struct SeedMean {
    double mean = 0.0, standard_error = 0.0;
};
SeedMean seed_mean(const std::vector<RenderResult>& set);

/// Renders `arrays` with `params` and seeds 1..m.
std::vector<RenderResult> render_seeds(const SceneArrays& arrays, const Params& params, int m);

}  // namespace candela::test
