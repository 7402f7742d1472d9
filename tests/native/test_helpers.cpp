#include "test_helpers.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "bsdf/material.h"
#include "core/math.h"
#include "core/parallel.h"
#include "film/film.h"
#include "integrators/integrator.h"
#include "lights/light.h"
#include "scene/scene.h"
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

uint32_t MeshBuilder::add_box(Vec3 h, uint32_t material) {
    const uint32_t base = uint32_t(positions.size() / 3);
    for (int i = 0; i < 8; ++i)  // corner i has bits (x, y, z)
        for (float v : {(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z}) positions.push_back(v);
    const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        triangles.insert(triangles.end(),
                         {base + f[0], base + f[1], base + f[2], base + f[0], base + f[2], base + f[3]});
        tri_material.insert(tri_material.end(), {material, material});
    }
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

uint32_t MeshBuilder::add_triangle(Vec3 a, Vec3 b, Vec3 c, uint32_t material) {
    const uint32_t base = uint32_t(positions.size() / 3);
    for (const Vec3& p : {a, b, c}) positions.insert(positions.end(), {p.x, p.y, p.z});
    triangles.insert(triangles.end(), {base, base + 1, base + 2});
    tri_material.push_back(material);
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
    // Rows written for the first 20 columns (before `visible_camera`) are padded; the camera then sees an
    // area light, as these tests were written to expect.
    std::vector<float> full = row;
    const size_t columns = light_columns().size();
    if (full.size() < columns) {
        full.resize(columns, 0.f);
        for (size_t c = row.size(); c < columns; ++c)
            if (light_columns()[c] == "visible_camera") full[c] = 1.f;
    }
    lights.insert(lights.end(), full.begin(), full.begin() + columns);
}

void MeshBuilder::add_point_light(Vec3 pos, Color strength, float radius) {
    std::vector<float> row(light_columns().size(), 0.f);
    row[0] = strength.x;
    row[1] = strength.y;
    row[2] = strength.z;
    row[3] = pos.x;
    row[4] = pos.y;
    row[5] = pos.z;
    row[8] = -1.f;
    row[15] = radius;
    add_light(0, row);
}

void MeshBuilder::add_area_light(Vec3 center, Vec3 u, Vec3 v, Vec3 direction, Color strength, bool disk) {
    std::vector<float> row(20, 0.f);
    row[0] = strength.x;
    row[1] = strength.y;
    row[2] = strength.z;
    row[3] = center.x;
    row[4] = center.y;
    row[5] = center.z;
    row[6] = direction.x;
    row[7] = direction.y;
    row[8] = direction.z;
    row[9] = u.x;
    row[10] = u.y;
    row[11] = u.z;
    row[12] = v.x;
    row[13] = v.y;
    row[14] = v.z;
    row[19] = disk ? 1.f : 0.f;
    add_light(3, row);
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

std::vector<float> look_at(Vec3 eye, Vec3 target, Vec3 up) {
    const Vec3 back = normalize(eye - target);  // the camera looks down its −Z
    const Vec3 right = normalize(cross(up, back));
    const Vec3 y = cross(back, right);
    return {right.x, y.x, back.x, eye.x, right.y, y.y, back.y, eye.y, right.z, y.z, back.z, eye.z, 0, 0, 0, 1};
}

namespace {

/// Fills the image statistics of r from its Combined and Noise passes.
void summarize(RenderResult& r) {
    const size_t n = size_t(r.width) * r.height;
    double sum = 0.0, var_sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sum += r.rgba[4 * i] + r.rgba[4 * i + 1] + r.rgba[4 * i + 2];
        var_sum += double(r.noise[i]) * r.noise[i];
    }
    r.mean_rgb = sum / (3.0 * n);
    // Var(mean over pixels) = Σ var(pixel mean) / n²  (pixels are independent).
    r.standard_error = std::sqrt(var_sum) / n;
}

}  // namespace

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
    summarize(r);
    r.samples_done = int(s.progress().work_done);
    r.stop_reason = s.progress().stop_reason;
    r.relative_error = s.progress().relative_error;
    return r;
}

PreparedScene::PreparedScene(SceneArrays arrays, Params base) : m_base(std::move(base)) {
    arrays.validate();
    m_scene = std::make_unique<Scene>(arrays, m_base, nullptr);
}

PreparedScene::~PreparedScene() = default;

RenderResult PreparedScene::render(const Params& overrides) const {
    Params p = m_base;
    for (const auto& [key, value] : overrides.values()) p.set(key, value);
    const int width = p.require<int>("width"), height = p.require<int>("height");
    Film film(width, height, 0, 0, p.get<int>("tile_size", 32));
    const std::unique_ptr<Integrator> integrator = make_integrator(p);
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, resolve_thread_count(p.get<int>("threads", 0))};
    integrator->render(*m_scene, film, ctx);
    RenderResult r;
    r.rgba = film.combined();
    r.noise = film.noise();
    r.width = width;
    r.height = height;
    summarize(r);
    r.samples_done = int(counters.work_done);
    r.stop_reason = StopReason(counters.stop_reason.load());
    r.relative_error = counters.relative_error;
    return r;
}

SceneArrays furnace_scene(FurnaceScene kind, int segments, int rings) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(kind == FurnaceScene::EmissiveSphere ? 0.5f : 0.f));
    b.add_instance(b.add_sphere(1.f, segments, rings, m));
    // Blender's point power S has intensity S/(4π): I = π is S = 4π².
    if (kind == FurnaceScene::PointLight) b.add_point_light(Vec3(0.f), Color(4.f * k_pi * k_pi));
    if (kind == FurnaceScene::FourPointLights)
        for (float share : {0.1f, 0.2f, 0.3f, 0.4f}) b.add_point_light(Vec3(0.f), Color(share * 4.f * k_pi * k_pi));
    return b.arrays();
}

double furnace_expected(FurnaceScene kind, int max_bounces) {
    return kind == FurnaceScene::EmissiveSphere ? 1.0 - std::pow(0.5, max_bounces + 2)
                                                : 1.0 - std::pow(0.5, max_bounces + 1);
}

double furnace_facet_bias(int segments, int rings) {
    // The area of the mesh add_sphere builds (unit radius), triangle by triangle.
    MeshBuilder b;
    b.add_sphere(1.f, segments, rings, b.add_material(Color(0.5f), Color(0.f)));
    double area = 0.0;
    for (size_t t = 0; t < b.triangles.size(); t += 3) {
        Vec3 p[3];
        for (int k = 0; k < 3; ++k) {
            const uint32_t i = b.triangles[t + k];
            p[k] = Vec3(b.positions[3 * i], b.positions[3 * i + 1], b.positions[3 * i + 2]);
        }
        area += 0.5 * double(length(cross(p[1] - p[0], p[2] - p[0])));
    }
    return 4.0 * k_pi / area - 1.0;
}

long proc_status_kb(const char* key) {
    std::ifstream f("/proc/self/status");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::strlen(key)));
    return -1;
}

}  // namespace candela::test
