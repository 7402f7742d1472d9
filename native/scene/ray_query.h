// The per-query Embree context: the triangles a ray must ignore (the one it leaves and, for shadow rays, the one it
// aims at; robustness.md §1.2) and the ray's type, checked against each object's ray visibility. Embree calls the
// context filter only when a query installs it, so rays that need neither check cost nothing extra.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>

#include "scene/surface_hit.h"

namespace candela {

struct RayQueryContext {
    RTCIntersectContext context;  // first member: Embree hands the filter a pointer to it
    PrimitiveRef skip[2];
    uint8_t ray_type = 0;                 // RayType bits; 0 = no visibility check
    const uint8_t* object_flags = nullptr;  // per top-level geometry id (ObjectFlag bits)
};

/// Sets up the context; `object_flags` is only consulted when `check_visibility` (some object hides from this
/// ray type).
void init_ray_query(RayQueryContext* c, const PrimitiveRef& skip_a, const PrimitiveRef& skip_b, uint8_t ray_type,
                    const uint8_t* object_flags, bool check_visibility);

}  // namespace candela
