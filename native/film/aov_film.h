// Data passes (AOVs) of the first surface the camera sees, accumulated the way Cycles 3.4 writes them
// (kernel/film/data_passes.h, film_write_data_passes, and the pass accessor's conversion):
//   Normal (3)  — shading normal (after any Normal Map) facing the camera, world space; averaged over all of a
//                 pixel's samples.
//   Albedo (3)  — Cycles' (denoising) albedo of the material at the hit, textures evaluated: the sum of its
//                 closures' colour weights, Fresnel-tinted specular lobes times their Fresnel colour, Transparent
//                 closures left out (integrators/camera_hit.cpp); averaged over all samples.
//   Depth (1)   — distance along the camera's view axis (Cycles' Z depth); from the pixel's sample 0 only,
//                 1e10 where that sample saw no surface.
//   IndexOB (1) — the object's pass index; from sample 0 only (an average of ids across an edge would be none).
//   IC Records (1) — an integrator's debug pass, written whole by the integrator (set_pass), not accumulated from
//                 camera samples: the irradiance cache's records per pixel (0 for the other integrators).
// Sample positions come from the same filter importance sampling as Combined (each sample lands in its pixel
// with weight 1), so the averaged passes are filtered exactly like the image, and a miss adds zero. Sums are
// per pixel in sample order: deterministic for any thread count. Tiles are the film's; each has its own lock.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/vec.h"
#include "film/film.h"

namespace candela {

/// What one camera sample saw first (all zero for a miss).
struct AovSample {
    bool hit = false;
    float depth = 0.f;
    Vec3 normal{0.f};
    Color albedo{0.f};
    float object_index = 0.f;
};

struct AovAccum {
    double normal[3] = {0, 0, 0};
    double albedo[3] = {0, 0, 0};
    float depth = 0.f, object_index = 0.f;  // of sample 0
    uint32_t n = 0;

    void add(const AovSample& s, bool sample_zero) {
        for (int c = 0; c < 3; ++c) {
            normal[c] += s.normal[c];
            albedo[c] += s.albedo[c];
        }
        if (sample_zero) {
            depth = s.hit ? s.depth : 0.f;
            object_index = s.object_index;
        }
        ++n;
    }
};

class AovFilm {
public:
    /// The data passes Candela can write: (Blender pass name, channels).
    static const std::vector<std::pair<std::string, int>>& pass_specs();

    /// Accumulates `passes` (names from pass_specs(); "Combined" and "Noise" are the film's and are skipped)
    /// over the film's tiles. Throws InvalidParameter naming an unknown pass.
    AovFilm(const Film& film, const std::vector<std::string>& passes);

    /// No pass is accumulated from camera samples (integrator passes aside): tracers need not record AovSamples.
    bool empty() const { return m_pixels.empty(); }
    bool enabled(const std::string& name) const;
    const std::vector<std::string>& passes() const { return m_enabled; }

    /// Adds a tile's worth of samples (row-major within the tile), like Film::add_tile.
    void add_tile(size_t tile_index, const std::vector<AovAccum>& tile_pixels);
    /// A pass as float32 rows bottom to top (W·H·channels), or empty if the pass is not written.
    std::vector<float> get(const std::string& name, int* channels) const;

    /// Whether `name` is a pass an integrator writes whole (set_pass) rather than one accumulated per sample.
    static bool integrator_pass(const std::string& name);
    /// Whether `name` is one of BDPT's strategy images ("BDPT d1 s1 t2", "BDPT d1 s1 t2 unweighted"; RGB).
    static bool strategy_pass(const std::string& name);
    /// The channels of pass `name`, or 0 if there is no such pass.
    static int channels_of(const std::string& name);
    /// Replaces integrator pass `name` (if it was asked for) by `values`: W·H·channels floats, rows bottom to top.
    void set_pass(const std::string& name, std::vector<float> values);

private:
    int m_width, m_height;
    std::vector<Tile> m_tiles;
    std::vector<std::string> m_enabled;
    std::vector<AovAccum> m_pixels;  // empty when no pass is enabled
    std::unique_ptr<std::mutex[]> m_tile_locks;
    mutable std::mutex m_integrator_lock;
    std::vector<std::pair<std::string, std::vector<float>>> m_integrator_passes;
};

/// "Depth,Normal" → {"Depth", "Normal"} (spaces around names are ignored).
std::vector<std::string> split_pass_list(const std::string& list);

}  // namespace candela
