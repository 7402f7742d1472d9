// Photon paths (Jensen 2001, ch. 5; docs/photon-mapping.md, "Pass 1"): light paths from the emitters, chosen ∝ power
// (or aimed at the caustic targets: caustic_emission.h), traced in importance transport mode by the vertex BSDF's
// light-side sampling (integrators/common/vertex_bsdf.h, Veach's adjoint shading-normal factor included), with
// Russian roulette by the surface's albedo from the first bounce (survival min(1, max f·|cos|/p): a surviving
// photon keeps about its parent's power). A photon reports every arrival at a surface that has estimated lobes
// (common/lobe_classes.h) — the first one included — with the flux it carries there (β, a flux per emitted path)
// and whether its path so far is a caustic one (L S⁺: at least one scattering, all of them traced).
//
// At a vertex with both traced and estimated lobes the path continues through one part, chosen with probability
// ∝ the part's albedo and divided by that probability (the parts sum to the BSDF: unbiased). Caustic-only paths
// (the caustic map's) continue through traced lobes only: a scattering by an estimated lobe ends every caustic path
// that could follow, so nothing is lost and nothing is divided.
//
// Random numbers: path i of a stream is sample i of a Sobol' sampler keyed by the stream, one named dimension set
// per vertex (the emission uses bounce 0's), so paths are a padded (0,2)-sequence in every pair of dimensions,
// independent of how paths are batched or threaded.
#pragma once

#include <cstdint>

#include "integrators/common/light_path.h"
#include "integrators/common/lobe_classes.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/photon_map/caustic_emission.h"
#include "integrators/render_context.h"
#include "lights/emitter_set.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

struct PhotonRules {
    int max_bounces = 12;  // scatterings of a photon path at most
    float alpha_threshold = k_default_traced_roughness * k_default_traced_roughness;
};

/// A photon arriving at a surface with estimated lobes.
struct PhotonArrival {
    const SurfaceHit* hit = nullptr;
    Vec3 w;                // unit: toward where the photon came from
    Color flux{0.f};       // its flux weight on arrival
    int depth = 0;         // scatterings before this arrival (0: straight from the emitter)
    bool caustic = false;  // depth ≥ 1 and every scattering so far traced
    uint32_t emitter = 0;  // EmitterSet index
};

enum class PhotonPaths { All, CausticOnly };

class PhotonTracer {
public:
    PhotonTracer(const Scene& scene, const EmitterSet& emitters, const PhotonRules& rules,
                 const CausticEmission* aimed = nullptr)
        : m_scene(scene), m_emitters(emitters), m_rules(rules), m_aimed(aimed) {}

    /// Traces the photon path of the sampler's current sample (positioned by the caller); arrive(const
    /// PhotonArrival&) is called at each arrival (CausticOnly: caustic arrivals only, from the aimed emission).
    template <class Arrive>
    void trace(SobolSampler& sampler, PhotonPaths paths, Arrive&& arrive, PathStats& stats) const;

private:
    const Scene& m_scene;
    const EmitterSet& m_emitters;
    const PhotonRules& m_rules;
    const CausticEmission* m_aimed;
};

template <class Arrive>
void PhotonTracer::trace(SobolSampler& sampler, PhotonPaths paths, Arrive&& arrive, PathStats& stats) const {
    const bool caustic_only = paths == PhotonPaths::CausticOnly;
    const BounceSample u0 = sampler.sample_bounce(0);
    ++stats.paths;
    const LightPathStart start =
        caustic_only ? (m_aimed ? m_aimed->sample(u0.light_select, u0.light, u0.bsdf, u0.roulette) : LightPathStart{})
                     : start_light_path(m_emitters, u0.light_select, u0.light, u0.bsdf, u0.lobe);
    if (!start.valid) return;
    Color beta = start.beta;
    Ray ray = start.ray;
    PrimitiveRef from;
    bool all_traced = true;  // every scattering so far by a traced lobe
    const float alpha_t = m_rules.alpha_threshold;
    for (int depth = 0;; ++depth) {
        SurfaceHit hit;
        ++stats.rays;
        if (!m_scene.intersect(ray, &hit, from)) return;
        // A soft point light lights its first receiver through the disk that faces it (lights/light_emission.h).
        if (depth == 0 && !emission_arrives(m_emitters[start.emitter], hit.p, ray.d)) return;
        const Vec3 w_l = -ray.d;
        const ShadingPoint sp = m_scene.shade(hit, w_l);
        const Bsdf& bsdf = sp.bsdf();
        const uint32_t traced = traced_lobe_mask(bsdf, alpha_t);
        const bool has_traced = traced != 0;
        const bool has_estimated = bsdf.size() > __builtin_popcount(traced);
        if (has_estimated) {
            const bool caustic = depth >= 1 && all_traced;
            if (!caustic_only || caustic) arrive(PhotonArrival{&hit, w_l, beta, depth, caustic, start.emitter});
        }
        if (depth >= m_rules.max_bounces) return;
        if (caustic_only && !has_traced) return;
        // Which part scatters: ∝ the parts' albedos (caustic paths: the traced part only).
        float p_traced = 1.f;
        if (has_traced && has_estimated && !caustic_only) {
            const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, w_l);
            const Vec3 wl_local = v.frame.to_local(w_l);
            const float a_t = luminance(lobe_subset(bsdf, traced, true).albedo(wl_local));
            const float a_e = luminance(lobe_subset(bsdf, traced, false).albedo(wl_local));
            p_traced = a_t + a_e > 0.f ? a_t / (a_t + a_e) : 0.5f;
        } else if (!has_traced) {
            p_traced = 0.f;
        }
        const BounceSample u = sampler.sample_bounce(depth + 1);
        const bool use_traced = u.light_select < p_traced;
        const float p_part = use_traced ? p_traced : 1.f - p_traced;
        if (!(p_part > 0.f)) return;
        const LobeSubset subset{alpha_t, use_traced};
        const bool split = has_traced && has_estimated;
        const VertexBsdf vb(m_scene, hit, w_l, sp, split ? &subset : nullptr);
        const VertexBsdf::Sample s = vb.sample_light(w_l, u.bsdf, u.lobe);
        if (!s.valid()) return;
        const Color weight = s.weight / p_part;
        const float q = light_path_survival(RouletteMode::Albedo, weight, Color(0.f));
        if (!(q > 0.f) || u.roulette >= q) return;
        beta *= weight / q;
        if (is_black(beta) || !is_finite(beta)) return;
        all_traced = all_traced && use_traced;
        ray = ray_leaving(hit, s.w);
        from = hit.primitive;
    }
}

}  // namespace candela
