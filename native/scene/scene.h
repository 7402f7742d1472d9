// The immutable render-time scene integrators see: an Embree BVH over triangle meshes (single-use
// meshes flattened into world space, shared meshes as Embree instances of one geometry), the camera,
// materials and lights. Everything is stored in camera-world space (the camera at the origin), where
// float precision is best for what the image shows (pbrt-v4's CameraWorld convention).
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "bsdf/material.h"
#include "core/parallel.h"
#include "core/params.h"
#include "core/transform.h"
#include "lights/light.h"
#include "scene/camera.h"
#include "scene/embree_device.h"
#include "scene/surface_hit.h"

namespace candela {

class SceneArrays;

struct SceneStats {
    size_t unique_triangles = 0;    // stored once each
    size_t instanced_triangles = 0; // what instancing would have cost flattened
    size_t meshes = 0, instances = 0, emissive_triangles = 0;
    size_t embree_bytes = 0;        // what Embree holds: vertex/index buffers and BVHs (its memory monitor)
    size_t shading_bytes = 0;       // Candela's per-triangle shading data and per-instance placements
};

class Scene {
public:
    /// Builds the scene; throws InvalidScene/InvalidParameter for bad input and Cancelled if `cancel`
    /// fires during the BVH build. `arrays` must have been validated.
    Scene(const SceneArrays& arrays, const Params& params, const CancelToken* cancel);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    /// Closest surface hit along the ray within (ray.tmin, ray.tmax), ignoring the triangle `skip` (the one
    /// the ray leaves from: with the scale-relative origin offset this removes self-intersection).
    bool intersect(const Ray& ray, SurfaceHit* hit, const PrimitiveRef& skip = {}) const;
    /// True if any surface lies along o + t·d for t in (0, tmax), ignoring the triangles at both ends.
    bool occluded(const Vec3& o, const Vec3& d, float tmax, const PrimitiveRef& skip_from = {},
                  const PrimitiveRef& skip_to = {}) const;
    /// Closest emitting side of an area light along the ray before tmax: its index and distance. For a
    /// camera ray (`camera_ray`), lights hidden from the camera (AreaLight::visible_camera false) are skipped.
    bool intersect_area_light(const Vec3& o, const Vec3& d, float tmin, float tmax, uint32_t* light, float* t,
                              bool camera_ray = false) const;

    const Camera& camera() const { return m_camera; }
    const std::vector<Material>& materials() const { return m_materials; }
    const LightSet& lights() const { return m_lights; }
    float radius() const { return m_radius; }
    const SceneStats& stats() const { return m_stats; }
    /// Embree scene handle, for benchmarks that shoot raw rays.
    RTCScene embree_scene() const { return m_top.get(); }

private:
    struct MeshShading;
    struct Placement;
    void build(const SceneArrays& arrays, const CancelToken* cancel);

    EmbreeDevice m_device;
    EmbreeScene m_top;
    std::vector<EmbreeScene> m_mesh_scenes;  // one per instanced mesh
    std::vector<MeshShading> m_shading;      // per mesh (world space if flattened)
    std::vector<Placement> m_placements;     // per top-level geometry id
    Camera m_camera;
    std::vector<Material> m_materials;
    LightSet m_lights;
    Vec3 m_offset;  // added to world positions: −camera position
    float m_radius = 1.f;
    SceneStats m_stats;
};

}  // namespace candela
