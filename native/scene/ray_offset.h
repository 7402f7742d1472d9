// Self-intersection avoidance without a fixed epsilon: move a ray origin off its surface by a distance
// that scales with the magnitude of the coordinates (Wächter & Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems ch. 6, 2019). Integer ulp steps far from the origin,
// a small absolute step near it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

/// p moved off the surface along n (n points to the side the new ray leaves from).
///
/// Wächter & Binder's absolute step near zero (1/65536 for coordinates below 1/32) assumes unit-sized scenes:
/// in a scene 1e-4 across it is 15 % of the scene, and rays skip through thin walls. Scenes are in camera-world
/// space, so a point's own magnitude |p|∞ measures the rounding around it: below 1/32 the step shrinks with it
/// (|p|∞/2048, equal to 1/65536 at |p|∞ = 1/32). At |p|∞ ≥ 1/32 nothing changes.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& n) {
    constexpr float k_origin = 1.f / 32.f, k_float_scale = 1.f / 65536.f, k_int_scale = 256.f;
    const Vec3 a(std::fabs(p.x), std::fabs(p.y), std::fabs(p.z));
    // std::max/min, not fmax/fmin: p is finite, and these compile to single instructions.
    const float magnitude = std::max(a.x, std::max(a.y, a.z));
    const float float_scale = std::min(k_float_scale, magnitude * (k_float_scale / k_origin));
    auto component = [float_scale](float p_i, float abs_i, float n_i) {
        const int32_t of_i = static_cast<int32_t>(k_int_scale * n_i);
        const int32_t bits = static_cast<int32_t>(float_bits(p_i));
        const float stepped = bits_float(static_cast<uint32_t>(bits + (p_i < 0.f ? -of_i : of_i)));
        return abs_i < k_origin ? p_i + float_scale * n_i : stepped;
    };
    return {component(p.x, a.x, n.x), component(p.y, a.y, n.y), component(p.z, a.z, n.z)};
}

/// Origin for a ray leaving a surface with geometric normal ng in direction d.
inline Vec3 spawn_origin(const Vec3& p, const Vec3& ng, const Vec3& d) {
    return offset_ray_origin(p, dot(d, ng) >= 0.f ? ng : -ng);
}

}  // namespace candela
