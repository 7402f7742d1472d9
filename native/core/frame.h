// Orthonormal frame around a unit normal: Duff et al. 2017, "Building an Orthonormal Basis, Revisited"
// (branchless, no singularity except the sign switch at n.z = 0).
#pragma once

#include <cmath>

#include "core/vec.h"

namespace candela {

struct Frame {
    Vec3 s, t, n;

    Frame() = default;
    explicit Frame(const Vec3& normal) : n(normal) {
        const float sign = std::copysign(1.f, n.z);
        const float a = -1.f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = Vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3(b, sign + n.y * n.y * a, -n.y);
    }

    Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace candela
