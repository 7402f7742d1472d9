// Solid-angle sampling of area-like emitters (docs/robustness-notes.md §2):
//   - spherical triangles: Arvo 1995, "Stratified Sampling of Spherical Triangles", structured as in
//     pbrt-v4 (plane normals, stable vertex angles, clamped cos b′); solid angle by Van Oosterom–Strackee;
//   - spherical rectangles: Ureña, Fajardo & King 2013, "An Area-Preserving Parametrization for Spherical
//     Rectangles", with Cycles' fallbacks (tiny S, grazing);
//   - spheres: uniform cone of directions (Taylor branch for tiny solid angles), area sampling inside.
// The spherical computations run in double precision: the inputs are floats, and double removes most of the
// cancellation traps (acos near ±1, 1 − cosθ_max). The spherical triangle, sampled on every next-event
// estimate toward a near mesh light, replaces libm's double atan2 and sin/cos (each over 100 instructions) by
// truncated series accurate to ~1e-8 relative (atan) and ~1e-9 (sin, 1 − cos) — below the float resolution
// of its pdf and direction; the bounds are derived where the series are defined.
// Every sampler returns pdf = 0 for "no sample" and never NaN/Inf.
#pragma once

#include "core/vec.h"

namespace candela {

/// Triangles are sampled by solid angle only inside this range (pbrt-v4 `shapes.h`), else by area.
inline constexpr double k_min_spherical_triangle_sr = 3e-4;
inline constexpr double k_max_spherical_triangle_sr = 6.22;
/// Rectangles: solid angle below this → area sampling (Cycles' S < 1e-5 is too small for float callers:
/// we keep pbrt-v4's 1e-4).
inline constexpr double k_min_spherical_rectangle_sr = 1e-4;
/// Grazing: both edge-plane normals almost along the rectangle normal (Cycles, Blender bug #98930).
inline constexpr double k_spherical_rectangle_grazing_nz2 = 0.99999;
/// Sphere cone: below this sin²θ_max use the Taylor expansion of 1 − cosθ_max (pbrt-v4).
inline constexpr double k_sphere_taylor_sin2 = 0.00068523;

/// A direction drawn from the solid angle of an emitter with its density; pdf == 0 ⇔ no sample.
struct SphericalSample {
    Vec3 w;           // unit direction from the reference point
    float pdf = 0.f;  // solid-angle density
};

/// A triangle (v0, v1, v2) seen from p, prepared once for both the solid angle and sampling: the unit vertex
/// directions, the triple product a·(b×c) and Ω (Van Oosterom–Strackee; 0 if degenerate). make() is the one
/// place Ω is computed, so a pdf evaluated from it equals the pdf of a sample drawn from it bit for bit.
struct SphericalTriangle {
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    double triple = 0;
    double omega = 0;

    static SphericalTriangle make(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2);
    /// Uniform direction inside the spherical triangle (Arvo 1995): pdf = 1/Ω.
    SphericalSample sample(Vec2 u) const;
};

/// Solid angle of the triangle (a, b, c) seen from p, Van Oosterom–Strackee 1983; 0 if degenerate.
/// Equal to SphericalTriangle::make(p, a, b, c).omega.
double spherical_triangle_solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Uniform direction inside the spherical triangle (v0, v1, v2) seen from p (Arvo 1995).
/// pdf = 1/Ω with Ω = spherical_triangle_solid_angle(p, v0, v1, v2) — the value the pdf evaluation uses.
SphericalSample sample_spherical_triangle(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, Vec2 u);

/// A rectangle (corner s, orthogonal edges ex, ey) prepared for sampling from reference point o
/// (Ureña et al. 2013). `usable()` says whether solid-angle sampling is robust from o; the pdf evaluation of
/// a light must use the same test to mirror the sampling branch.
struct SphericalRectangle {
    // Local frame: x ∥ ex, y ∥ ey, z = x × y flipped so that the rectangle lies at z0 < 0.
    double o[3];
    double x[3], y[3], z[3];
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0, z0 = 0;
    double b0 = 0, b1 = 0, k = 0, S = 0;
    bool valid = false;  // S computed and > 0
    bool grazing = false;

    static SphericalRectangle make(const Vec3& o, const Vec3& s, const Vec3& ex, const Vec3& ey);
    bool usable() const { return valid && !grazing && S > k_min_spherical_rectangle_sr; }
    float solid_angle() const { return float(S); }
    /// The point on the rectangle for u ∈ [0,1)² (uniform in solid angle: pdf = 1/S).
    Vec3 sample_point(Vec2 u) const;
};

/// A direction toward a sphere (center, radius) from `ref`, with the point it reaches.
struct SphereSample {
    Vec3 w;  // unit direction
    Vec3 p;  // point on the sphere
    Vec3 n;  // outward normal at p
    float dist = 0.f;
    float pdf = 0.f;  // solid angle; 0 = no sample
};

/// Outside the sphere: uniform cone of directions (Taylor branch when sin²θ_max < k_sphere_taylor_sin2), the
/// surface point found analytically (no ray–sphere intersection). Inside/on the sphere: uniform area
/// sampling converted to solid angle.
SphereSample sample_sphere(const Vec3& ref, const Vec3& center, float radius, Vec2 u);
/// The density sample_sphere() gives the unit direction w (0 if w misses the sphere).
float sphere_pdf(const Vec3& ref, const Vec3& center, float radius, const Vec3& w);
/// Solid angle subtended by the sphere from ref (4π inside).
double sphere_solid_angle(const Vec3& ref, const Vec3& center, float radius);

}  // namespace candela
