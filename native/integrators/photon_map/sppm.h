// Stochastic progressive photon mapping (Hachisuka & Jensen 2009; docs/photon-mapping.md, "SPPM"): a consistent
// photon mapper. Each iteration i:
//   1. one camera sample per pixel (filter importance sampled, so a sample counts for its own pixel only) follows
//      traced (delta) lobes to its first vertex with estimated lobes E — the visible point x_i with throughput β_i;
//      emission found on the way and next-event estimation of direct light at x_i through E go to the pixel's
//      direct sum (common/direct_light.h, light sampling only: no BSDF ray of E counts emission);
//   2. a photon pass of `photons_per_iteration` paths (photon_shooting.h, arrivals after ≥ 1 scattering: direct
//      light is step 1's);
//   3. each photon looks up the visible points whose spheres hold it in a hash grid over them (sppm_gather.h,
//      visible_point_grid.h: the sphere with the side check), and per pixel the M photons found add
//      Φ = Σ β_i·f_E(w_i, w_p)·a·Φ_p (common/fixed_view_bsdf.h), and the statistics shrink (α the radius reduction,
//      default 2/3):
//         N' = N + αM,   R' = R·√(N'/(N + M)),   τ' = (τ + Φ)·R'²/R²,
//      the pixel's estimate being  L = direct sum / i + τ/(π R² · emitted paths so far).
// As i grows R → 0 and the kernel bias vanishes while every photon's share of the estimate shrinks: the image
// converges to the path tracer's (RMSE ∝ i^(−1/3) at α = 2/3 for a smooth image). Only delta lobes are traced by
// default (traced_roughness 0): glossy lobes are estimated and converge like the rest.
//
// The film holds each pixel's current estimate as the mean of its entries: iteration i adds i·L_i − (i−1)·L_(i−1)
// as one entry. The estimates of the two noise replicates share the photon statistics, so the film's noise
// estimate would lie: SPPM reports none ("n/a") and the noise-threshold stop is off (progressive_driver.h).
// Determinism without atomics: the photons are gathered in fixed batches whose (pixel, photon) pairs are
// concatenated in batch order and sorted stably by pixel, so every pixel sums its photons in photon index order
// (sppm_gather.h); every iteration's photons are a function of the seed and the iteration, so the image is the same
// for every thread count.
#pragma once

#include "integrators/integrator.h"
#include "integrators/photon_map/photon_settings.h"

namespace candela {

void render_sppm(const SppmSettings& settings, const Scene& scene, Film& film, RenderContext& ctx);

/// Bytes per pixel of SPPM's statistics, visible point and its share of the grid (a point listed in up to 8 cells,
/// its bucket starts); the (pixel, photon) pairs of an iteration (8 bytes each while gathered, 4 once sorted) come
/// on top and grow with the photons per iteration and the radius.
double sppm_bytes_per_pixel();

}  // namespace candela
