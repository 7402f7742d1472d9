// Self-intersection avoidance without a fixed epsilon: move a ray origin off its surface by a distance
// that scales with the magnitude of the coordinates (Wächter & Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems ch. 6, 2019). Integer ulp steps far from the origin,
// a small absolute step near it.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

/// p moved off the surface along n (n points to the side the new ray leaves from).
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& n) {
    constexpr float k_origin = 1.f / 32.f, k_float_scale = 1.f / 65536.f, k_int_scale = 256.f;
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
        const int32_t of_i = static_cast<int32_t>(k_int_scale * n[i]);
        const int32_t bits = static_cast<int32_t>(float_bits(p[i]));
        const float p_i = bits_float(static_cast<uint32_t>(bits + ((p[i] < 0.f) ? -of_i : of_i)));
        out[i] = std::fabs(p[i]) < k_origin ? p[i] + k_float_scale * n[i] : p_i;
    }
    return out;
}

/// Origin for a ray leaving a surface with geometric normal ng in direction d.
inline Vec3 spawn_origin(const Vec3& p, const Vec3& ng, const Vec3& d) {
    return offset_ray_origin(p, dot(d, ng) >= 0.f ? ng : -ng);
}

}  // namespace candela
