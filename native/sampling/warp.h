// Warps from the unit square to common domains, each with its density (w.r.t. solid angle or area).
// References: Shirley & Chiu 1997 (concentric disk); Malley's method for the cosine hemisphere;
// Pharr, Jakob & Humphreys, PBRT 4th ed., §A.5 (uniform sphere, cone, triangle).
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

/// cos x and sin x for |x| ≤ π/4, in float: Taylor polynomials about 0 (cos to x¹⁰, sin to x⁹). Their
/// remainders are below the first omitted terms, x¹²/12! ≤ 1.2e-10 and x¹¹/11! ≤ 1.8e-9 at π/4 — under a
/// hundredth of a float ulp of results in [0.7, 1] (cos) and far below sin's relative ulp (the relative
/// remainder x¹⁰/11! ≤ 2.3e-9); what remains is Horner rounding, about an ulp. Cheaper than std::cos/sin's
/// range reduction and call, for the warps whose angle is already in [−π/4, π/4].
inline void sincos_quarter_pi(float x, float* s, float* c) {
    const float x2 = x * x;
    *s = x * (1.f + x2 * (-1.f / 6.f + x2 * (1.f / 120.f + x2 * (-1.f / 5040.f + x2 * (1.f / 362880.f)))));
    *c = 1.f + x2 * (-0.5f + x2 * (1.f / 24.f + x2 * (-1.f / 720.f + x2 * (1.f / 40320.f + x2 * (-1.f / 3628800.f)))));
}

/// Uniform point on the unit disk, area density 1/π; concentric map keeps strata compact.
/// Branch-free: which of |ox|, |oy| is larger is a coin flip per sample (a mispredicted branch half the time),
/// so both octant cases are one computation with selected operands.
inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
    const float ox = 2.f * u.x - 1.f, oy = 2.f * u.y - 1.f;
    // |ox| > |oy|: θ = (π/4)(oy/ox) ∈ [−π/4, π/4], point r·(cos θ, sin θ) with r = ox.
    // Else θ = π/2 − φ with φ = (π/4)(ox/oy) ∈ [−π/4, π/4]: cos θ = sin φ, sin θ = cos φ, r = oy.
    const bool x_major = std::fabs(ox) > std::fabs(oy);
    const float r = x_major ? ox : oy, q = x_major ? oy : ox;
    float s, c;
    sincos_quarter_pi(r != 0.f ? (k_pi / 4.f) * (q / r) : 0.f, &s, &c);  // r = 0 only at the centre (q = 0 too)
    return {r * (x_major ? c : s), r * (x_major ? s : c)};
}

/// Cosine-weighted direction about +z (Malley): pdf = cos θ / π.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
    const Vec2 d = sample_uniform_disk_concentric(u);
    const float z = safe_sqrt(1.f - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.f ? cos_theta * k_inv_pi : 0.f; }

/// Uniform direction on the hemisphere about +z: pdf = 1/(2π).
inline Vec3 sample_uniform_hemisphere(Vec2 u) {
    const float z = u.x;
    const float r = safe_sqrt(1.f - z * z);
    const float phi = 2.f * k_pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniform_hemisphere_pdf() { return k_inv_two_pi; }

/// Uniform direction on the unit sphere: pdf = 1/(4π).
inline Vec3 sample_uniform_sphere(Vec2 u) {
    const float z = 1.f - 2.f * u.x;
    const float r = safe_sqrt(1.f - z * z);
    const float phi = 2.f * k_pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniform_sphere_pdf() { return k_inv_four_pi; }

/// Uniform direction in the cone of half-angle acos(cos_max) about +z: pdf = 1/(2π(1 − cos_max)).
inline Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
    const float cos_t = (1.f - u.x) + u.x * cos_max;
    const float sin_t = safe_sqrt(1.f - cos_t * cos_t);
    const float phi = 2.f * k_pi * u.y;
    return {std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t};
}
inline float uniform_cone_pdf(float cos_max) { return 1.f / (2.f * k_pi * (1.f - cos_max)); }

/// Uniform barycentrics (b0, b1) on a triangle (Heitz 2019, "A Low-Distortion Map Between Triangle and
/// Square"): area density 1/A.
inline Vec2 sample_uniform_triangle(Vec2 u) {
    // Below the diagonal: b0 = u.x/2, b1 = u.y − b0; above it: b1 = u.y/2, b0 = u.x − b1. Written with selects:
    // which side a sample falls on is a coin flip, a mispredicted branch half the time.
    const bool below = u.x < u.y;
    const float h = 0.5f * (below ? u.x : u.y);
    return {below ? h : u.x - h, below ? u.y - h : h};
}

}  // namespace candela
