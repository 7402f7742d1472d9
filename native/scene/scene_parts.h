// The parts of Scene shared by its translation units (scene.cpp builds them, shading.cpp reads them at
// hits). Not part of the interface integrators use.
#pragma once

#include <cstdint>
#include <vector>

#include "core/transform.h"
#include "scene/mesh_attributes.h"
#include "scene/scene.h"

namespace candela {

/// Per-triangle shading data of one mesh, in the space its Embree geometry uses.
struct Scene::MeshShading {
    std::vector<uint32_t> material;
    std::vector<uint8_t> smooth;
    std::vector<Vec3> normals;           // 3 per triangle, or empty
    std::vector<int32_t> emissive_rank;  // index among the mesh's emissive triangles, −1 if not emissive
    std::vector<Vec3> corners;           // 3 positions per triangle (same space as normals), for the shadow
                                         // terminator offset of smooth triangles; empty when no instance needs it
    MeshAttributes attributes;           // only for meshes with textured materials
};

/// What a top-level Embree geometry id stands for.
struct Scene::Placement {
    uint32_t mesh = 0;
    uint32_t pass_index = 0;  // Blender's object pass index (the IndexOB pass)
    bool instanced = false;
    // A mirroring transform (det < 0) reverses the winding: the winding normal then points into the object,
    // so it is flipped back (as Cycles does for negative scale) and glass keeps its inside.
    bool mirrored = false;
    float magnitude = 0.f;    // largest |coordinate| of its vertices in camera-world space (rounding scale)
    Affine normal_to_world;   // cofactor matrix (instances only)
    int32_t light_base = -1;  // light index of the mesh's first emissive triangle in this placement
    int32_t mesh_scene = -1;  // an instance's shared BVH (index into m_mesh_scenes)
    Affine object_to_world;   // object → camera-world (flattened meshes too: textures need object space)
    Affine world_to_object;
    Vec3 color{1.f};  // Object Info > Color, Alpha, Random (instance_color, instance_random)
    float alpha = 1.f, random = 0.f;
    float terminator_offset = 0.f;  // Cycles' Shadow Terminator > Geometry Offset (instance_terminator)
    int32_t motion = -1;            // a moving instance's MotionTransform (Scene::m_motions), −1 if it stays;
                                    // its transforms above are then those at the shutter's middle
};

inline const Scene::Placement& Scene::placement_now(uint32_t id, std::optional<Placement>& scratch) const {
    const Placement& pl = m_placements[id];
    return __builtin_expect(pl.motion < 0, 1) ? pl : moved_placement(pl, scratch);
}

}  // namespace candela
