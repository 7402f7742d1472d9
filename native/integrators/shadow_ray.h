// The shadow ray of next-event estimation: is the segment from a surface point to a sampled light point blocked?
//
// The ray starts at the scale-relative offset origin (scene/ray_offset.h), which lies up to a few ulps off the
// shading point. Keeping the light sample's direction wi from there would translate the whole segment by that
// offset: its end then misses the sampled point by the same amount, and toward a point seen at grazing incidence
// on the emitter (a sphere's rim facets, a light in a receiver's plane) the translated end lies behind the
// emitter's plane, so the ray meets the emitter itself before tmax and the sample is lost — a bias of −0.37 % on
// a faceted sphere light (tests/native/analytic_lights_test.cpp). Aiming from the offset origin at the sampled
// point keeps the end on the emitter's side of its plane; stopping 10⁻⁴ short of it (as pbrt's ShadowEpsilon
// does) keeps the emitter's own triangle out, whatever the rounding of the hit distance.
#pragma once

#include <cmath>
#include <limits>

#include "core/math.h"
#include "lights/light_sample.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace candela {

/// Shadow-ray end margin: the ray stops at (1 − k_shadow_epsilon) of the distance to the light point. Mirrored by
/// Scene::intersect_area_light's (1 + 1e-4) so camera and BSDF rays see a light exactly when light sampling does.
constexpr float k_shadow_epsilon = 1e-4f;

/// True if something blocks the light sample `ls` seen from `hit`; `origin` is hit.p offset to the side wi leaves
/// from (offset_ray_origin with the geometric normal flipped to that side). Distant lights (infinite dist) are
/// tested along wi to infinity.
inline bool shadow_ray_blocked(const Scene& scene, const SurfaceHit& hit, const Vec3& origin, const LightSample& ls) {
    if (!std::isfinite(ls.dist)) return scene.occluded(origin, ls.wi, std::numeric_limits<float>::infinity(), hit.primitive);
    // The segment origin + t·to_light, t ∈ [0, 1 − ε]: Embree takes an unnormalised direction (t is then a fraction
    // of the segment), which saves normalising it.
    const Vec3 to_light = (hit.p + ls.wi * ls.dist) - origin;
    if (!(length_squared(to_light) > 0.f)) return false;
    return scene.occluded(origin, to_light, 1.f - k_shadow_epsilon, hit.primitive);
}

}  // namespace candela
