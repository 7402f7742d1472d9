// The immutable render-time scene integrators see: an Embree BVH over triangle meshes (single-use
// meshes flattened into world space, shared meshes as Embree instances of one geometry), the camera,
// materials and lights. Everything is stored in camera-world space (the camera at the origin), where
// float precision is best for what the image shows (pbrt-v4's CameraWorld convention).
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "bsdf/material.h"
#include "bsdf/material_inputs.h"
#include "core/motion_transform.h"
#include "core/parallel.h"
#include "core/params.h"
#include "core/transform.h"
#include "lights/emitter_set.h"
#include "lights/light.h"
#include "lights/light_emission.h"
#include "lights/light_sampler.h"
#include "scene/camera.h"
#include "scene/embree_device.h"
#include "scene/ray_visibility.h"
#include "scene/shading_point.h"
#include "scene/shutter_time.h"
#include "scene/surface_hit.h"

namespace candela {

class SceneArrays;
class MeshBvhCache;

struct SceneStats {
    size_t unique_triangles = 0;     // stored once each
    size_t instanced_triangles = 0;  // what instancing would have cost flattened
    size_t meshes = 0, instances = 0, emissive_triangles = 0;
    size_t embree_bytes = 0;      // what Embree holds: vertex/index buffers and BVHs (its memory monitor)
    size_t shading_bytes = 0;     // Candela's per-triangle shading data and per-instance placements
    size_t coplanar_objects = 0;  // objects with a coplanar overlapping rival (they get the tie-break filter)
};

/// The triangles of one top-level object as Embree holds them (Scene::object_triangles), for samplers of
/// surface points: vertex positions (camera-world space for a flattened mesh; object space for an instance, which
/// object_to_world maps to camera-world space) and three vertex indices per triangle. Valid while the scene lives.
struct ObjectTriangles {
    const float* vertices = nullptr;    // x, y, z per vertex
    const uint32_t* indices = nullptr;  // 3 per triangle
    uint32_t triangle_count = 0;
    bool instanced = false;
    uint32_t mesh = 0;                 // the input mesh: the instances of one mesh share vertices and indices
    Affine object_to_world;            // the identity for a flattened mesh (its vertices are in world space)
    uint8_t flags = k_object_default;  // ObjectFlag bits: the ray types the object is visible to
};

class Scene : private EmissionSource {
public:
    /// Builds the scene; throws InvalidScene/InvalidParameter for bad input and Cancelled if `cancel`
    /// fires during the BVH build. `arrays` must have been validated.
    /// With a `cache` (the 3D viewport), every mesh is instanced and the meshes' object-space BVHs come from the
    /// cache where it has them (scene/mesh_bvh_cache.h), so a build after a transform-only edit builds only the
    /// top-level BVH; the scene then uses the cache's Embree device.
    Scene(const SceneArrays& arrays, const Params& params, const CancelToken* cancel, MeshBvhCache* cache = nullptr);
    ~Scene() override;
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    /// Closest surface hit along the ray within (ray.tmin, ray.tmax). `skip` is the triangle the ray leaves
    /// from: the scale-relative origin offset (ray_offset.h) already keeps the ray off it, so it is dropped only
    /// where a filter runs anyway (objects with a coplanar rival, ray types some object is hidden from). Surfaces
    /// whose planes coincide within float rounding at the hit (coplanar overlapping faces of different objects,
    /// found at build: coplanar_overlap.h) are not told apart by distance: an emitting one wins, then the later
    /// object, so the choice is the same for every ray. Objects invisible to the ray's type (ray.type) are not hit.
    bool intersect(const Ray& ray, SurfaceHit* hit, const PrimitiveRef& skip = {}) const;
    /// Closest hits of n ≤ k_packet_size rays of one type that leave no surface (camera rays of one pixel):
    /// one Embree packet query where no filter runs on them, else intersect() per ray. Coherent rays traverse
    /// the BVH together, several times faster than one by one; the hits are intersect()'s (tested).
    static constexpr int k_packet_size = 8;
    void intersect_packet(const Ray* rays, int n, TracedHit* hits) const;
    /// True if any surface lies along o + t·d for t in (0, tmax), ignoring the objects invisible to shadow rays
    /// (and the triangles at both ends where a filter runs, as in intersect()). d need not be a unit vector (t is
    /// then in units of |d|: a segment o → o + d is d with tmax ≤ 1).
    bool occluded(const Vec3& o, const Vec3& d, float tmax, const PrimitiveRef& skip_from = {},
                  const PrimitiveRef& skip_to = {}) const {
        return occluded(o, d, tmax, k_ray_shadow, skip_from, skip_to);
    }
    /// The same for a segment of another ray type: a connection to the camera is a CAMERA ray (objects hidden from
    /// the camera do not block it), a shadow ray a SHADOW ray.
    bool occluded(const Vec3& o, const Vec3& d, float tmax, RayType type, const PrimitiveRef& skip_from = {},
                  const PrimitiveRef& skip_to = {}) const;
    /// Closest emitting side of an area light along the ray before tmax·(1 + 1e-4): its index and distance. The
    /// margin mirrors the shadow rays' (they stop at 1 − 1e-4 of the light's distance), so a light lying in a
    /// surface's plane is seen by camera and BSDF rays exactly when light sampling sees it. For a camera ray
    /// (`camera_ray`), lights hidden from the camera (AreaLight::visible_camera false) are skipped.
    bool intersect_area_light(const Vec3& o, const Vec3& d, float tmin, float tmax, uint32_t* light, float* t,
                              bool camera_ray = false) const;

    /// The material at a hit seen from direction wo (toward the viewer): its BSDF for that side, emission and
    /// shading normal, with textures and normal maps evaluated there (scene/shading.cpp). `path`: what the Light
    /// Path node reads there (the ray's type and the path's depths); null: no path (its outputs read 0).
    ShadingPoint shade(const SurfaceHit& hit, const Vec3& wo, const LightPathInfo* path = nullptr) const;
    /// Whether some material or the world reads a Light Path output (integrators that cannot define them say so).
    bool reads_light_path() const { return m_shaders->reads_light_path(); }

    /// What reaches `to` from `from` along the straight segment (docs/light_paths.md, "Transparent shadows"): 0 if
    /// an opaque surface blocks it, else the product of the transparent surfaces' Transparent weights (Cycles'
    /// transparent shadows), each shaded as a shadow ray sees it (`path`: the shadow ray's Light Path inputs, its
    /// transparent_depth counting the surfaces crossed; at most `max_surfaces` of them, more block). `to_infinity`:
    /// `to` is a direction and the segment a ray to infinity. Without transparent materials this is occluded().
    Color transmittance(const Vec3& from, const Vec3& to, bool to_infinity, const PrimitiveRef& skip_from,
                        const LightPathInfo& path, int max_surfaces) const;
    /// Whether some material has a Transparent closure (shadow rays then go through transmittance()).
    bool has_transparent_materials() const { return m_any_transparent; }

    /// The world's radiance along escaping direction d for a path with Light Path inputs `path`, when the world
    /// shader reads the Light Path node (world_reads_light_path()); otherwise use the light set's world light or
    /// background, which are the same for every path.
    Color world_radiance(const Vec3& d, const LightPathInfo& path) const;
    bool world_reads_light_path() const { return m_world_path_dependent; }

    /// The shadow-ray origin of Cycles' shadow terminator geometry offset (docs/light_paths.md): for a smooth
    /// triangle of an object with a positive offset, the point lifted toward the smooth surface the vertex normals
    /// describe (Hanika 2021), blended in for light directions wl near the terminator; the hit point otherwise.
    Vec3 terminator_point(const SurfaceHit& hit, const Vec3& ns_side, const Vec3& ng_side, const Vec3& wl) const;
    bool has_terminator_offsets() const { return m_any_terminator_offset; }
    /// Whether some material's normal comes from a Bump or Normal Map node (bump shadowing applies there).
    bool has_bent_normals() const { return m_any_bent_normal; }
    /// Whether terminator_point can move `hit` (a smooth triangle of an object with a positive offset).
    bool terminator_lifts(const SurfaceHit& hit) const;
    /// Whether the camera or some object moves over the shutter (motion blur).
    bool has_motion() const { return m_has_motion; }
    /// Whether some moving object emits light: it is rendered still, at the shutter's middle (its emissive
    /// triangles are lights at fixed places), and the session says so.
    bool has_still_moving_emitters() const { return m_still_emitters; }

    const Camera& camera() const { return m_camera; }
    /// Replaces the camera (camera params as the constructor reads them; camera_to_world rigid, in world space):
    /// the viewport renders one built scene through many views and film sizes. Only while no integrator renders
    /// this scene.
    void set_camera(const Params& params, const Affine& camera_to_world);
    const std::vector<Material>& materials() const { return m_materials; }
    const LightSet& lights() const { return m_lights; }
    /// What depends only on the scene, built on first use and kept while the scene lives (thread-safe; the same
    /// object make_light_sampler(kind, lights()) and EmitterSet(lights(), bounds()) would build, so images do not
    /// change): the viewport renders one scene through many views (set_camera) and coarse levels, and each render
    /// would otherwise rebuild them for every level (the light tree is O(N log N) in the emitters, every
    /// emissive triangle one). scene/scene_light_caches.cpp.
    const LightSampler& light_sampler(LightSelection kind) const;
    const EmitterSet& emitters() const;
    /// Half the diagonal of the bounds of the geometry and the point lights (what the lights are finalized with).
    float radius() const { return m_radius; }
    /// The bounding sphere of the geometry, area lights and point lights (camera-world space).
    const SceneSphere& bounds() const { return m_bounds; }
    /// BSDF flags material k can have on either side, anywhere (k_bsdf_*: reflection, transmission, diffuse,
    /// glossy, specular = a delta lobe): the constant BSDFs' flags, or for a textured material every flag its
    /// closures can take for some input (a Glossy closure with a roughness texture may be delta somewhere).
    uint32_t material_flags(uint32_t k) const { return k < m_material_flags.size() ? m_material_flags[k] : 0u; }
    const SceneStats& stats() const { return m_stats; }

    /// Holdout weight of the surface hit seen from wo (Cycles: 1 for a holdout object, else the material's
    /// Holdout closure weight, evaluated at the hit when a texture or Mix factor drives it): alpha loses this
    /// much where the camera sees the surface.
    float holdout(const SurfaceHit& hit, const Vec3& wo) const {
        if (m_object_flags[hit.object] & k_object_holdout) return 1.f;
        const int32_t inputs = m_materials[hit.material].inputs;
        if (inputs >= 0 && m_material_inputs[size_t(inputs)].holdout_reg >= 0) return varying_holdout(hit, wo);
        return hit.material < m_material_holdout.size() ? m_material_holdout[hit.material] : 0.f;
    }
    bool has_holdouts() const { return m_has_holdouts; }
    /// Whether the object hit is visible to rays of `type` (Blender's Ray Visibility).
    bool visible_to(const SurfaceHit& hit, uint8_t type) const { return (m_object_flags[hit.object] & type) != 0; }
    /// Ray types some object is hidden from (light-rooted integrators cannot honour DIFFUSE, GLOSSY and
    /// TRANSMISSION visibility, and say so).
    uint32_t hidden_ray_types() const { return m_hidden_from; }
    /// Blender's pass index of the object hit (the IndexOB pass).
    uint32_t pass_index(const SurfaceHit& hit) const;

    // Geometry for samplers of surface points (scene/scene_geometry.cpp). Top-level objects are numbered
    // 0 .. object_count() − 1 (SurfaceHit::object), one per instance with faces.
    uint32_t object_count() const;
    /// The object's triangles; an instance's object_to_world is the one at the thread's shutter time (a moving
    /// object's transform there, scene/shutter_time.h).
    ObjectTriangles object_triangles(uint32_t object) const;
    /// A top-level object's object → camera-world transform at the thread's shutter time.
    Affine object_to_world(uint32_t object) const;
    /// Whether a top-level object moves over the shutter (motion blur).
    bool object_moves(uint32_t object) const;
    /// The SurfaceHit at barycentrics (b1, b2) of triangle `prim` of `object`, filled as intersect() fills a hit
    /// there (position, normals, material, light, primitive, object), with t = 0; shade() works on it. A moving
    /// object's point is where it is at the thread's shutter time, as a ray traced then would find it.
    SurfaceHit surface_point(uint32_t object, uint32_t prim, float b1, float b2) const;
    /// ObjectFlag bits of a top-level object: the ray types it is visible to, holdout.
    uint8_t object_flags(uint32_t object) const { return m_object_flags[object]; }
    /// Embree scene handle, for benchmarks that shoot raw rays.
    RTCScene embree_scene() const { return m_top.get(); }

private:
    struct MeshShading;
    struct Placement;
    struct QueryContext;
    struct Builder;  // scene/scene_build.cpp
    friend struct Builder;
    void build(const SceneArrays& arrays, const CancelToken* cancel, MeshBvhCache* cache);
    /// Placement `id` at the thread's shutter time (scene/shutter_time.h): the stored one for an object that does
    /// not move, else a copy made in `scratch` with its transforms interpolated (a Placement would be constructed
    /// on every hit; but GCC 12 zero-fills a declared std::optional<Placement>, so hot callers declare `scratch`
    /// only when the scene moves: Scene::decode_hit).
    inline const Placement& placement_now(uint32_t id, std::optional<Placement>& scratch) const;  // scene_parts.h
    /// placement_now's copy of a moving placement `pl`, its transforms at the thread's shutter time.
    __attribute__((cold)) const Placement& moved_placement(const Placement& pl,
                                                           std::optional<Placement>& scratch) const;
    /// Embree's ray time: the thread's shutter time where an instance moves, else the shutter's middle without
    /// reading the thread-local time (a TLS lookup per ray in the shared module).
    float ray_time() const { return m_motions.empty() ? k_shutter_middle : shutter_time(); }
    /// The SurfaceHit of Embree's hit (geometry, triangle, instance ids, barycentrics, unnormalised Ng) at
    /// distance t along `ray`.
    void decode_hit(const Ray& ray, uint32_t geom, uint32_t prim, uint32_t inst, float u, float v,
                    const Vec3& ng_embree, float t, SurfaceHit* hit) const;
    /// Embree filter: drops the skipped triangles and hits on objects hidden from the ray's type and, for
    /// closest-hit queries, breaks ties between coplanar surfaces by a fixed priority instead of float rounding (no
    /// z-fighting speckle). The context filter of ray types some object is hidden from (it sees every hit).
    static void filter_hits(const RTCFilterFunctionNArguments* args);
    /// The geometry filter of objects with a coplanar rival (coplanar_overlap.h): filter_hits, for queries without
    /// a context filter. Other objects' hits are Embree's closest ones, unfiltered.
    static void coplanar_filter(const RTCFilterFunctionNArguments* args);
    /// Priority among coplanar hits: emitters first, then the later geometry, then the higher triangle index.
    bool outranks(const PrimitiveRef& a, const PrimitiveRef& b) const;
    void add_environment();
    /// Shading normal at barycentrics (b1, b2) of triangle `prim`: the interpolated smooth normal (world space),
    /// turned to the side of the unit winding normal ng; ng itself for a flat triangle.
    static Vec3 shading_normal(const MeshShading& s, const Placement& pl, uint32_t prim, float b1, float b2,
                               const Vec3& ng);
    /// The shader program's inputs at a hit on placement `pl`, seen from wo (scene/shading.cpp).
    /// With `differentials`, also the offsets of Bump's finite differences (ShadingInputs::dp …).
    ShadingInputs shading_inputs(const SurfaceHit& hit, const Vec3& wo, const Placement& pl, bool differentials = false,
                                 const LightPathInfo* path = nullptr) const;
    /// The Holdout weight of a material whose weight comes from its shader program, at the hit (shading.cpp).
    float varying_holdout(const SurfaceHit& hit, const Vec3& wo) const;
    /// Whether material k's emission comes from its shader program (a textured emitter).
    bool varying_emission(uint32_t k) const;
    /// Emitted radiance of a textured emitter at barycentrics (b1, b2) of triangle `prim` of placement `pl`.
    Color textured_emission(const Placement& pl, uint32_t prim, const Vec3& p, const Vec3& ng, float b1, float b2,
                            const Vec3& wo) const;
    /// Its average over the triangle v (four fixed points; only the light selection uses it).
    Color average_emission(const Placement& pl, uint32_t prim, const Vec3 (&v)[3], const Vec3& ng) const;
    // EmissionSource: textured emitter `id` (a row of m_emitters).
    Color emission(uint32_t id, const Vec3& p, const Vec3& ng, float b1, float b2, const Vec3& wo) const override;

    std::shared_ptr<EmbreeDevice> m_device;  // own, or a MeshBvhCache's (declared first: released last)
    EmbreeScene m_top;
    std::vector<std::shared_ptr<EmbreeScene>> m_mesh_scenes;  // one per instanced mesh (shared with a cache)
    std::vector<MeshShading> m_shading;                       // per mesh (world space if flattened)
    std::vector<Placement> m_placements;                      // per top-level geometry id
    struct Emitter {
        uint32_t placement, prim;  // top-level geometry id and the mesh's triangle
    };
    std::vector<Emitter> m_emitters;        // textured emitting triangles (TriangleLight::source_id)
    std::vector<uint8_t> m_object_flags;    // per top-level geometry id: ObjectFlag bits
    std::vector<float> m_material_holdout;  // per material (constant weights), or empty (no Holdout closures)
    bool m_has_holdouts = false;
    uint32_t m_hidden_from = 0;              // ray types some object is invisible to (they need the filter)
    bool m_any_coplanar = false;             // some object has the coplanar geometry filter
    bool m_any_transparent = false;          // some material has a Transparent closure (transparent shadows)
    bool m_world_path_dependent = false;     // the world shader reads the Light Path node
    bool m_any_terminator_offset = false;    // some object has a shadow terminator offset
    bool m_any_bent_normal = false;          // some material bends its normal (Bump, Normal Map): bump shadowing
    bool m_has_motion = false;               // motion blur: the camera or an object moves over the shutter
    bool m_still_emitters = false;           // a moving emitter is rendered at the shutter's middle
    std::vector<MotionTransform> m_motions;  // per moving instance (Placement::motion), camera-world space
    Camera m_camera;
    std::vector<Material> m_materials;
    std::shared_ptr<const ShaderLibrary> m_shaders;
    std::vector<MaterialInputs> m_material_inputs;   // textured materials (Material::inputs)
    int32_t m_world_program = -1, m_world_reg = -1;  // the world shader, if it varies with direction
    int m_threads = 0;
    LightSet m_lights;
    Vec3 m_offset;  // added to world positions: −camera position
    float m_radius = 1.f;
    SceneSphere m_bounds;
    std::vector<uint32_t> m_material_flags;  // per material: material_flags()
    SceneStats m_stats;
    // light_sampler() and emitters(): built once each, on first use.
    static constexpr size_t k_light_selections = size_t(LightSelection::Ward) + 1;
    mutable std::once_flag m_light_sampler_once[k_light_selections];
    mutable std::unique_ptr<LightSampler> m_light_samplers[k_light_selections];
    mutable std::once_flag m_emitters_once;
    mutable std::unique_ptr<EmitterSet> m_emitter_set;
};

}  // namespace candela
