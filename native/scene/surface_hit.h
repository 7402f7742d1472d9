// A ray–surface intersection as integrators see it.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

/// Identifies the triangle a ray hit (Embree's ids), so a ray leaving it can skip it (docs/robustness-notes.md §1.2).
struct PrimitiveRef {
    static constexpr uint32_t k_none = 0xFFFFFFFFu;  // RTC_INVALID_GEOMETRY_ID
    uint32_t geom = k_none, prim = k_none, inst = k_none;

    bool valid() const { return geom != k_none; }
    bool operator==(const PrimitiveRef& o) const { return geom == o.geom && prim == o.prim && inst == o.inst; }
};

struct SurfaceHit {
    float t = 0.f;
    Vec3 p;   // world (camera-relative) position
    Vec3 ng;  // unit geometric normal (winding orientation, not flipped toward the ray)
    Vec3 ns;  // unit shading normal, on the same side as ng
    uint32_t material = 0;
    int32_t light = -1;        // index in the LightSet if the triangle emits, else −1
    PrimitiveRef primitive;    // the triangle hit
    uint32_t object = 0;       // top-level object (Embree geometry id) the triangle belongs to
    float b1 = 0.f, b2 = 0.f;  // barycentric weights of the triangle's second and third corners
};

/// The closest hit of a ray traced ahead of its path (camera rays go to Embree eight at a time), handed to the
/// integrator that continues from it.
struct TracedHit {
    SurfaceHit hit;
    bool found = false;  // false: the ray escaped (hit is unset)
};

}  // namespace candela
