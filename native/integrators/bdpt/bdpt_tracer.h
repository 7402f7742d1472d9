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
        : m_context{scene, emitters, settings} {}

    /// The camera sample's radiance (strategies t ≥ 2); the t = 1 strategies are splatted into `sink`.
    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov, SplatSink sink) const;

private:
    BdptContext m_context;
};

}  // namespace candela
