// Closed forms the irradiance cache tests compare with (docs/irradiance_cache.md, "Expected values"), and a gather
// driven by an analytic radiance field instead of a scene.
#pragma once

#include <functional>
#include <vector>

#include "core/frame.h"
#include "core/rng.h"
#include "core/vec.h"
#include "integrators/irradiance_cache/ic_hemisphere.h"

namespace candela::test {

/// Irradiance at x with normal n from a convex planar polygon of radiance 1 entirely above x's tangent plane
/// (Lambert's formula): E = ½ |Σ_i β_i (n·u_i)| with v_i the unit vectors to the corners, β_i = acos(v_i·v_{i+1}),
/// u_i = normalize(v_i × v_{i+1}).
double polygon_irradiance(const std::vector<Vec3>& corners, const Vec3& x, const Vec3& n);

/// Irradiance at a point of a plane from a parallel disk of radius r and radiance 1 at height h, whose centre lies
/// at lateral distance d from the point: E = π/2 · [1 − (1 + H² − R²)/√((1 + H² + R²)² − 4R²)] with H = h/d,
/// R = r/d (the configuration factor of a parallel disk off axis; on the axis, d → 0, E = π r²/(r² + h²)).
double disk_irradiance(double r, double h, double d);

/// What a gather ray sees: radiance and hit distance (∞ for none).
struct AnalyticHit {
    Color L{0.f};
    float distance = 1e30f;
};
using AnalyticField = std::function<AnalyticHit(const Vec3& origin, const Vec3& direction)>;

/// A stratified gather at (x, n) of `strata`, jittered by `rng`, in the field.
HemisphereSamples analytic_gather(const AnalyticField& field, const Vec3& x, const Frame& frame,
                                  const GatherStrata& strata, Pcg32& rng);

/// The analytic room of the interpolation tests: a receiver in the plane z = 0 inside the box [−1.5, 1.5]² ×
/// [0, 1.2] with black walls, lit only by an emitter of radiance 1 in the ceiling facing down — a disk (centre
/// (0.2, 0.1), radius 0.4), a rectangle ([−0.3, 0.5] × [−0.2, 0.4]) or a triangle ((−0.4, −0.3), (0.5, −0.2),
/// (0.1, 0.6)). Gather rays hit the walls at finite distances (so R is finite) and see the emitter; next-event
/// estimation is not involved. The irradiance on the receiver is the emitter's closed form (the walls are black).
enum class RoomEmitter { Disk, Rectangle, Triangle };
struct AnalyticRoom {
    RoomEmitter emitter;
    static constexpr float k_half = 1.5f, k_height = 1.2f;
    AnalyticHit trace(const Vec3& o, const Vec3& d) const;
    double exact(const Vec3& x) const;  // E at x on the floor (normal +z)
    AnalyticField field() const {
        return [this](const Vec3& o, const Vec3& d) { return trace(o, d); };
    }
};

}  // namespace candela::test
