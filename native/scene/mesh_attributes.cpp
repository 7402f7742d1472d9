#include "scene/mesh_attributes.h"

#include <algorithm>

#include "input/scene_arrays.h"

namespace candela {

namespace {

/// ∇u, ∇v per triangle: an offset d = a·e1 + b·e2 in the plane of the edges e1 = p1 − p0, e2 = p2 − p0 has
/// (a, b) = G⁻¹·(e1·d, e2·d) with the Gram matrix G, so ∇u = Δu1·(G22·e1 − G12·e2)/det + Δu2·(G11·e2 − G12·e1)/det.
std::vector<Vec3> uv_gradients(const SceneArrays& arrays, const std::vector<Vec2>& uv, uint32_t tri_begin,
                               uint32_t tri_end) {
    const Array* positions = arrays.find("positions");
    const Array* triangles = arrays.find("triangles");
    if (!positions || !triangles) return {};
    const float* pos = positions->data<float>();
    const uint32_t* tri = triangles->data<uint32_t>();
    std::vector<Vec3> out(2 * size_t(tri_end - tri_begin), Vec3(0.f));
    for (uint32_t t = tri_begin; t < tri_end; ++t) {
        Vec3 p[3];
        for (int k = 0; k < 3; ++k) {
            const float* v = pos + 3 * size_t(tri[3 * size_t(t) + k]);
            p[k] = Vec3(v[0], v[1], v[2]);
        }
        const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const float g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
        const float det = g11 * g22 - g12 * g12;
        if (!(det > 0.f)) continue;
        const Vec3 w1 = (e1 * g22 - e2 * g12) / det, w2 = (e2 * g11 - e1 * g12) / det;
        const size_t local = t - tri_begin;
        const Vec2* c = &uv[3 * local];
        out[2 * local] = w1 * (c[1].x - c[0].x) + w2 * (c[2].x - c[0].x);
        out[2 * local + 1] = w1 * (c[1].y - c[0].y) + w2 * (c[2].y - c[0].y);
    }
    return out;
}

}  // namespace

MeshAttributes MeshAttributes::load(const SceneArrays& arrays, uint32_t mesh, uint32_t tri_begin, uint32_t tri_end) {
    MeshAttributes a;
    const size_t n = tri_end - tri_begin;
    if (const Array* uvs = arrays.find("uvs")) {
        const float* p = uvs->data<float>() + 6 * size_t(tri_begin);
        a.uv.resize(3 * n);
        for (size_t i = 0; i < 3 * n; ++i) a.uv[i] = Vec2{p[2 * i], p[2 * i + 1]};
        a.uv_gradient = uv_gradients(arrays, a.uv, tri_begin, tri_end);
    }
    if (const Array* t = arrays.find("tangents")) {
        const float* p = t->data<float>() + 12 * size_t(tri_begin);
        a.tangent.assign(p, p + 12 * n);
    }
    if (const Array* at = arrays.find("corner_attributes")) {
        // (T, 3, 4·S): S slots of RGBA (or xyz + 1) per corner.
        a.attribute_slots = uint32_t(at->count() / (12 * std::max<size_t>(at->shape[0], 1)));
        const float* p = at->data<float>() + 12 * size_t(a.attribute_slots) * tri_begin;
        a.attributes.assign(p, p + 12 * size_t(a.attribute_slots) * n);
    }
    if (const Array* ts = arrays.find("mesh_texspace")) {
        const float* p = ts->data<float>() + 6 * size_t(mesh);
        a.texspace_location = Vec3(p[0], p[1], p[2]);
        a.texspace_size = Vec3(p[3], p[4], p[5]);
    }
    return a;
}

Vec3 MeshAttributes::uv_at(uint32_t t, float b1, float b2) const {
    if (uv.empty()) return Vec3(0.f);
    const Vec2* c = &uv[3 * size_t(t)];
    const float b0 = 1.f - b1 - b2;
    return {b0 * c[0].x + b1 * c[1].x + b2 * c[2].x, b0 * c[0].y + b1 * c[1].y + b2 * c[2].y, 0.f};
}

bool MeshAttributes::tangent_at(uint32_t t, float b1, float b2, Vec3* tangent_out, float* sign) const {
    if (tangent.empty()) return false;
    const float* c = &tangent[12 * size_t(t)];
    const float b0 = 1.f - b1 - b2;
    *tangent_out =
        Vec3(b0 * c[0] + b1 * c[4] + b2 * c[8], b0 * c[1] + b1 * c[5] + b2 * c[9], b0 * c[2] + b1 * c[6] + b2 * c[10]);
    const float s = b0 * c[3] + b1 * c[7] + b2 * c[11];
    *sign = s < 0.f ? -1.f : 1.f;
    return !is_black(*tangent_out);
}

Vec3 MeshAttributes::generated(const Vec3& p) const {
    Vec3 g;
    for (int k = 0; k < 3; ++k)
        g[k] = texspace_size[k] != 0.f ? (p[k] - texspace_location[k]) / (2.f * texspace_size[k]) + 0.5f : 0.5f;
    return g;
}

}  // namespace candela
