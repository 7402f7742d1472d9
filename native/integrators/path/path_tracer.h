// Unidirectional path tracing: estimates the pixel integral of the measurement equation with paths
// grown from the camera (Kajiya 1986, "The Rendering Equation"). At every vertex, direct light is
// estimated twice — by next-event estimation (one light chosen ∝ power, one point on it) and by the
// BSDF-sampled continuation ray hitting an emitter — and the two are combined with multiple importance
// sampling using the power heuristic (Veach 1997, ch. 9, eq. 9.13). Lights no BSDF ray can reach
// (point, spot, sun) get weight 1. Paths end at max_bounces or by Russian roulette with survival
// probability min(1, max throughput) from rr_start_bounce on (Arvo & Kirk 1990), which keeps the
// estimator unbiased for the truncated sum.
#pragma once

#include "integrators/path/path_settings.h"
#include "integrators/render_context.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

class PathTracer {
public:
    PathTracer(const Scene& scene, const PathSettings& settings) : m_scene(scene), m_settings(settings) {}

    /// Radiance arriving along the camera ray; *alpha is 0 when film_transparent and the ray escapes.
    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha) const;

private:
    const Scene& m_scene;
    const PathSettings& m_settings;
};

}  // namespace candela
