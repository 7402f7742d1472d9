// Spatial and directional bounds of emitters for the light BVH (Conty Estevez & Kulla 2018, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting", in the form of pbrt-v4's BVHLightSampler): an
// axis-aligned box, an orientation cone (axis w, normal spread θ_o, emission spread θ_e beyond it), the flux
// φ, and whether the emitters shine on both sides. importance(p, n) is a conservative estimate of the
// light a cluster sends to a point: it is > 0 wherever a light of the cluster can contribute.
// Also: per-light upper bounds of the unoccluded irradiance at a point (Ward 1991 adaptive shadow testing).
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "core/vec.h"
#include "lights/light.h"

namespace candela {

/// acos of cos clamped to [−1, 1], skipping libm for the two cosines the light tree meets most: 1 (a single
/// emitter's normal cone) and 0 (a Lambertian emission spread, θ_e = π/2). acosf(1) = +0 and acosf(±0) = π/2
/// rounded to float, correctly rounded by libm at both points, so the result has the same bits as the call
/// (LightBoundsAcos.MatchesLibm checks it); NaN still goes through std::acos.
inline float acos_clamped(float c) {
    if (c >= 1.f) return 0.f;
    if (c == 0.f) return 1.57079632679489661923f;
    return std::acos(c <= -1.f ? -1.f : c);
}

struct Bounds3 {
    Vec3 lo{std::numeric_limits<float>::infinity()};
    Vec3 hi{-std::numeric_limits<float>::infinity()};

    bool empty() const { return lo.x > hi.x; }
    void extend(const Vec3& p) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    void extend(const Bounds3& b) {
        lo = vmin(lo, b.lo);
        hi = vmax(hi, b.hi);
    }
    Vec3 centroid() const { return (lo + hi) * 0.5f; }
    Vec3 diagonal() const { return hi - lo; }
    float surface_area() const {
        const Vec3 d = diagonal();
        return 2.f * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
};

struct LightBounds {
    Bounds3 bounds;
    Vec3 w{0.f, 0.f, 1.f};    // orientation cone axis (unit)
    float phi = 0.f;          // flux (luminance), the same measure as light_power()
    float cos_theta_o = 1.f;  // spread of the emitters' normals about w
    float cos_theta_e = 0.f;  // emission beyond the normal spread (cos π/2 for Lambertian emitters)
    bool two_sided = false;

    /// Conservative importance at point p with normal n (n = 0: no cosine factor), 0 where no light of the
    /// cluster can contribute.
    float importance(const Vec3& p, const Vec3& n) const;
};

/// LightBounds prepared for repeated importance queries (the light tree's nodes): the bounding sphere and the
/// cone's sine are precomputed, and the angle differences use sines and cosines together, so a query costs three
/// or four square roots instead of a dozen. Same value as LightBounds::importance.
struct LightImportance {
    Vec3 centre;
    float radius = 0.f, radius2 = 0.f;  // bounding sphere of the box
    float d2_min = 1e-12f;              // pbrt-v4's distance clamp (see importance)
    Vec3 w{0.f, 0.f, 1.f};
    float cos_o = 1.f, sin_o = 0.f, cos_e = 0.f, phi = 0.f;
    bool two_sided = false;

    LightImportance() = default;
    explicit LightImportance(const LightBounds& b);
    float operator()(const Vec3& p, const Vec3& n) const;
};

/// Union of two light bounds (the box, the smallest cone containing both cones, Σφ, max θ_e).
LightBounds union_bounds(const LightBounds& a, const LightBounds& b);

/// The bounds of a finite light; std::nullopt for infinite lights (sun, world), which the BVH keeps apart.
std::optional<LightBounds> light_bounds(const Light& light);

/// An upper bound of the luminance of the unoccluded irradiance ∫ L_i |cos θ| dω that light `l` delivers
/// at ctx (|cos|: valid for reflection and transmission; ctx.n = 0 drops the cosine). 0 means the light
/// cannot contribute (behind a one-sided emitter, outside a spot cone, ...). Multiply by the BSDF's maximum
/// (ρ/π for Lambert) for a radiance bound.
float light_irradiance_bound(const Light& l, const LightSampleContext& ctx);

}  // namespace candela
