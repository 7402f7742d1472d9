// The gather of one irradiance cache record: a stratified M × N cosine-weighted hemisphere (the course's importance
// sampling for irradiance) and Ward & Heckbert's gradients from the same samples (docs/irradiance_cache.md).
//
// Stratum (j, k), j < M in polar angle and k < N in azimuth, is the cell sin²θ ∈ [j/M, (j+1)/M), φ ∈ [2πk/N,
// 2π(k+1)/N): each holds 1/(MN) of the cosine-weighted measure, and one jittered direction ω_jk in it has density
// cos θ/π, so with L_jk the radiance arriving along ω_jk and r_jk the distance of the surface it comes from
//
//   E   ≈ π/(MN) Σ L_jk                                                       (unbiased)
//   R   = MN / Σ 1/r_jk                        (the harmonic mean distance; rays that escape add 0 to the sum)
//   ∇_r E ≈ Σ L_jk ∫_cell(j,k) (n × ω) dω                     (∂E/∂rotation = ∫ L (n × ω) dω, L constant per cell)
//   ∇_t E ≈ Σ_k [ u_k (2π/N) Σ_{j≥1} sin θ_j⁻ cos² θ_j⁻ (L_jk − L_{j−1,k}) / min(r_jk, r_{j−1,k})
//              + v_k⁻ Σ_j (sin θ_j⁺ − sin θ_j⁻) (L_jk − L_{j,k−1}) / min(r_jk, r_{j,k−1}) ]
// where θ_j⁻ = asin √(j/M), θ_j⁺ = asin √((j+1)/M) bound stratum row j, u_k is the base-plane direction of column k's
// centre and v_k⁻ the base-plane direction perpendicular to the boundary between columns k−1 and k (azimuth 2πk/N +
// π/2). The translational gradient is Ward & Heckbert's: moving x sweeps the boundaries between neighbouring cells
// across the nearer of the two surfaces, exchanging one cell's radiance for the other's over the swept solid angle.
// Both gradients take L as constant over each cell. For the rotation that replaces the unbiased weight tan θ_jk of
// the sample's own direction, whose variance diverges (logarithmically) at the horizon, by the cell's exact integral
// (finite for every cell): biased by L's variation inside a cell, which vanishes as M and N grow.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "core/frame.h"
#include "core/vec.h"
#include "integrators/irradiance_cache/ic_record.h"

namespace candela {

/// The strata of a gather of about `rays` rays: M × N with N ≈ πM (Ward's proportion: cells of about equal
/// angular extent), M, N ≥ 1.
struct GatherStrata {
    int M = 1, N = 1;
    static GatherStrata for_rays(int rays);
    int count() const { return M * N; }
};

/// The local direction of stratum (j, k) at jitter u ∈ [0, 1)² (z = the normal).
Vec3 gather_direction(const GatherStrata& s, int j, int k, float u1, float u2);

/// What the gather saw: per stratum (row-major, index j·N + k) the radiance and the hit distance (∞: escaped).
struct HemisphereSamples {
    GatherStrata strata;
    std::vector<Vec3> dir;  // local directions
    std::vector<Color> L;
    std::vector<float> r;
};

/// E, R and the gradients of a gather, in the frame's local coordinates (gradients: z = the normal).
struct GatherEstimate {
    Color E{0.f};
    float R = std::numeric_limits<float>::infinity();  // ∞ when every ray escaped
    Vec3 grad_r[3], grad_t[3];
};
GatherEstimate estimate_gather(const HemisphereSamples& s);

/// How a gather becomes a record: Ward's a, whether gradients are used (then the gradient limit applies), the world
/// size of a pixel at the record (0: no spacing clamps) and the clamps in pixels, and the largest R (the scene's
/// diameter: R is ∞ when every ray escaped).
struct RecordRules {
    float a = 0.15f;
    bool gradients = true;
    float footprint = 0.f;
    float min_spacing = 0.f, max_spacing = 0.f;
    float max_R = 1e30f;
};

/// The record at p (frame: its normal) from a gather estimate in local coordinates (ic_record.h; the R rules in
/// docs/irradiance_cache.md): R = the harmonic mean distance (≤ max_R); with gradients, the gradient limit
/// R ≤ E/|∇_t E| (luminance); the validity radius a·R clamped to [min, max] × footprint; and where the minimum
/// keeps R above the gradient limit, ∇_t E scaled down to it.
IcRecord record_from_gather(GatherEstimate est, const Vec3& p, const Frame& frame, const RecordRules& rules);

/// The same gradients in world space.
inline void gradients_to_world(const Frame& f, GatherEstimate& g) {
    for (int c = 0; c < 3; ++c) {
        g.grad_r[c] = f.to_world(g.grad_r[c]);
        g.grad_t[c] = f.to_world(g.grad_t[c]);
    }
}

}  // namespace candela
