#include "random_scene.h"

#include <cmath>
#include <vector>

#include "bsdf/material.h"
#include "core/math.h"
#include "core/rng.h"
#include "integrators/integrator.h"
#include "lights/light.h"

namespace candela::test {
namespace {

struct Random {
    Pcg32 rng;
    explicit Random(uint64_t seed) : rng(mix64(seed), seed) {}
    float uniform() { return rng.next_float(); }
    float range(float a, float b) { return a + (b - a) * uniform(); }
    int integer(int n) { return int(rng.next_u32() % uint32_t(n)); }
    bool chance(float p) { return uniform() < p; }
    float log_uniform(float lo, float hi) { return std::exp(range(std::log(lo), std::log(hi))); }
    Vec3 vec(float s) { return Vec3(range(-s, s), range(-s, s), range(-s, s)); }
    Vec3 unit() {
        for (;;) {
            const Vec3 v = vec(1.f);
            const float l = length(v);
            if (l > 1e-3f && l <= 1.f) return v / l;
        }
    }
};

void push(std::vector<float>& out, const Vec3& v) { out.insert(out.end(), {v.x, v.y, v.z}); }

}  // namespace

RandomScene make_random_scene(uint64_t seed) {
    Random r(seed);
    const float scale = r.log_uniform(1e-4f, 1e4f);  // the scene's size
    std::vector<float> positions, materials, lights, transforms, normals;
    std::vector<uint32_t> triangles, tri_material, mesh_start{0}, instance_mesh, material_type, light_type;
    std::vector<uint8_t> smooth;

    const int mat_count = 1 + r.integer(6);
    const size_t columns = material_columns().size();
    for (int m = 0; m < mat_count; ++m) {
        material_type.push_back(uint32_t(r.integer(int(material_type_names().size()))));
        std::vector<float> row(columns, 0.f);
        for (size_t c = 0; c < columns; ++c) row[c] = r.uniform();  // every column in [0, 1)
        const bool emissive = r.chance(0.3f);
        const float strength = emissive ? r.log_uniform(1e-3f, 1e6f) : 0.f;
        for (int c = 3; c < 6; ++c) row[c] = emissive ? strength * r.uniform() : 0.f;
        materials.insert(materials.end(), row.begin(), row.end());
    }

    const int mesh_count = 1 + r.integer(6);
    for (int m = 0; m < mesh_count; ++m) {
        const Vec3 centre = r.vec(scale);
        const float size = scale * r.log_uniform(1e-3f, 1.f);
        const int tris = 1 + r.integer(40);
        for (int t = 0; t < tris; ++t) {
            const uint32_t base = uint32_t(positions.size() / 3);
            Vec3 v[3] = {centre + r.vec(size), centre + r.vec(size), centre + r.vec(size)};
            if (r.chance(0.05f)) v[2] = v[1];                         // zero-area triangle
            if (r.chance(0.05f)) v[2] = v[0] + (v[1] - v[0]) * 0.5f;  // collinear
            for (const Vec3& p : v) push(positions, p);
            triangles.insert(triangles.end(), {base, base + 1, base + 2});
            tri_material.push_back(uint32_t(r.integer(mat_count)));
            smooth.push_back(r.chance(0.5f));
            for (int k = 0; k < 3; ++k) push(normals, r.chance(0.02f) ? Vec3(0.f) : r.unit());  // disagreeing normals
        }
        mesh_start.push_back(uint32_t(triangles.size() / 3));
        const int copies = r.chance(0.3f) ? 2 + r.integer(5) : 1;
        for (int c = 0; c < copies; ++c) {
            instance_mesh.push_back(uint32_t(m));
            const Vec3 s(r.chance(0.2f) ? -r.range(0.5f, 2.f) : r.range(0.5f, 2.f), r.range(0.5f, 2.f),
                         r.range(0.5f, 2.f));
            const Vec3 t = c == 0 ? Vec3(0.f) : r.vec(scale);
            transforms.insert(transforms.end(), {s.x, 0, 0, t.x, 0, s.y, 0, t.y, 0, 0, s.z, t.z, 0, 0, 0, 1});
        }
    }

    const int light_count = r.integer(5);
    const size_t lcols = light_columns().size();
    for (int l = 0; l < light_count; ++l) {
        light_type.push_back(uint32_t(r.integer(int(light_type_names().size()))));
        std::vector<float> row(lcols, 0.f);
        const float strength = r.log_uniform(1e-3f, 1e6f);
        row[0] = strength * r.uniform();
        row[1] = strength * r.uniform();
        row[2] = strength * r.uniform();
        const Vec3 p = r.chance(0.2f) ? Vec3(positions[0], positions[1], positions[2]) : r.vec(scale);  // on a surface
        const Vec3 d = r.unit();
        row[3] = p.x;
        row[4] = p.y;
        row[5] = p.z;
        row[6] = d.x;
        row[7] = d.y;
        row[8] = d.z;
        const Vec3 u = r.unit() * (scale * r.log_uniform(1e-4f, 1.f)),
                   v = normalize(cross(d, u)) * (scale * r.log_uniform(1e-4f, 1.f));
        row[9] = u.x;
        row[10] = u.y;
        row[11] = u.z;
        row[12] = v.x;
        row[13] = v.y;
        row[14] = v.z;
        row[15] = r.chance(0.5f) ? 0.f : scale * r.log_uniform(1e-5f, 0.1f);  // radius
        row[16] = r.range(0.f, k_pi);                                         // spot size
        row[17] = r.uniform();                                                // spot blend
        row[18] = r.chance(0.5f) ? 0.f : r.range(0.f, 3.f);                   // sun angle
        row[19] = r.chance(0.5f) ? 1.f : 0.f;                                 // ellipse
        lights.insert(lights.end(), row.begin(), row.end());
    }

    const Vec3 eye = r.vec(2.f * scale);
    const Vec3 forward = normalize(Vec3(positions[0], positions[1], positions[2]) - eye + r.vec(1e-3f * scale));
    const Vec3 right = normalize(cross(forward, std::fabs(forward.z) < 0.99f ? Vec3(0, 0, 1) : Vec3(1, 0, 0)));
    const Vec3 up = cross(right, forward);
    // Blender cameras look down −Z with +Y up: columns are (right, up, −forward).
    const float camera[16] = {right.x, up.x, -forward.x, eye.x, right.y, up.y, -forward.y, eye.y,
                              right.z, up.z, -forward.z, eye.z, 0,       0,    0,          1};

    RandomScene out;
    SceneArrays& a = out.arrays;
    const size_t V = positions.size() / 3, T = triangles.size() / 3, I = instance_mesh.size();
    a.set("positions", ElemType::F32, {V, 3}, positions.data());
    a.set("triangles", ElemType::U32, {T, 3}, triangles.data());
    a.set("normals", ElemType::F32, {T, 3, 3}, normals.data());
    a.set("tri_smooth", ElemType::U8, {T}, smooth.data());
    a.set("tri_material", ElemType::U32, {T}, tri_material.data());
    a.set("mesh_tri_start", ElemType::U32, {mesh_start.size()}, mesh_start.data());
    a.set("instance_mesh", ElemType::U32, {I}, instance_mesh.data());
    a.set("instance_transform", ElemType::F32, {I, 4, 4}, transforms.data());
    a.set("material_type", ElemType::U32, {material_type.size()}, material_type.data());
    a.set("materials", ElemType::F32, {material_type.size(), columns}, materials.data());
    if (!light_type.empty()) {
        a.set("light_type", ElemType::U32, {light_type.size()}, light_type.data());
        a.set("lights", ElemType::F32, {light_type.size(), lcols}, lights.data());
    }
    a.set("camera_to_world", ElemType::F32, {4, 4}, camera);
    if (r.chance(0.5f)) {
        const float w[3] = {r.uniform(), r.uniform(), r.uniform()};
        a.set("world_color", ElemType::F32, {3}, w);
    }

    Params& p = out.params;
    p.set("width", int64_t(8));
    p.set("height", int64_t(6));
    p.set("samples", int64_t(2));
    p.set("max_bounces", int64_t(r.integer(9)));
    p.set("seed", int64_t(seed));
    p.set("threads", int64_t(1));
    p.set("camera_type", std::string(r.chance(0.2f) ? "ORTHO" : "PERSP"));
    p.set("ortho_scale", double(scale));
    p.set("clip_start", double(1e-3f * scale));
    p.set("clip_end", double(1e3f * scale));
    const auto& registry = integrator_registry();
    const std::string integrator = registry[size_t(r.integer(int(registry.size())))].name;
    p.set("integrator", integrator);
    if (integrator == "MLT" || integrator == "MMLT") {  // the defaults (10⁵ bootstrap paths) are for real frames
        p.set("mlt_bootstrap", int64_t(1000));
        p.set("mlt_chains", int64_t(16));
    }
    return out;
}

}  // namespace candela::test
