// What a render will allocate beyond the scene arrays it was handed (Embree's vertex and index buffers, the BVH
// with its build's temporaries, per-triangle shading data, emissive-triangle lights, the film), predicted from
// the arrays before anything is built, and compared with the memory the machine can give: a render that cannot
// fit is refused with a message naming the biggest mesh, instead of being killed by the kernel's OOM killer
// halfway through the BVH build.
//
// The per-triangle costs are upper bounds measured on this build (Embree 3.13, RTC_BUILD_QUALITY_HIGH with
// spatial splits, since made per object under a two-level top scene; the robustness test re-measures): the peak resident growth of a scene build was 120–165 bytes per triangle, vertex and index
// buffers and shading data included, for meshes of 65k–1M triangles, from smooth spheres to random triangle
// soups (tests/robustness/memory_test.cpp measures it again and checks the estimate stays above it); each build
// thread adds Embree's thread-local allocation blocks (4 MB allowed per thread).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/params.h"
#include "input/scene_arrays.h"

namespace candela {

struct MemoryEstimate {
    double geometry_bytes = 0.0;  // meshes, BVH (peak while building), lights
    double film_bytes = 0.0;
    double integrator_bytes = 0.0;   // the integrator's own data (IntegratorEntry::memory_bytes)
    double limit_bytes = 0.0;        // what may be allocated (0: unknown, nothing is refused)
    std::string limit_source;        // "memory_limit_mb" or "available memory (MemAvailable)"
    std::vector<double> mesh_bytes;  // per mesh, every instance included
    int64_t biggest_mesh = -1;
    size_t biggest_mesh_triangles = 0;

    double total_bytes() const { return geometry_bytes + film_bytes + integrator_bytes; }
    bool fits() const { return limit_bytes <= 0.0 || total_bytes() <= limit_bytes; }
    /// Why the render does not fit, naming the biggest mesh (by mesh_names[i] if given, else "mesh i").
    std::string refusal(const std::vector<std::string>& mesh_names = {}) const;
};

/// Bytes per pixel of the film (accumulators, the display buffer, pass copies).
double film_bytes_per_pixel();

/// The estimate for a validated scene and a film of `film_pixels`; the limit is the `memory_limit_mb` param if
/// set (> 0), else MemAvailable from /proc/meminfo.
MemoryEstimate estimate_memory(const SceneArrays& arrays, const Params& params, double film_pixels);

/// MemAvailable of /proc/meminfo in bytes, or 0 if it cannot be read (then nothing is refused).
double available_memory_bytes();

}  // namespace candela
