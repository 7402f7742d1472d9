// The scene's triangles for samplers of surface points (scene/surface_sampler.h): each object's vertex and index
// buffers, read back from Embree (the input arrays are gone after the build), and the hit at a point of a triangle,
// decoded exactly as a ray's hit there is.
#include <embree3/rtcore.h>

#include <string>

#include "core/error.h"
#include "scene/scene.h"
#include "scene/scene_parts.h"

namespace candela {

uint32_t Scene::object_count() const { return uint32_t(m_placements.size()); }

ObjectTriangles Scene::object_triangles(uint32_t object) const {
    if (object >= m_placements.size()) throw InternalError("object_triangles: no object " + std::to_string(object));
    const Placement& pl = m_placements[object];
    // A flattened mesh is top-level geometry `object`; an instance's triangles are geometry 0 of its shared BVH.
    const RTCGeometry g = pl.instanced ? rtcGetGeometry(m_mesh_scenes[size_t(pl.mesh_scene)]->get(), 0)
                                       : rtcGetGeometry(m_top.get(), object);
    ObjectTriangles t;
    t.vertices = static_cast<const float*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
    t.indices = static_cast<const uint32_t*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_INDEX, 0));
    t.triangle_count = uint32_t(m_shading[pl.mesh].material.size());
    t.instanced = pl.instanced;
    t.mesh = pl.mesh;
    if (pl.instanced) t.object_to_world = object_to_world(object);
    t.flags = m_object_flags[object];
    return t;
}

Affine Scene::object_to_world(uint32_t object) const {
    if (object >= m_placements.size()) throw InternalError("object_to_world: no object " + std::to_string(object));
    std::optional<Placement> scratch;
    return placement_now(object, scratch).object_to_world;
}

bool Scene::object_moves(uint32_t object) const {
    return object < m_placements.size() && m_placements[object].motion >= 0;
}

SurfaceHit Scene::surface_point(uint32_t object, uint32_t prim, float b1, float b2) const {
    const ObjectTriangles t = object_triangles(object);
    if (prim >= t.triangle_count) throw InternalError("surface_point: no triangle " + std::to_string(prim));
    Vec3 v[3];
    for (int k = 0; k < 3; ++k) {
        const float* p = t.vertices + 3 * size_t(t.indices[3 * size_t(prim) + k]);
        v[k] = Vec3(p[0], p[1], p[2]);
    }
    // Embree's geometric normal, in the space of the vertices: (v1 − v0) × (v2 − v0) (counter-clockwise front).
    const Vec3 ng = cross(v[1] - v[0], v[2] - v[0]);
    Vec3 p = v[0] * (1.f - b1 - b2) + v[1] * b1 + v[2] * b2;
    if (t.instanced) p = t.object_to_world.point(p);
    // decode_hit places the hit at ray.o + ray.d·t: a ray at p with t = 0 puts it at p; the ids are what Embree
    // reports for a hit on this triangle (an instance: geometry 0 of the instanced scene, instance `object`).
    Ray at;
    at.o = p;
    at.d = Vec3(0.f);
    SurfaceHit hit;
    if (t.instanced)
        decode_hit(at, 0u, prim, object, b1, b2, ng, 0.f, &hit);
    else
        decode_hit(at, object, prim, RTC_INVALID_GEOMETRY_ID, b1, b2, ng, 0.f, &hit);
    return hit;
}

}  // namespace candela
