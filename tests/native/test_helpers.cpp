#include "test_helpers.h"

#include <algorithm>
#include <cmath>

#include "bsdf/material.h"
#include "core/math.h"
#include "lights/light.h"
#include "session/session.h"

namespace candela::test {

uint32_t MeshBuilder::add_material(Color base, Color emission) {
    material_type.push_back(0);
    for (float v : {base.x, base.y, base.z, emission.x, emission.y, emission.z}) materials.push_back(v);
    return uint32_t(material_type.size() - 1);
}

void MeshBuilder::add_closure(uint32_t material, const std::string& type,
                              const std::vector<std::pair<std::string, float>>& values) {
    const auto& columns = closure_columns();
    std::vector<float> row(columns.size(), 0.f);
    auto set = [&](const std::string& name, float v) {
        for (size_t c = 0; c < columns.size(); ++c)
            if (columns[c] == name) row[c] = v;
    };
    for (const char* w : {"weight_r", "weight_g", "weight_b"}) set(w, 1.f);
    for (const auto& [name, v] : values) set(name, v);
    const auto& names = closure_type_names();
    closure_type.push_back(uint32_t(std::find(names.begin(), names.end(), type) - names.begin()));
    closure_material.push_back(material);
    closure_params.insert(closure_params.end(), row.begin(), row.end());
}

uint32_t MeshBuilder::add_sphere(float radius, int segments, int rings, uint32_t material) {
    const uint32_t base = uint32_t(positions.size() / 3);
    for (int r = 0; r <= rings; ++r) {
        const float theta = k_pi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.f * k_pi * s / segments;
            positions.push_back(radius * std::sin(theta) * std::cos(phi));
            positions.push_back(radius * std::sin(theta) * std::sin(phi));
            positions.push_back(radius * std::cos(theta));
        }
    }
    auto idx = [&](int r, int s) { return base + uint32_t(r * segments + (s % segments)); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = idx(r, s), b = idx(r, s + 1), c = idx(r + 1, s), d = idx(r + 1, s + 1);
            if (r > 0) {
                triangles.insert(triangles.end(), {a, c, b});
                tri_material.push_back(material);
            }
            if (r + 1 < rings) {
                triangles.insert(triangles.end(), {b, c, d});
                tri_material.push_back(material);
            }
        }
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

uint32_t MeshBuilder::add_quad_z(float x0, float x1, float y0, float y1, float h, uint32_t material) {
    const uint32_t base = uint32_t(positions.size() / 3);
    for (float v : {x0, y0, h, x1, y0, h, x1, y1, h, x0, y1, h}) positions.push_back(v);
    triangles.insert(triangles.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    tri_material.insert(tri_material.end(), {material, material});
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

void MeshBuilder::add_instance(uint32_t mesh, const float* rows16) {
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    instance_mesh.push_back(mesh);
    instance_transform.insert(instance_transform.end(), rows16 ? rows16 : identity, (rows16 ? rows16 : identity) + 16);
}

void MeshBuilder::add_light(uint32_t type, const std::vector<float>& row) {
    light_type.push_back(type);
    lights.insert(lights.end(), row.begin(), row.end());
}

void MeshBuilder::add_point_light(Vec3 pos, Color strength, float radius) {
    std::vector<float> row(light_columns().size(), 0.f);
    row[0] = strength.x; row[1] = strength.y; row[2] = strength.z;
    row[3] = pos.x; row[4] = pos.y; row[5] = pos.z;
    row[8] = -1.f;
    row[15] = radius;
    add_light(0, row);
}

SceneArrays MeshBuilder::arrays(const float* camera_rows16) const {
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    SceneArrays a;
    const size_t V = positions.size() / 3, T = triangles.size() / 3;
    a.set("positions", ElemType::F32, {V, 3}, positions.data());
    a.set("triangles", ElemType::U32, {T, 3}, triangles.data());
    a.set("tri_material", ElemType::U32, {T}, tri_material.data());
    a.set("mesh_tri_start", ElemType::U32, {mesh_tri_start.size()}, mesh_tri_start.data());
    a.set("instance_mesh", ElemType::U32, {instance_mesh.size()}, instance_mesh.data());
    a.set("instance_transform", ElemType::F32, {instance_mesh.size(), 4, 4}, instance_transform.data());
    a.set("material_type", ElemType::U32, {material_type.size()}, material_type.data());
    a.set("materials", ElemType::F32, {material_type.size(), 6}, materials.data());
    if (!light_type.empty()) {
        a.set("light_type", ElemType::U32, {light_type.size()}, light_type.data());
        a.set("lights", ElemType::F32, {light_type.size(), light_columns().size()}, lights.data());
    }
    a.set("camera_to_world", ElemType::F32, {4, 4}, camera_rows16 ? camera_rows16 : identity);
    if (!closure_type.empty()) {
        a.set("closure_material", ElemType::U32, {closure_material.size()}, closure_material.data());
        a.set("closure_type", ElemType::U32, {closure_type.size()}, closure_type.data());
        a.set("closure_params", ElemType::F32, {closure_type.size(), closure_columns().size()}, closure_params.data());
    }
    if (!world_color.empty()) a.set("world_color", ElemType::F32, {3}, world_color.data());
    return a;
}

Params basic_params(int w, int h, int samples, int max_bounces) {
    Params p;
    p.set("width", int64_t(w));
    p.set("height", int64_t(h));
    p.set("samples", int64_t(samples));
    p.set("max_bounces", int64_t(max_bounces));
    p.set("pixel_filter", std::string("BOX"));
    p.set("filter_width", 1.0);
    return p;
}

RenderResult render(SceneArrays arrays, Params params) {
    Session s(std::move(arrays), std::move(params));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    RenderResult r;
    int channels = 0;
    r.rgba = s.get_pass("Combined", &channels);
    r.noise = s.get_pass("Noise", &channels);
    r.width = s.width();
    r.height = s.height();
    const size_t n = size_t(r.width) * r.height;
    double sum = 0.0, var_sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sum += r.rgba[4 * i] + r.rgba[4 * i + 1] + r.rgba[4 * i + 2];
        var_sum += double(r.noise[i]) * r.noise[i];
    }
    r.mean_rgb = sum / (3.0 * n);
    // Var(mean over pixels) = Σ var(pixel mean) / n²  (pixels are independent).
    r.standard_error = std::sqrt(var_sum) / n;
    r.samples_done = s.progress().samples_done;
    r.stop_reason = s.progress().stop_reason;
    r.relative_error = s.progress().relative_error;
    return r;
}

}  // namespace candela::test
