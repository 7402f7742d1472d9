// The walk of a light path (light tracing, the source-shooting generator), built on the light-path pieces photon
// shooting uses too (common/light_path.h): an emitted ray chosen ∝ power (lights/emitter_set.h) with the flux
// weight β₀ = Le·|cos|/(p_pos·p_dir·P(light)), then at every surface
// vertex x_k a visit with the throughput β_k — for which E[Σ_k β_k h(x_k, w_k)] = ∫∫ h L_in |w·ng| dω dA, L_in the
// radiance arriving at x_k from w (docs/architecture.md, "light paths") — and the continuation by light-side
// sampling of the vertex BSDF (integrators/common/vertex_bsdf.h: importance transport, Veach's adjoint factor),
// Russian roulette on the throughput relative to the first vertex's (a light path's β is a flux, not ≤ 1).
#pragma once

#include <cmath>
#include <limits>

#include "integrators/common/light_path.h"
#include "integrators/common/roulette.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/render_context.h"
#include "lights/emitter_set.h"
#include "sampling/sampler.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace candela {

struct LightWalkRules {
    int max_depth = 13;  // surface vertices visited at most
    RouletteMode rr_mode = RouletteMode::Throughput;
    int rr_start_bounce = 3;  // roulette from this vertex depth on (the first vertex is depth 1)
};

/// Walks the light path of the sampler's current sample, its dimensions from bounce `dim_bounce` on (the emitted
/// ray at dim_bounce, vertex k at dim_bounce + k). `start(es, emitter)` sees the emitted ray; `visit(vb, w_l, beta,
/// depth, u)` each vertex (w_l toward the light side, u its bounce sample — its `light` values are the visitor's:
/// the walk draws the direction from `bsdf`, the lobe from `lobe`, roulette from `roulette`).
template <class S, class Start, class Visit>
void walk_light_path(const Scene& scene, const EmitterSet& emitters, const LightWalkRules& rules, S& sampler,
                     int dim_bounce, PathStats& stats, Start&& start, Visit&& visit) {
    // The emitted ray: the emitter (LightSelect), its origin (Light), its direction (Bsdf), a triangle's side (lobe).
    const BounceSample u0 = draw_bounce(sampler, dim_bounce, k_need_light_select | k_need_light | k_need_lobe);
    const LightPathStart emitted = start_light_path(emitters, u0.light_select, u0.light, u0.bsdf, u0.lobe);
    ++stats.paths;
    if (!emitted.valid) return;
    Color beta = emitted.beta;
    start(emitted.emission, emitted.emitter);
    Ray ray = emitted.ray;
    PrimitiveRef from;
    float beta_ref = 0.f, eta_scale = 1.f;
    for (int depth = 1;; ++depth) {
        SurfaceHit hit;
        ++stats.rays;
        if (!scene.intersect(ray, &hit, from)) return;
        // A soft point light lights its first receiver through the disk that faces it (lights/light_emission.h).
        if (depth == 1 && !emission_arrives(emitters[emitted.emitter], hit.p, ray.d)) return;
        const Vec3 w_l = -ray.d;
        const VertexBsdf vb(scene, hit, w_l, scene.shade(hit, w_l));
        if (depth == 1) beta_ref = max_component(beta);
        const bool last = depth >= rules.max_depth;
        const bool roulette_here = !last && rules.rr_mode != RouletteMode::Off && depth >= rules.rr_start_bounce;
        const BounceSample u = draw_bounce(sampler, dim_bounce + depth,
                                           k_need_light | k_need_lobe | (roulette_here ? k_need_roulette : 0u));
        visit(vb, w_l, beta, depth, u);
        if (last) return;
        const VertexBsdf::Sample s = vb.sample_light(w_l, u.bsdf, u.lobe);
        if (!s.valid()) return;
        beta *= s.weight;
        if (s.bsdf.is_transmission() && s.bsdf.eta > 0.f) eta_scale /= s.bsdf.eta * s.bsdf.eta;
        if (roulette_here) {
            const float q = light_path_survival(rules.rr_mode, s.weight, beta * (eta_scale / beta_ref));
            if (!(q > 0.f) || u.roulette >= q) return;
            beta /= q;
        }
        if (is_black(beta) || !is_finite(beta)) return;
        ray = ray_leaving(hit, s.w);
        from = hit.primitive;
    }
}

}  // namespace candela
