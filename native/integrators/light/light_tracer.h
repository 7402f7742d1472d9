// Light tracing (particle tracing): estimates the image by paths grown from the lights, each vertex connected to
// the camera and splatted where it lands on the film (Veach 1997, §10.2: the strategies t = 1 of bidirectional
// path tracing; Arvo & Kirk's particle tracing). A light path starts with an emitted ray chosen ∝ power
// (lights/emitter_set.h) and flux weight β₀ = Le·|cos|/(p_pos·p_dir·P(light)); at each surface x_k its throughput
// β_k has E[Σ_k β_k h(x_k, w_k)] = ∫∫ h L_in |cos| dω dA, so the camera connection from x_k splats
//     v = β_k · f(w_cam, w_l) · |w_cam·ng| · (|w_l·ns|/|w_l·ng|) · K(x_k)
// at the raster position it lands on, K the camera's importance per unit area (scene/camera.h); the film counts
// (light paths)/(W·H) samples per pixel, so v is what a camera sample there would return. The path continues by
// light-side sampling of the vertex BSDF (integrators/common/vertex_bsdf.h), Russian roulette on its throughput
// relative to the first vertex's.
//
// What light tracing cannot reach: a camera sees a light path's vertex only if that vertex scatters diffusely or
// glossily; emitters seen directly or through specular chains (E S* L) are added by a camera pass of specular
// paths (SpecularCameraTracer), and surfaces seen only through specular chains (E S+ D …) get no light at all —
// they are the bidirectional tracer's job (docs/architecture.md).
#pragma once

#include "film/aov_film.h"
#include "film/film.h"
#include "integrators/light/light_settings.h"
#include "integrators/render_context.h"
#include "lights/emitter_set.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

class LightTracer {
public:
    LightTracer(const Scene& scene, const LightSettings& settings, const EmitterSet& emitters)
        : m_scene(scene), m_settings(settings), m_emitters(emitters) {}

    /// Traces the light path of the sampler's current sample (its dimensions from bounce `dim_bounce` on) and adds
    /// its camera connections to `splats` (replicate `replicate`).
    void trace(Sampler& sampler, int dim_bounce, uint32_t replicate, SplatBuffer& splats, PathStats& stats) const;

private:
    template <class S>
    void trace_path(S& sampler, int dim_bounce, uint32_t replicate, SplatBuffer& splats, PathStats& stats) const;

    const Scene& m_scene;
    const LightSettings& m_settings;
    const EmitterSet& m_emitters;
};

/// The camera pass of light tracing: the light a camera ray finds at emitters directly or through delta
/// (specular) scattering only — what no light path can connect to the camera —, with the camera's alpha and data
/// passes. A non-delta scattering ends the path: that light is the light tracer's.
class SpecularCameraTracer {
public:
    SpecularCameraTracer(const Scene& scene, const LightSettings& settings) : m_scene(scene), m_settings(settings) {}
    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov) const;

private:
    const Scene& m_scene;
    const LightSettings& m_settings;
};

}  // namespace candela
