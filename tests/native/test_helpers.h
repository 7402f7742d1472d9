// Builders for small test scenes as scene arrays, and a synchronous render helper.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/params.h"
#include "core/vec.h"
#include "input/scene_arrays.h"
#include "integrators/render_context.h"

namespace candela {
class Scene;
}

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
    void add_closure(uint32_t material, const std::string& type,
                     const std::vector<std::pair<std::string, float>>& values);
    /// UV sphere (segments around, rings pole to pole) as one mesh; returns the mesh index.
    uint32_t add_sphere(float radius, int segments, int rings, uint32_t material);
    /// Axis-aligned quad in the z = h plane spanning [x0, x1] × [y0, y1]; returns the mesh index.
    uint32_t add_quad_z(float x0, float x1, float y0, float y1, float h, uint32_t material);
    /// Axis-aligned closed box [-hx, hx] × [-hy, hy] × [-hz, hz] (12 triangles, wound outward); returns the
    /// mesh index.
    uint32_t add_box(Vec3 half_extent, uint32_t material);
    /// One triangle (a, b, c) as its own mesh; returns the mesh index.
    uint32_t add_triangle(Vec3 a, Vec3 b, Vec3 c, uint32_t material);
    void add_instance(uint32_t mesh, const float* rows16 = nullptr);
    void add_point_light(Vec3 pos, Color strength, float radius = 0.f);
    /// Blender area light (rectangle, or disk/ellipse when `disk`): full edge vectors (diameters) u and v,
    /// shining along the unit `direction` (the light's −Z); `strength` is Blender's power in W, so the
    /// radiance is strength/(4·area) (Cycles 3.4).
    void add_area_light(Vec3 center, Vec3 u, Vec3 v, Vec3 direction, Color strength, bool disk);
    void add_light(uint32_t type, const std::vector<float>& row);

    SceneArrays arrays(const float* camera_rows16 = nullptr) const;
};

/// Params for a w×h render from a camera at the origin looking down −Z.
Params basic_params(int w, int h, int samples, int max_bounces);

/// Row-major camera_to_world of a camera at `eye` looking at `target` (the camera looks down its −Z with +Y
/// up, Blender's convention); `up` must not be parallel to the view direction.
std::vector<float> look_at(Vec3 eye, Vec3 target, Vec3 up);

struct RenderResult {
    std::vector<float> rgba;   // bottom-up
    std::vector<float> noise;  // per pixel: standard error of the mean luminance
    int width = 0, height = 0;
    double mean_rgb = 0.0;        // mean over pixels and RGB channels
    double standard_error = 0.0;  // of mean_rgb's luminance estimate, from per-pixel sample variances
    int samples_done = 0;
    StopReason stop_reason = StopReason::Running;
    double relative_error = -1.0;
};

/// Renders through a Session (the path the add-on takes).
RenderResult render(SceneArrays arrays, Params params);

/// A scene built once (Embree device, BVH, lights) and rendered many times with different integrator
/// settings, for tests that sweep many configurations over one scene. `base` holds what the scene and the
/// film depend on (size, camera, threads); render() adds the overrides to it.
class PreparedScene {
public:
    PreparedScene(SceneArrays arrays, Params base);
    ~PreparedScene();
    RenderResult render(const Params& overrides) const;
    const Scene& scene() const { return *m_scene; }

private:
    Params m_base;
    std::unique_ptr<Scene> m_scene;
};

/// The closed-sphere furnaces of docs/verification.md §1, seen from the centre (camera at the origin
/// looking down −Z), albedo 0.5 everywhere:
///   EmissiveSphere: every facet emits Le = 0.5 → L = Le/(1 − ρ) = 1 (exact for any closed shape);
///   PointLight:     a point light of intensity π at the centre (pbrt S1) → L = ρI/(π(1 − ρ)) = 1;
///   FourPointLights: four coincident point lights of intensities π·(0.1, 0.2, 0.3, 0.4) (pbrt S2 with unequal
///                   powers: catches light-selection pmf errors) → 1.
/// The point-light answers hold for a true sphere; a UV sphere of `segments` × `rings` has less area than
/// the sphere (its mean radiance is 4π/area, see furnace_facet_bias) — use ≥ 128 × 64 when the tolerance is
/// under 1 %.
enum class FurnaceScene { EmissiveSphere, PointLight, FourPointLights };
SceneArrays furnace_scene(FurnaceScene kind, int segments = 128, int rings = 64);
/// The furnace's pixel value with max_bounces = K: emitters are seen at vertices 0..K+1, so
/// Le(1 − ρ^(K+2))/(1 − ρ); point lights are sampled (NEE) at vertices 0..K, so 1 − ρ^(K+1).
double furnace_expected(FurnaceScene kind, int max_bounces);
/// Relative excess of the area-mean radiance of the point-light furnace on a UV sphere over the true
/// sphere's: 4π/area(mesh) − 1 (power balance of a closed diffuse enclosure: area·B = ρ(4πI + area·B)).
double furnace_facet_bias(int segments, int rings);

/// A "kB" field of /proc/self/status ("VmRSS:", "VmHWM:"), or -1. Writing "5" to /proc/self/clear_refs resets
/// VmHWM (the peak) to the current resident size, so a test can measure the peak growth of what it runs.
long proc_status_kb(const char* key);

}  // namespace candela::test
