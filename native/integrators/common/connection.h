// Visibility of a connection between two surface points (the generators' and photon mapping's connections): the
// segment from a's offset origin on the side it leaves by to b's offset point on the side it arrives from
// (scene/ray_offset.h), stopping k_shadow_epsilon short, with both end triangles skipped — the rules of the
// shadow ray (integrators/shadow_ray.h) at both ends.
#pragma once

#include "integrators/shadow_ray.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace candela {

/// Whether the segment between surface points a and b is unblocked for rays of `type` (a shadow ray by default).
inline bool surfaces_connect(const Scene& scene, const SurfaceHit& a, const SurfaceHit& b,
                             RayType type = RayType(k_ray_shadow)) {
    const Vec3 w = b.p - a.p;
    const Vec3 o = offset_ray_origin(a.p, dot(w, a.ng) > 0.f ? a.ng : -a.ng);
    const Vec3 target = offset_ray_origin(b.p, dot(w, b.ng) < 0.f ? b.ng : -b.ng);
    const Vec3 seg = target - o;
    if (!(length_squared(seg) > 0.f)) return true;
    return !scene.occluded(o, seg, 1.f - k_shadow_epsilon, type, a.primitive, b.primitive);
}

}  // namespace candela
