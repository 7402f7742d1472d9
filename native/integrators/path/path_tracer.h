// Unidirectional path tracing: estimates the pixel integral of the measurement equation with paths
// grown from the camera (Kajiya 1986, "The Rendering Equation"). At every vertex direct light is
// estimated twice — by next-event estimation (light_samples stratified shadow rays, each choosing one
// light by the light_selection strategy — or every light, for ALL — and a point on it by area or by solid
// angle, light_pdf) and by the continuation ray hitting an emitter — and the two are combined by multiple importance
// sampling with the balance or power heuristic (Veach 1997, ch. 9, eqs. 9.12–9.13, with n_light =
// light_samples). light_sampling restricts it to one estimator (BSDF_ONLY keeps light sampling for delta
// lights, which no ray can hit). Lights no BSDF ray can reach (point, spot, sun) get weight 1. The
// continuation is drawn by BSDF importance sampling, or uniformly / cosine-weighted over the hemisphere for
// teaching (hemisphere_sampling). branching_factor > 1 splits the path at the first surface into that many
// stratified continuations (Cook's stochastic ray tracing), each carrying 1/b of the throughput. Paths end
// at max_bounces, or by Russian roulette from rr_start_bounce on (Arvo & Kirk 1990) with survival
// min(1, max throughput·Πη²) or the surface's albedo for the continuation ray, or Cycles' rule (survival
// min(1, √(max throughput·Πη²)), decided on arrival at vertex v — v = 0 the first — when v + 1 >= rr_start_bounce,
// before its shadow rays; Cycles decides at vertices whose bounce count exceeds min_light_bounces = m, so
// rr_start_bounce = m + 2 reproduces it), each of which keeps
// the estimator unbiased for the truncated sum. The Light Paths settings (common/light_paths.h, Cycles 3.4's
// semantics) add per-type bounce limits, Clamp Direct and Indirect, Filter Glossy and the Caustics switches, all off
// by default. A Transparent BSDF's pass-through is not a bounce: the ray carries on (its MIS origin stays the vertex
// before the transparent surfaces, at the summed distance), and shadow rays pass Transparent surfaces too (Cycles'
// transparent shadows), so both estimators of the light behind see the same transparency.
#pragma once

#include "film/aov_film.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/path/path_settings.h"
#include "integrators/render_context.h"
#include "lights/light_sampler.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

class PathTracer {
public:
    PathTracer(const Scene& scene, const PathSettings& settings, const LightSampler& light_sampler)
        : m_scene(scene), m_settings(settings), m_light_sampler(light_sampler) {}

    /// Radiance arriving along the camera ray; *alpha is 0 when film_transparent and the ray escapes (and loses
    /// a holdout's weight); `aov`, if given, receives the data passes of the first surface hit.
    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov = nullptr) const;
    /// The same for a camera ray already traced (Scene::intersect_packet): the path starts from its hit.
    Color Li(const Ray& camera_ray, const TracedHit& first, Sampler& sampler, PathStats& stats, float* alpha,
             AovSample* aov = nullptr) const;

    /// How the ray being traced was produced: what the vertex it hits needs for MIS, roulette and dims.
    struct PathState {
        Color beta{1.f};           // throughput
        EmissionOrigin origin;     // the scattering that produced the ray, for MIS at an emitter it finds
        float mis_t = 0.f;         // distance from that scattering to the ray's origin (transparent surfaces between)
        float eta_scale = 1.f;     // Π η² over refractions (roulette only)
        PrimitiveRef from;         // the triangle the ray leaves (skipped by the intersection)
        int dim_offset = 0;        // added to the vertex index for sample dimensions (branches use their own)
        AovSample* aov = nullptr;  // camera ray only: where its first hit's data passes go
        LightPathState lp;         // bounce counts, the ray's type for the Light Path node, Filter Glossy's pdf
    };

private:
    /// Templated on the concrete sampler (Li dispatches once per path), so every draw inlines.
    /// `first`, if given, is the closest hit of `ray` (traced ahead), used instead of intersecting it again.
    /// `vertex` counts the surfaces the path has reached (0: the camera ray's), transparent ones included: it
    /// names the sample dimensions. The bounce counts live in the state (PathState::lp).
    template <class ConcreteSampler>
    void trace(Ray ray, PathState state, int vertex, ConcreteSampler& sampler, PathStats& stats, Color& L, float* alpha,
               const TracedHit* first = nullptr) const;
    /// The vertex at `hit`: roulette, next-event estimation and the continuation. Returns true with `ray` and
    /// `state` set to the continuation's; false when the path ends here (or went on in branches).
    template <class ConcreteSampler>
    bool scatter(const SurfaceHit& hit, const ShadingPoint& sp, Ray& ray, PathState& state, int vertex,
                 ConcreteSampler& sampler, PathStats& stats, Color& L, float* alpha) const;
    /// Emission Le found by the path's ray (weighted against light sampling; may be clamped).
    void add_emission(const PathState& state, const Color& Le, float light_pdf, Color& L) const;
    /// The light the ray finds before the surface at t_surface (area lights) or beyond it when it escapes.
    void add_area_light_emission(const Ray& ray, float t_surface, const PathState& state, Color& L) const;
    void add_world_emission(const Ray& ray, const PathState& state, Color& L, float* alpha) const;

    const Scene& m_scene;
    const PathSettings& m_settings;
    const LightSampler& m_light_sampler;
};

}  // namespace candela
