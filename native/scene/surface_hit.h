// A ray–surface intersection as integrators see it.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

struct SurfaceHit {
    float t = 0.f;
    Vec3 p;              // world (camera-relative) position
    Vec3 ng;             // unit geometric normal (winding orientation, not flipped toward the ray)
    Vec3 ns;             // unit shading normal, on the same side as ng
    uint32_t material = 0;
    int32_t light = -1;  // index in the LightSet if the triangle emits, else −1
};

}  // namespace candela
