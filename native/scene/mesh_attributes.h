// Per-corner surface attributes that textured materials read, kept only for the meshes whose materials vary
// over the surface: the render UV map, its tangents (Blender's MikkTSpace tangents and bitangent sign, as
// Cycles uses them) and the mesh's texture space (Generated coordinates). All in object space.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace candela {

class SceneArrays;

struct MeshAttributes {
    std::vector<Vec2> uv;        // 3 per triangle, or empty (UV = 0)
    std::vector<float> tangent;  // 4 per corner (x, y, z, sign), or empty (no tangent-space normal maps)
    // Per triangle with UVs, the gradients of u and of v over the triangle's plane (object space): Bump's finite
    // differences move the UV by (∇u·d, ∇v·d) for an object-space offset d.
    std::vector<Vec3> uv_gradient;
    // Mesh attributes the shader programs read (`corner_attributes`): per corner, 4 floats per slot.
    std::vector<float> attributes;
    uint32_t attribute_slots = 0;
    /// The corner values of triangle t (3 corners × 4·attribute_slots floats), or null.
    const float* attribute_corners(uint32_t t) const {
        return attributes.empty() ? nullptr : attributes.data() + 12 * size_t(attribute_slots) * t;
    }
    Vec3 texspace_location{0.f}, texspace_size{1.f};

    /// Rows [tri_begin, tri_end) of `uvs`, `tangents` and row `mesh` of `mesh_texspace`, where given.
    static MeshAttributes load(const SceneArrays& arrays, uint32_t mesh, uint32_t tri_begin, uint32_t tri_end);

    /// UV at barycentrics (b1, b2) of local triangle t, as (u, v, 0).
    Vec3 uv_at(uint32_t t, float b1, float b2) const;
    /// The UV change (du, dv, 0) of an object-space offset d within triangle t (0 without UVs).
    Vec3 uv_offset(uint32_t t, const Vec3& d) const {
        if (uv_gradient.empty()) return Vec3(0.f);
        return {dot(uv_gradient[2 * size_t(t)], d), dot(uv_gradient[2 * size_t(t) + 1], d), 0.f};
    }
    /// Interpolated (unnormalised) object-space tangent and its sign; false without tangents.
    bool tangent_at(uint32_t t, float b1, float b2, Vec3* tangent, float* sign) const;
    /// Blender's Generated coordinates of an object-space position: (p − location)/(2·size) + ½ per axis
    /// (½ on an axis of zero size).
    Vec3 generated(const Vec3& p) const;
};

}  // namespace candela
