// Where a textured emitter's radiance comes from: the scene evaluates the emitting material's shader program at
// a point of one of its triangles (scene/shading.cpp), so next-event estimation sees exactly the radiance a ray
// hitting that point would — the light-sampling estimate stays unbiased however the texture varies, and only
// the selection probabilities use a triangle's average radiance.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

class EmissionSource {
public:
    virtual ~EmissionSource() = default;
    /// Emitted radiance of emitter `id` at world point p (barycentric weights b1, b2 of the triangle's second and
    /// third corners), toward unit direction wo (from the point to the receiver); `ng` is the triangle's unit
    /// winding normal.
    virtual Color emission(uint32_t id, const Vec3& p, const Vec3& ng, float b1, float b2, const Vec3& wo) const = 0;
};

}  // namespace candela
