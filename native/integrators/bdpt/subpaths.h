// The two subpaths of a bidirectional sample (Veach 1997, §10.2): a camera subpath z₀ … from the camera (z₀ on the
// lens) grown by the path tracer's BSDF sampling, and a light subpath y₀ … from an emitter chosen ∝ power grown by
// light-side sampling (integrators/common/vertex_bsdf.h); each vertex records its throughput and both area
// densities (path_vertex.h). The camera subpath also records, per segment, the closest area light it passes
// (area lights are not surfaces: the path goes on through them, as in PATH), for the strategies s = 0 that end
// there.
#pragma once

#include <cstdint>
#include <vector>

#include "integrators/bdpt/bdpt_settings.h"
#include "integrators/bdpt/path_vertex.h"
#include "integrators/render_context.h"
#include "lights/emitter_set.h"
#include "sampling/primary_sample_sampler.h"
#include "sampling/sampler.h"

namespace candela {

/// An area light a camera subpath segment passes: the segment from z[segment − 1] toward z[segment].
struct AreaLightHit {
    int segment = -1;
    uint32_t light = 0;  // LightSet (= EmitterSet) index
    Vec3 p;
    float pdf_fwd = 0.f;  // the camera side's area density of the point
    Color beta{0.f};      // the camera subpath's throughput along the segment
};

struct BdptContext {
    const Scene& scene;
    const EmitterSet& emitters;
    const BdptSettings& settings;
    /// Some emitter a ray can hit exists (has_hittable_emission): else the s = 0 strategies carry no energy and are
    /// not evaluated (integrators/scene_skips.h, "bdpt_no_s0").
    bool s0_strategies = true;
    int max_camera() const { return settings.max_bounces + 3; }        // z₀, max_bounces + 1 scattering, an emitter
    int max_light() const { return settings.max_bounces + 2; }         // y₀ and max_bounces + 1 scattering
    int light_dim_bounce() const { return settings.max_bounces + 2; }  // after the camera subpath's dimensions
    /// How far beyond the frame camera rays reach (filter importance sampling: half the filter's support), pixels.
    float camera_margin() const { return 0.5f * settings.pixel.filter.support(); }
};

/// Per-vertex random numbers the connections use: a light sample from a camera vertex (s = 1: the emitter and a
/// point on it, or a direction toward a distant one), a lens sample from a light vertex (t = 1).
struct VertexNumbers {
    float u_select = 0.5f;
    Vec2 u_point{0.5f, 0.5f};
};

/// Fills z[0 .. n) for the camera ray (its first hit given, if traced ahead), returns n. `alpha` and `aov` as the
/// path tracer's (film transparency, holdout, data passes at the first hit).
int camera_subpath(const BdptContext& c, const Ray& ray, Sampler& sampler, std::vector<PathVertex>& z,
                   std::vector<VertexNumbers>& numbers, std::vector<AreaLightHit>& area_hits, PathStats& stats,
                   float* alpha, AovSample* aov);

/// Fills y[0 .. n) with a light subpath, returns n (0: no emitter could be sampled).
int light_subpath(const BdptContext& c, Sampler& sampler, std::vector<PathVertex>& y,
                  std::vector<VertexNumbers>& numbers, PathStats& stats);

/// The same walks driven by Metropolis' primary-sample state (integrators/mlt/), with at most `max_vertices`
/// vertices (multiplexed MLT builds a subpath of exactly the length its strategy needs). Its last vertex has its
/// connection numbers, not a sampled continuation. No film transparency, holdout alpha or data passes.
int camera_subpath(const BdptContext& c, const Ray& ray, PrimarySampleSampler& sampler, std::vector<PathVertex>& z,
                   std::vector<VertexNumbers>& numbers, std::vector<AreaLightHit>& area_hits, PathStats& stats,
                   int max_vertices);
int light_subpath(const BdptContext& c, PrimarySampleSampler& sampler, std::vector<PathVertex>& y,
                  std::vector<VertexNumbers>& numbers, PathStats& stats, int max_vertices);

}  // namespace candela
