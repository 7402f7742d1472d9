// Direct light at a surface vertex, estimated twice and combined by multiple importance sampling (Veach 1997,
// ch. 9, eqs. 9.12–9.13, with n_light = light_samples): by next-event estimation — k stratified shadow rays, each
// choosing a light by the light-selection strategy (or every light, for ALL; or Ward's adaptive shadow testing)
// and a point on it by area or solid angle — and by the BSDF-sampled continuation hitting an emitter. These are
// the rules every integrator that estimates direct light uses (PATH at every vertex; the photon mapper, the
// irradiance cache and the indirect path generators at their visible points): one copy, so they cannot disagree.
//
//   NEE sample of light i:   β · f(wo, wi) · Li · |cos θ| · w_light / (k · pmf_i · p_light),
//   emission found by a ray: β · Le · w_bsdf,   w_bsdf = w(p_bsdf, k · pmf_i · p_light)  (0 after LIGHT_ONLY),
// with delta lights (p_light = ∞ in effect) weighted 1, and BSDF_ONLY keeping light sampling for delta lights.
#pragma once

#include <cmath>
#include <cstdint>

#include "bsdf/bsdf.h"
#include "integrators/common/mis.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/shadow_ray.h"
#include "lights/light.h"
#include "lights/light_sampler.h"
#include "scene/scene.h"

namespace candela {

/// Which estimators of direct light run: BSDF sampling only (delta lights excepted: nothing can hit them),
/// next-event estimation only, or both combined by multiple importance sampling.
enum class LightSampling { BsdfOnly, LightOnly, Mis };

/// The direct-light settings an integrator hands the shared rules.
struct DirectLightRules {
    LightSampling light_sampling = LightSampling::Mis;
    MisHeuristic mis_heuristic = MisHeuristic::Power;
    LightPdfMode light_pdf = LightPdfMode::SolidAngle;
    int light_samples = 1;  // k shadow rays per vertex
    float ward_threshold = 0.05f;
};

/// Whether next-event estimation samples an environment's MIS-compensated map: when it is combined by MIS with
/// BSDF sampling, which covers the directions where the environment is below its mean (Karlík et al. 2019;
/// lights/environment_bake.h). Without MIS (LIGHT_ONLY) it must stand alone: the plain map.
inline bool nee_for_mis(const DirectLightRules& rules) { return rules.light_sampling == LightSampling::Mis; }

/// What a path's last scattering leaves for MIS at the emitter its ray finds.
struct EmissionOrigin {
    bool specular = true;      // camera ray or delta scatter: emission counts with weight 1
    float bsdf_pdf = 0.f;      // density of the strategy that produced the ray
    LightSampleContext point;  // the vertex the ray left, as light sampling saw it
    int ward_tested = 0;       // WARD: how many candidates that vertex shadow-tested (its MIS realisation)
};

/// Density with which next-event estimation at `origin` would have produced direction d toward light `index`
/// hit at distance t (0 where it could not: BSDF_ONLY, or after a delta scatter).
inline __attribute__((always_inline)) float nee_density(const DirectLightRules& rules, const LightSampler& sampler,
                                                        const LightSet& lights, const EmissionOrigin& origin,
                                                        uint32_t index, const Vec3& d, float t) {
    if (rules.light_sampling == LightSampling::BsdfOnly || origin.specular) return 0.f;
    const WardLightSampler* ward = sampler.ward();
    const float pmf = ward ? ward->adaptive_pmf(origin.point, index, size_t(origin.ward_tested))
                           : sampler.nee_pmf(origin.point, index);
    return float(rules.light_samples) * pmf *
           light_pdf_li(lights[index], origin.point, d, t, rules.light_pdf, nee_for_mis(rules));
}

/// MIS weight of emission found by a BSDF-sampled ray, against next-event estimation of density light_pdf.
inline __attribute__((always_inline)) float emission_weight(const DirectLightRules& rules, const EmissionOrigin& origin,
                                                            float light_pdf) {
    if (origin.specular) return 1.f;
    if (rules.light_sampling == LightSampling::LightOnly) return light_pdf > 0.f ? 0.f : 1.f;
    if (rules.light_sampling == LightSampling::Mis) return mis_weight(rules.mis_heuristic, origin.bsdf_pdf, light_pdf);
    return 1.f;
}

/// One next-event sample: its MIS-weighted contribution β·f·Li·|cos|·w/(k·pmf·p), and the visible irradiance share
/// luminance(Li)·|cos θ|/(k·pdf) that Ward's bounds bound (0 if invalid or occluded).
struct DirectLightSample {
    Color contribution{0.f};
    double visible = 0.0;
};

/// Next-event estimation of light `li` (selected with probability pmf) at vertex v for a path of throughput beta
/// arriving from wo_local, with the weight weight(ls, wi_local, density) → w of the sample (density = k·pmf·p_light):
/// the contribution is β·f·Li·|cos|·w/density. `rays` counts the shadow ray.
/// `shadow`: transparent shadows (shadow rays through Transparent surfaces, shaded with its Light Path inputs);
/// null: every surface blocks. Objects with a shadow terminator offset start their shadow rays from the lifted
/// point (shadow_ray_origin).
template <class Weight>
inline __attribute__((always_inline)) DirectLightSample sample_direct_light_weighted(
    const Scene& scene, const DirectLightRules& rules, const SurfaceHit& hit, const SurfaceVertex& v,
    SpawnPoints& spawn, const LightSampleContext& ctx, const Bsdf& bsdf, const Vec3& wo_local, const Color& beta,
    uint32_t li, float pmf, Vec2 u, Weight&& weight, uint64_t& rays, const ShadowRayInputs* shadow = nullptr) {
    DirectLightSample out;
    const LightSample ls = light_sample_li(scene.lights()[li], ctx, u, rules.light_pdf, nee_for_mis(rules));
    if (!ls.valid() || (rules.light_sampling == LightSampling::BsdfOnly && !ls.is_delta)) return out;
    const Vec3 wi_local = v.frame.to_local(ls.wi);
    // Both hemispheres (transmission); the geometric and shading sides must agree (no leaks) — except, as in Cycles,
    // for a light above the shading hemisphere but below the facet of a smooth triangle with a shadow terminator
    // offset: the lifted shadow ray, which its own facet may block, decides (docs/light_paths.md).
    const float cos_g = dot(ls.wi, v.ng);
    const bool below_facet = leaks(cos_g, wi_local.z);
    if (below_facet && !(wi_local.z > 0.f && cos_g < 0.f && scene.terminator_lifts(hit))) return out;
    const Color f = bsdf.f(wo_local, wi_local) * std::fabs(wi_local.z);
    if (is_black(f)) return out;
    ++rays;
    const bool front = below_facet ? true : cos_g > 0.f;
    const Vec3 origin = shadow_ray_origin(scene, hit, v.backfacing ? -hit.ns : hit.ns, v.ng, ls.wi, front, spawn);
    Color through(1.f);
    if (shadow && scene.has_transparent_materials()) {
        through = shadow_ray_transmittance(scene, hit, origin, ls, *shadow, !below_facet);
        if (is_black(through)) return out;
    } else if (shadow_ray_blocked(scene, hit, origin, ls, !below_facet)) {
        return out;
    }
    const int k = rules.light_samples;
    const float density = float(k) * pmf * ls.pdf;
    const float w = weight(ls, wi_local, density);
    out.contribution = beta * f * ls.Li * (w / density);
    if (shadow) out.contribution *= through;  // (exactly 1 without transparent materials)
    out.visible = double(luminance(ls.Li * through)) * std::fabs(wi_local.z) / (double(k) * double(ls.pdf));
    return out;
}

/// Next-event estimation of light `li` (selected with probability pmf) at vertex v for a path of throughput beta
/// arriving from wo_local. `continuation_pdf(wi_local)` is the density of the integrator's continuation strategy
/// (for MIS); `rays` counts the shadow ray; `shadow` as for sample_direct_light_weighted.
template <class ContinuationPdf>
inline __attribute__((always_inline)) DirectLightSample sample_direct_light(
    const Scene& scene, const DirectLightRules& rules, const SurfaceHit& hit, const SurfaceVertex& v,
    SpawnPoints& spawn, const LightSampleContext& ctx, const Bsdf& bsdf, const Vec3& wo_local, const Color& beta,
    uint32_t li, float pmf, Vec2 u, ContinuationPdf&& continuation_pdf, uint64_t& rays,
    const ShadowRayInputs* shadow = nullptr) {
    return sample_direct_light_weighted(
        scene, rules, hit, v, spawn, ctx, bsdf, wo_local, beta, li, pmf, u,
        [&](const LightSample& ls, const Vec3& wi_local, float density) __attribute__((always_inline)) {
            if (ls.is_delta || rules.light_sampling != LightSampling::Mis) return 1.f;
            return mis_weight(rules.mis_heuristic, density, continuation_pdf(wi_local));
        },
        rays, shadow);
}

/// Runs next-event estimation at a light-sample context with the strategy of `sampler` (one light per shadow
/// ray, every light for ALL, Ward's adaptive shadow testing for WARD), calling estimate(light, pmf, u) → the
/// sample's visible share for each light sample. Returns how many candidates WARD tested (its MIS realisation;
/// 0 otherwise).
///
/// Ward 1991, adaptive shadow testing: lights in decreasing order of their contribution bound are estimated
/// exactly (every light sample, selection probability 1) until the untested bounds sum to at most ward_threshold ×
/// the visible irradiance found so far; the untested tail is then estimated without bias by k samples of one tail
/// light ∝ bound (WardList). The stopping index depends only on lights already tested, so each tested estimate
/// stays unbiased (optional stopping), and the tail estimate uses fresh numbers.
template <class Estimate>
inline __attribute__((always_inline)) int next_event_estimation(const DirectLightRules& rules,
                                                                const LightSampler& sampler, const LightSet& lights,
                                                                const LightSampleContext& ctx, float u_select,
                                                                Vec2 u_light, Estimate&& estimate) {
    const uint32_t k = uint32_t(rules.light_samples);
    if (const WardLightSampler* ward = sampler.ward()) {
        const WardList list = ward->candidates(ctx);
        double visible = 0.0;
        size_t tested = 0;
        while (!list.should_stop(tested, visible, double(rules.ward_threshold))) {
            const uint32_t li = list.candidates()[tested].light;
            for (uint32_t i = 0; i < k; ++i) visible += estimate(li, 1.f, light_sample_u(u_light, i, k));
            ++tested;
        }
        if (tested < list.size()) {
            for (uint32_t i = 0; i < k; ++i) {
                float q = 0.f;
                const size_t j = list.select_tail(tested, light_select_u(u_select, i, k), &q);
                if (q > 0.f && j < list.size()) estimate(list.candidates()[j].light, q, light_sample_u(u_light, i, k));
            }
        }
        return int(tested);
    }
    if (sampler.exhaustive()) {
        for (uint32_t li = 0; li < lights.size(); ++li)
            for (uint32_t i = 0; i < k; ++i) estimate(li, 1.f, light_sample_u(u_light, i, k));
        return 0;
    }
    for (uint32_t i = 0; i < k; ++i) {
        float pmf = 0.f;
        const uint32_t li = sampler.select(ctx, light_select_u(u_select, i, k), &pmf);
        if (pmf > 0.f) estimate(li, pmf, light_sample_u(u_light, i, k));
    }
    return 0;
}

}  // namespace candela
