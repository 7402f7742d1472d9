// The local geometry a path scatters with at a surface, and the rules every integrator applies there:
//
// Shading frame. Surfaces are two-sided: the geometric and shading normals are turned to the side the camera-side
// direction w_c arrives from (the direction toward the eye along the path: wo for a camera path, the direction
// the light path leaves in for a light path), and the frame is built on the shading normal unless w_c lies below
// it (a shading normal facing away, near silhouettes of smooth low-poly meshes), where the geometric normal is
// used instead. The frame is a function of w_c only, so both directions a path can be generated in see the same
// BSDF f(w_c, w_l) at each vertex, and light-rooted and camera-rooted integrators agree.
//
// Light leaks. A direction whose geometric side (sign of w·ng) differs from its shading side (sign of its local
// z) would pass through the surface: it contributes nothing (reflection must stay above ng, transmission below).
//
// Ray origins. A ray leaving the vertex starts at the position offset off the surface (scene/ray_offset.h) on
// the side of ng it leaves by (front: reflection, the side w_c is on; back: transmission); the two origins are
// made on first use and shared by every ray leaving that side.
#pragma once

#include "bsdf/bsdf.h"
#include "core/frame.h"
#include "core/vec.h"
#include "scene/ray_offset.h"
#include "scene/surface_hit.h"

namespace candela {

struct SurfaceVertex {
    Vec3 p;
    Vec3 ng, ns;         // geometric and shading normals, on the side of w_c
    Frame frame;         // the shading frame (see above)
    bool backfacing;     // w_c arrives against the winding normal (glass: from inside)
    bool shading_frame;  // the frame is built on ns (false: on ng, w_c being below ns)

    /// The vertex at `hit` with shading normal `shading_normal` (on the winding side), seen along w_c.
    static inline __attribute__((always_inline)) SurfaceVertex at(const SurfaceHit& hit, const Vec3& shading_normal,
                                                                  const Vec3& w_c) {
        SurfaceVertex v;
        v.p = hit.p;
        v.ng = hit.ng;
        v.ns = shading_normal;
        v.backfacing = dot(w_c, v.ng) < 0.f;
        if (v.backfacing) {
            v.ng = -v.ng;
            v.ns = -v.ns;
        }
        v.shading_frame = dot(w_c, v.ns) > 0.f;
        v.frame = Frame(v.shading_frame ? v.ns : v.ng);
        return v;
    }

    /// Bump shadowing (bsdf/bsdf.h) at this vertex: active where a Bump or Normal Map node bent the shading normal
    /// (`bent`, ShadingPoint::bent) off the smooth one (`smooth`, SurfaceHit::ns: winding side) and the BSDF is
    /// evaluated in the bent normal's frame.
    BumpShadowing bump_shadowing(bool bent, const Vec3& smooth) const {
        BumpShadowing b;
        if (!bent || !shading_frame) return b;
        b.smooth = frame.to_local(backfacing ? -smooth : smooth);
        b.active = true;
        return b;
    }
};

/// Whether a direction with geometric cosine cos_g = w·ng and shading-frame z `local_z` lies on one side of the
/// surface geometrically and on the other in the shading frame, or grazes it: it would leak light through.
inline __attribute__((always_inline)) bool leaks(float cos_g, float local_z) {
    return cos_g == 0.f || (cos_g > 0.f) != (local_z > 0.f);
}

/// The two ray origins of a vertex (front: the side of ng, back: the other), made on first use.
class SpawnPoints {
public:
    SpawnPoints(const Vec3& p, const Vec3& ng) : m_p(p), m_ng(ng) {}
    inline __attribute__((always_inline)) const Vec3& origin(bool front) {
        const int side = front ? 0 : 1;
        if (!m_made[side]) {
            m_origin[side] = offset_ray_origin(m_p, front ? m_ng : -m_ng);
            m_made[side] = true;
        }
        return m_origin[side];
    }

private:
    Vec3 m_p, m_ng;
    Vec3 m_origin[2];
    bool m_made[2] = {false, false};
};

}  // namespace candela
