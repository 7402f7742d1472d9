// SPPM's step 3 (sppm.h; docs/photon-mapping.md, "SPPM"): the photons of one iteration meet the visible points.
// Every photon looks up the points whose spheres hold it in a hash grid over them (visible_point_grid.h), and each
// point sums, over the photons it accepts, f_E(w_o, w_p)·a(w_o, w_p)·Φ_p — its estimated lobes toward the photon's
// direction with Veach's adjoint factor (common/fixed_view_bsdf.h: shaded once, its frame made once) — and counts
// them (M).
//
// Determinism without atomics: photons are taken in batches of k_gather_batch; each batch lists its (point, photon)
// pairs in photon order, the batches are concatenated in batch order (core/parallel_ordered.h) and the pairs sorted
// stably by point, so each point sums its photons in photon index order, for every thread count. Memory: the pairs
// are gathered in rounds of whole batches holding about k_pair_budget pairs (a round's size follows the previous
// round's pairs per batch: a function of the photons and points alone), each round's sums added in round order.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "integrators/photon_map/photon_shooting.h"
#include "integrators/render_context.h"
#include "scene/scene.h"

namespace candela {

inline constexpr size_t k_gather_batch = 4096;
/// (point, photon) pairs a round holds about: 8 bytes each while gathered, 4 once sorted.
inline constexpr size_t k_pair_budget = size_t(1) << 22;
/// A round's pair buffers at their peak, for the memory estimate: the batches' pair vectors (up to twice their
/// size in capacity, as vectors grow by doubling) and the sorted photon indices side by side, 84 MB. A round
/// passes the budget only when one batch alone does (thousands of points around each photon).
inline constexpr double k_gather_round_bytes = double(k_pair_budget) * (2 * 2 * sizeof(uint32_t) + sizeof(uint32_t));

struct VisiblePoint {
    SurfaceHit hit;
    Vec3 wo{0.f};
    Color beta{0.f};
    bool valid = false;
    bool transmits = false;  // the estimated lobes transmit: photons from both sides count
};

/// Per point: Σ f·a·Φ_p over the photons found, in photon order, and their number M.
struct PixelFlux {
    std::vector<Color> phi;
    std::vector<uint32_t> found;
};

/// The flux the photons of `shot` bring to `points` (radius radii[i] each; invalid points get none), shading the
/// points at shutter time `time` with the estimated lobes of `alpha_threshold`. The stage "Gathering photons"
/// counts photons; if ctx.cancel fires the result is partial (the caller checks).
PixelFlux gather_flux(const Scene& scene, const std::vector<VisiblePoint>& points, const std::vector<float>& radii,
                      const PhotonShot& shot, float alpha_threshold, float time, RenderContext& ctx);

}  // namespace candela
