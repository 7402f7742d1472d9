// Builders for small test scenes as scene arrays, and a synchronous render helper.
#pragma once

#include <string>
#include <vector>

#include "core/params.h"
#include "core/vec.h"
#include "integrators/render_context.h"
#include "scene/scene_arrays.h"

namespace candela::test {

struct MeshBuilder {
    std::vector<float> positions;     // (V, 3)
    std::vector<uint32_t> triangles;  // (T, 3)
    std::vector<uint32_t> tri_material;
    std::vector<uint32_t> mesh_tri_start{0};
    std::vector<uint32_t> instance_mesh;
    std::vector<float> instance_transform;
    std::vector<uint32_t> material_type;
    std::vector<float> materials;  // rows of 6
    std::vector<uint32_t> closure_material, closure_type;
    std::vector<float> closure_params;  // rows of closure_columns()
    std::vector<float> world_color;     // empty = black
    std::vector<uint32_t> light_type;
    std::vector<float> lights;  // rows of 20

    uint32_t add_material(Color base, Color emission);
    /// Appends a closure to `material`: `values` maps closure column names to values (weight 1 by default).
    void add_closure(uint32_t material, const std::string& type, const std::vector<std::pair<std::string, float>>& values);
    /// UV sphere (segments around, rings pole to pole) as one mesh; returns the mesh index.
    uint32_t add_sphere(float radius, int segments, int rings, uint32_t material);
    /// Axis-aligned quad in the z = h plane spanning [x0, x1] × [y0, y1]; returns the mesh index.
    uint32_t add_quad_z(float x0, float x1, float y0, float y1, float h, uint32_t material);
    void add_instance(uint32_t mesh, const float* rows16 = nullptr);
    void add_point_light(Vec3 pos, Color strength, float radius = 0.f);
    void add_light(uint32_t type, const std::vector<float>& row);

    SceneArrays arrays(const float* camera_rows16 = nullptr) const;
};

/// Params for a w×h render from a camera at the origin looking down −Z.
Params basic_params(int w, int h, int samples, int max_bounces);

struct RenderResult {
    std::vector<float> rgba;      // bottom-up
    std::vector<float> noise;     // per pixel: standard error of the mean luminance
    int width = 0, height = 0;
    double mean_rgb = 0.0;        // mean over pixels and RGB channels
    double standard_error = 0.0;  // of mean_rgb's luminance estimate, from per-pixel sample variances
    int samples_done = 0;
    StopReason stop_reason = StopReason::Running;
    double relative_error = -1.0;
};

RenderResult render(SceneArrays arrays, Params params);

}  // namespace candela::test
