// Bidirectional path tracing (Veach 1997, ch. 10; Lafortune & Willems 1993): for each camera sample a camera subpath
// and a light subpath (subpaths.h), every strategy (s, t) that joins their prefixes (strategy.h) weighted by
// multiple importance sampling over all strategies of the same path, summed; the t = 1 strategies land elsewhere on
// the film and are splatted. Path lengths are the path tracer's (at most max_bounces + 1 scattering vertices), so
// BDPT and PATH estimate the same image.
#pragma once

#include <vector>

#include "integrators/bdpt/strategy.h"
#include "integrators/bdpt/strategy_images.h"
#include "integrators/bdpt/subpaths.h"
#include "integrators/camera_tiles.h"
#include "integrators/scene_skips.h"

namespace candela {

/// While set on a thread (by the integrator, around one tile), BdptTracer::Li records every strategy's
/// contribution into `buffer` (strategy_images.h).
struct StrategyRecording {
    const StrategyImages* images = nullptr;
    StrategyImages::Buffer* buffer = nullptr;
};
StrategyRecording& strategy_recording();

class BdptTracer {
public:
    BdptTracer(const Scene& scene, const BdptSettings& settings, const EmitterSet& emitters)
        : m_context{scene, emitters, settings, has_hittable_emission(scene)} {}

    /// The camera sample's radiance (strategies t ≥ 2); the t = 1 strategies are splatted into `sink`.
    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov,
             SplatSink sink) const;

    /// One weighted contribution of a bidirectional sample: `L` lands at the camera ray's raster position, or
    /// (splat, t = 1) at `raster`.
    struct Contribution {
        Color L;
        bool splat = false;
        Vec2 raster{0.f};
    };
    /// Metropolis (integrators/mlt/): the whole bidirectional sample of primary-sample state `u` (every strategy,
    /// MIS-weighted, as Li), appended to `out`.
    void sample_all(const Ray& camera_ray, PrimarySampleSampler& u, PathStats& stats,
                    std::vector<Contribution>& out) const;
    /// Multiplexed Metropolis: strategy (s, t) alone (subpaths of exactly s and t vertices), its MIS-weighted
    /// contribution appended to `out` (s = 0 may give two: the emitter z[t − 1] and an area light passed before it).
    void sample_strategy(const Ray& camera_ray, PrimarySampleSampler& u, int s, int t, PathStats& stats,
                         std::vector<Contribution>& out) const;
    const BdptContext& context() const { return m_context; }

private:
    BdptContext m_context;
};

}  // namespace candela
