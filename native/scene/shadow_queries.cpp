// The shadow-ray services of the scene: transparent shadows (Scene::transmittance) and the shadow terminator
// geometry offset (Scene::terminator_point). docs/light_paths.md describes both.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bsdf/bsdf_filters.h"
#include "scene/ray_offset.h"
#include "scene/scene_parts.h"

namespace candela {

Color Scene::transmittance(const Vec3& from, const Vec3& to, bool to_infinity, const PrimitiveRef& skip_from,
                           const LightPathInfo& path, int max_surfaces) const {
    constexpr float k_inf = std::numeric_limits<float>::infinity();
    // A segment is from + t·d, t ∈ [0, 1] (unnormalised d, as occluded() takes it); a ray to infinity has unit d.
    Vec3 o = from;
    Vec3 d = to_infinity ? to : to - from;
    const float tmax = to_infinity ? k_inf : 1.f;
    if (!m_any_transparent) return occluded(o, d, tmax, skip_from) ? Color(0.f) : Color(1.f);
    Color through(1.f);
    LightPathInfo info = path;
    PrimitiveRef skip = skip_from;
    for (int crossed = 0;; ++crossed) {
        SurfaceHit hit;
        if (!intersect(Ray{o, d, 0.f, tmax, k_ray_shadow}, &hit, skip)) return through;
        // An opaque surface, or more transparent ones than the budget allows, blocks the light.
        if (!(material_flags(hit.material) & k_bsdf_transparent) || crossed >= max_surfaces) return Color(0.f);
        const float dl = length(d);
        info.ray_length = hit.t * dl;
        const ShadingPoint sp = shade(hit, -d / dl, &info);
        through *= transparency(sp.bsdf());
        if (is_black(through)) return through;
        ++info.transparent_depth;
        // Go on from just beyond the surface toward the same end point.
        const Vec3 next = offset_ray_origin(hit.p, dot(d, hit.ng) > 0.f ? hit.ng : -hit.ng);
        if (!to_infinity) d = (o + d) - next;
        o = next;
        skip = hit.primitive;
    }
}

bool Scene::terminator_lifts(const SurfaceHit& hit) const {
    if (!m_any_terminator_offset) return false;
    const Placement& pl = m_placements[hit.object];
    const MeshShading& s = m_shading[pl.mesh];
    return pl.terminator_offset > 0.f && !s.corners.empty() && !s.smooth.empty() && s.smooth[hit.primitive.prim];
}

Vec3 Scene::terminator_point(const SurfaceHit& hit, const Vec3& ns_side, const Vec3& ng_side, const Vec3& wl) const {
    if (!m_any_terminator_offset) return hit.p;
    std::optional<Placement> moved;
    const Placement& pl = placement_now(hit.object, moved);
    const float cutoff = pl.terminator_offset;
    const MeshShading& s = m_shading[pl.mesh];
    const uint32_t prim = hit.primitive.prim;
    if (!terminator_lifts(hit)) return hit.p;
    // How much of the offset to apply (Cycles' shadow_ray_offset, signed cosines): all of it for light directions
    // near or past the smooth terminator or below the facet, none for directions well above both the shading and
    // the geometric horizon, with a linear blend between.
    const float nl = dot(ns_side, wl), ngl = dot(ng_side, wl);
    const float amount = nl < cutoff ? clamp(2.f - (ngl + nl) / cutoff, 0.f, 1.f) : clamp(1.f - ngl / cutoff, 0.f, 1.f);
    if (!(amount > 0.f)) return hit.p;
    // Hanika 2021 ("Hacking the Shadow Terminator", Ray Tracing Gems II, ch. 4): the point moved onto the
    // barycentric blend of its projections onto the tangent planes of the three vertices (only the planes it lies
    // below), a quadratic-like lift toward the smooth surface the vertex normals describe. Mesh space.
    const float w[3] = {1.f - hit.b1 - hit.b2, hit.b1, hit.b2};
    Vec3 p(0.f), n(0.f);
    for (int k = 0; k < 3; ++k) {
        p += s.corners[3 * prim + k] * w[k];
        n += s.normals[3 * prim + k] * w[k];
    }
    // The vertex normals turned to the side the shadow ray leaves from (the geometric normal's side): a mesh-space
    // vector v lies on the side of world direction ng_side when M·v does (M the object's transform).
    const Vec3 n_world = pl.instanced ? pl.object_to_world.vector(n) : n;
    const float sign = dot(n_world, ng_side) < 0.f ? -1.f : 1.f;
    Vec3 lift(0.f);
    for (int k = 0; k < 3; ++k) {
        const Vec3 nk = s.normals[3 * prim + k] * sign;
        const float below = std::fmin(0.f, dot(p - s.corners[3 * prim + k], nk));
        lift -= nk * (below * w[k]);
    }
    if (pl.instanced) lift = pl.object_to_world.vector(lift);
    return hit.p + lift * amount;
}

}  // namespace candela
