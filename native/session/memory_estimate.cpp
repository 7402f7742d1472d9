#include "session/memory_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/parallel.h"
#include "core/vec.h"
#include "film/film.h"
#include "integrators/integrator.h"

namespace candela {

namespace {

// Upper bounds per element (see the header for the measurements behind the BVH figure).
constexpr double k_bvh_bytes_per_triangle = 160.0;  // BVH nodes, spatial-split references, build temporaries
constexpr double k_vertex_bytes = 12.0;             // Embree vertex buffer (float3)
constexpr double k_index_bytes = 12.0;              // Embree index buffer (uint3)
constexpr double k_shading_bytes = 9.0;             // material (4) + smooth flag (1) + emissive rank (4)
constexpr double k_normal_bytes = 36.0;             // 3 shading normals, for meshes with smooth faces
constexpr double k_corner_bytes = 36.0;             // 3 corner positions (smooth meshes with a terminator offset)
constexpr double k_instance_bytes = 512.0;          // Embree instance, top-level BVH leaf, placement
constexpr double k_light_bytes = 256.0;             // an emissive triangle's light and its light-tree share
constexpr double k_thread_bytes = 4e6;              // per build thread: Embree's thread-local allocation blocks

std::string gigabytes(double bytes) {
    char buf[32];
    if (bytes >= 1e9)
        std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
    else
        std::snprintf(buf, sizeof buf, "%.0f MB", std::ceil(bytes / 1e6));
    return buf;
}

std::string thousands(size_t n) {
    std::string s = std::to_string(n);
    for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
    return s;
}

}  // namespace

double film_bytes_per_pixel() { return double(sizeof(PixelAccum) + sizeof(Color) + 8 * sizeof(float)); }

double available_memory_bytes() {
    std::ifstream f("/proc/meminfo");
    std::string line;
    while (std::getline(f, line)) {
        if (line.rfind("MemAvailable:", 0) != 0) continue;
        std::istringstream in(line.substr(13));
        double kb = 0.0;
        in >> kb;
        return kb * 1024.0;
    }
    return 0.0;
}

MemoryEstimate estimate_memory(const SceneArrays& arrays, const Params& params, double film_pixels) {
    MemoryEstimate e;
    e.film_bytes = film_pixels * film_bytes_per_pixel();
    const IntegratorEntry& integrator = find_integrator(params.get<std::string>("integrator", "PATH"));
    if (integrator.memory_bytes) e.integrator_bytes = integrator.memory_bytes(params, film_pixels);
    const double limit_mb = params.get<double>("memory_limit_mb", 0.0);
    if (limit_mb > 0.0) {
        e.limit_bytes = limit_mb * 1e6;
        e.limit_source = "memory_limit_mb";
    } else {
        e.limit_bytes = available_memory_bytes();
        e.limit_source = "available memory (MemAvailable)";
    }

    const uint32_t* triangles = arrays.get("triangles").data<uint32_t>();
    const uint32_t* tri_material = arrays.get("tri_material").data<uint32_t>();
    const uint32_t* mesh_start = arrays.get("mesh_tri_start").data<uint32_t>();
    const uint32_t* instance_mesh = arrays.get("instance_mesh").data<uint32_t>();
    const Array* smooth_arr = arrays.find("tri_smooth");
    const uint8_t* smooth = smooth_arr && arrays.has("normals") ? smooth_arr->data<uint8_t>() : nullptr;
    const size_t mesh_count = arrays.rows("mesh_tri_start") - 1;
    const size_t instance_count = arrays.rows("instance_mesh");
    // Emissive materials (the base emission columns 3..5).
    const Array& mats = arrays.get("materials");
    std::vector<uint8_t> emissive(mats.shape[0], 0);
    for (size_t k = 0; k < mats.shape[0]; ++k) {
        const float* r = mats.data<float>() + k * mats.shape[1];
        emissive[k] = mats.shape[1] >= 6 && (r[3] > 0.f || r[4] > 0.f || r[5] > 0.f);
    }

    std::vector<uint32_t> uses(mesh_count, 0);
    for (size_t i = 0; i < instance_count; ++i) ++uses[instance_mesh[i]];
    std::vector<uint8_t> terminator(mesh_count, 0);  // some instance has a shadow terminator offset
    if (const Array* t = arrays.find("instance_terminator"))
        for (size_t i = 0; i < instance_count; ++i)
            if (t->data<float>()[i] > 0.f) terminator[instance_mesh[i]] = 1;
    const uint8_t* smooth_any =
        smooth_arr && (arrays.has("normals") || arrays.has("vertex_normals")) ? smooth_arr->data<uint8_t>() : nullptr;
    e.mesh_bytes.assign(mesh_count, 0.0);
    double biggest = -1.0;
    for (size_t m = 0; m < mesh_count; ++m) {
        const size_t t0 = mesh_start[m], t1 = mesh_start[m + 1], n = t1 - t0;
        if (uses[m] == 0 || n == 0) continue;
        uint32_t vlo = UINT32_MAX, vhi = 0;
        size_t lights = 0;
        bool any_smooth = false, any_smooth_faces = false;
        for (size_t t = t0; t < t1; ++t) {
            for (int k = 0; k < 3; ++k) {
                vlo = std::min(vlo, triangles[3 * t + k]);
                vhi = std::max(vhi, triangles[3 * t + k]);
            }
            lights += emissive[tri_material[t]];
            any_smooth |= smooth && smooth[t];
            any_smooth_faces |= smooth_any && smooth_any[t];
        }
        const double vertices = double(vhi) - double(vlo) + 1.0;
        // One geometry and BVH per mesh (a single-use mesh is flattened into the top-level BVH, the same cost),
        // per use: an instance (if shared) and the emissive triangles' lights.
        double bytes =
            vertices * k_vertex_bytes + double(n) * (k_index_bytes + k_shading_bytes + k_bvh_bytes_per_triangle);
        if (any_smooth) bytes += double(n) * k_normal_bytes;
        if (any_smooth_faces && terminator[m]) bytes += double(n) * k_corner_bytes;
        if (uses[m] > 1) bytes += double(uses[m]) * k_instance_bytes;
        bytes += double(uses[m]) * double(lights) * k_light_bytes;
        e.mesh_bytes[m] = bytes;
        e.geometry_bytes += bytes;
        if (bytes > biggest) {
            biggest = bytes;
            e.biggest_mesh = int64_t(m);
            e.biggest_mesh_triangles = n;
        }
    }
    if (e.geometry_bytes > 0.0)
        e.geometry_bytes += k_thread_bytes * resolve_thread_count(params.get<int>("threads", 0));
    return e;
}

std::string MemoryEstimate::refusal(const std::vector<std::string>& mesh_names) const {
    std::string s = "the render needs about " + gigabytes(total_bytes()) + " of memory (scene " +
                    gigabytes(geometry_bytes) + ", film " + gigabytes(film_bytes) +
                    (integrator_bytes > 0.0 ? ", integrator " + gigabytes(integrator_bytes) : std::string()) +
                    ") but only " + gigabytes(limit_bytes) + " are available (" + limit_source + ")";
    if (integrator_bytes > geometry_bytes && integrator_bytes > film_bytes) {
        s += "; most of it is the integrator's own data (" + gigabytes(integrator_bytes) +
             "): lower its budget in its settings";
    } else if (biggest_mesh >= 0 && geometry_bytes >= film_bytes) {
        const size_t m = size_t(biggest_mesh);
        const std::string name = m < mesh_names.size() ? mesh_names[m] : "mesh " + std::to_string(m);
        s += "; the biggest is " + name + " with " + thousands(biggest_mesh_triangles) + " triangles (" +
             gigabytes(mesh_bytes[m]) + "): decimate it, or use instances";
    } else {
        s += "; lower the resolution or use a render border";
    }
    return s;
}

}  // namespace candela
