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
#include "integrators/common/surface_vertex.h"
#include "lights/light_sample.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace candela {

/// Shadow-ray end margin: the ray stops at (1 − k_shadow_epsilon) of the distance to the light point. Mirrored by
/// Scene::intersect_area_light's (1 + 1e-4) so camera and BSDF rays see a light exactly when light sampling does.
constexpr float k_shadow_epsilon = 1e-4f;

/// True if something blocks the light sample `ls` seen from `hit`; `origin` is hit.p offset to the side wi leaves
/// from (offset_ray_origin with the geometric normal flipped to that side). Distant lights (infinite dist) are
/// tested along wi to infinity. `skip_self` false: the ray may hit hit's own triangle (a terminator-offset shadow ray
/// toward a light below the facet, which Cycles lets its own facet block).
inline bool shadow_ray_blocked(const Scene& scene, const SurfaceHit& hit, const Vec3& origin, const LightSample& ls,
                               bool skip_self = true) {
    const PrimitiveRef skip = skip_self ? hit.primitive : PrimitiveRef{};
    if (!std::isfinite(ls.dist)) return scene.occluded(origin, ls.wi, std::numeric_limits<float>::infinity(), skip);
    // The segment origin + t·to_light, t ∈ [0, 1 − ε]: Embree takes an unnormalised direction (t is then a fraction
    // of the segment), which saves normalising it.
    const Vec3 to_light = (hit.p + ls.wi * ls.dist) - origin;
    if (!(length_squared(to_light) > 0.f)) return false;
    return scene.occluded(origin, to_light, 1.f - k_shadow_epsilon, skip);
}

/// How a shadow ray treats transparent surfaces (Cycles' transparent shadows): the Light Path inputs it is shaded
/// with and how many Transparent surfaces it may cross (the path's remaining transparent bounces).
struct ShadowRayInputs {
    LightPathInfo path;
    int max_surfaces = 0;
};

/// What of light sample `ls` reaches `hit` (origin as for shadow_ray_blocked): 1 or 0 without transparent
/// materials (exactly shadow_ray_blocked), else the product of the Transparent weights of the surfaces crossed
/// (Scene::transmittance).
inline Color shadow_ray_transmittance(const Scene& scene, const SurfaceHit& hit, const Vec3& origin,
                                      const LightSample& ls, const ShadowRayInputs& in, bool skip_self = true) {
    if (!scene.has_transparent_materials())
        return shadow_ray_blocked(scene, hit, origin, ls, skip_self) ? Color(0.f) : Color(1.f);
    const PrimitiveRef skip = skip_self ? hit.primitive : PrimitiveRef{};
    if (!std::isfinite(ls.dist)) return scene.transmittance(origin, ls.wi, true, skip, in.path, in.max_surfaces);
    // The same end margin as shadow_ray_blocked: the segment stops (1 − ε) of the way to the light point.
    const Vec3 light_point = hit.p + ls.wi * ls.dist;
    const Vec3 end = origin + (light_point - origin) * (1.f - k_shadow_epsilon);
    if (!(length_squared(light_point - origin) > 0.f)) return Color(1.f);
    return scene.transmittance(origin, end, false, skip, in.path, in.max_surfaces);
}

/// The shadow-ray origin at `hit` for a light in direction wl leaving on the front (ng's side) or the back:
/// spawn's offset origin, or with a shadow terminator offset (Scene::terminator_point) the lifted point's.
inline Vec3 shadow_ray_origin(const Scene& scene, const SurfaceHit& hit, const Vec3& ns_side, const Vec3& ng_side,
                              const Vec3& wl, bool front, SpawnPoints& spawn) {
    // terminator_point leaves the point where it cannot lift it (a flat triangle, no offset): decided here first,
    // without its per-call set-up (Blender's default offset is 0.1, so most scenes have offsets but flat meshes).
    if (!scene.terminator_lifts(hit)) return spawn.origin(front);
    const Vec3 ng = front ? ng_side : -ng_side;
    const Vec3 p = scene.terminator_point(hit, front ? ns_side : -ns_side, ng, wl);
    return (p.x == hit.p.x && p.y == hit.p.y && p.z == hit.p.z) ? spawn.origin(front) : offset_ray_origin(p, ng);
}

}  // namespace candela
