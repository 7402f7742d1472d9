#include "integrators/path/path_tracer.h"

#include <cmath>
#include <limits>

#include "core/frame.h"
#include "core/math.h"
#include "integrators/camera_hit.h"
#include "integrators/ray_types.h"
#include "integrators/shadow_ray.h"
#include "sampling/warp.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

/// Continuation direction by the chosen hemisphere strategy; delta or mixed-delta BSDFs always use their
/// own sampling (a uniform or cosine direction can never hit a delta lobe).
BsdfSample sample_continuation(HemisphereSampling mode, const Bsdf& bsdf, const Vec3& wo, Vec2 u, float uc) {
    if (mode == HemisphereSampling::Bsdf || (bsdf.flags() & k_bsdf_specular)) return bsdf.sample(wo, u, uc);
    const bool both_sides = (bsdf.flags() & k_bsdf_transmission) != 0;
    BsdfSample s;
    s.wi = mode == HemisphereSampling::Uniform ? sample_uniform_hemisphere(u) : sample_cosine_hemisphere(u);
    if (s.wi.z <= 1e-7f) return {};
    s.pdf = mode == HemisphereSampling::Uniform ? uniform_hemisphere_pdf() : cosine_hemisphere_pdf(s.wi.z);
    if (both_sides) {
        s.pdf *= 0.5f;
        if (uc >= 0.5f) s.wi.z = -s.wi.z;
    }
    s.f = bsdf.f(wo, s.wi);
    s.flags = (s.wi.z > 0.f ? k_bsdf_reflection : k_bsdf_transmission) | k_bsdf_diffuse;
    return s;
}

/// The density sample_continuation draws wi with (for MIS).
float continuation_pdf(HemisphereSampling mode, const Bsdf& bsdf, const Vec3& wo, const Vec3& wi) {
    if (mode == HemisphereSampling::Bsdf || (bsdf.flags() & k_bsdf_specular)) return bsdf.pdf(wo, wi);
    const bool both_sides = (bsdf.flags() & k_bsdf_transmission) != 0;
    if (!both_sides && wi.z <= 0.f) return 0.f;
    const float p = mode == HemisphereSampling::Uniform ? uniform_hemisphere_pdf() : cosine_hemisphere_pdf(std::fabs(wi.z));
    return both_sides ? 0.5f * p : p;
}

/// Clamps an indirect contribution's brightest component to `clamp` (0 = off).
inline __attribute__((always_inline)) void clamp_contribution(Color& c, float clamp) {
    if (clamp > 0.f && max_component(c) > clamp) c *= clamp / max_component(c);
}

}  // namespace

Color PathTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov) const {
    Color L(0.f);
    *alpha = 1.f;
    if (!(camera_ray.tmax > camera_ray.tmin)) return L;  // outside a fisheye's image circle: nothing (Cycles)
    PathState st;
    st.aov = aov;
    std::visit([&](auto& concrete) { trace(camera_ray, st, 0, concrete, stats, L, alpha); }, sampler);
    return L;
}

Color PathTracer::Li(const Ray& camera_ray, const TracedHit& first, Sampler& sampler, PathStats& stats, float* alpha,
                     AovSample* aov) const {
    Color L(0.f);
    *alpha = 1.f;
    if (!(camera_ray.tmax > camera_ray.tmin)) return L;  // outside a fisheye's image circle: nothing (Cycles)
    PathState st;
    st.aov = aov;
    std::visit([&](auto& concrete) { trace(camera_ray, st, 0, concrete, stats, L, alpha, &first); }, sampler);
    return L;
}

// Emission found by a ray: MIS against light sampling (weight 1 after a camera ray or a delta scatter; 0 when
// only light sampling estimates direct light). Indirect light (found after at least one diffuse/glossy bounce
// from the first surface) may be clamped.
inline __attribute__((always_inline)) void PathTracer::add_emission(const PathState& st, int bounce, const Color& Le,
                                                                    float light_pdf, Color& L) const {
    Color c = st.beta * Le * emission_weight(m_settings.direct, st.origin, light_pdf);
    if (bounce >= 2) clamp_contribution(c, m_settings.clamp_indirect);
    L += c;
}

// Area lights are not occluders: any emitting side before the surface adds its radiance.
inline __attribute__((always_inline)) void PathTracer::add_area_light_emission(const Ray& ray, float t_surface, int bounce,
                                                                               const PathState& st, Color& L) const {
    const LightSet& lights = m_scene.lights();
    if (lights.area_lights().empty()) return;
    uint32_t li;
    float tl;
    if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, t_surface, &li, &tl, /*camera_ray=*/bounce == 0)) {
        const auto& area = std::get<AreaLight>(lights[li]);
        add_emission(st, bounce, area.radiance, nee_density(m_settings.direct, m_light_sampler, lights, st.origin, li, ray.d, tl), L);
    }
}

inline __attribute__((always_inline)) void PathTracer::add_world_emission(const Ray& ray, int bounce, const PathState& st,
                                                                          Color& L, float* alpha) const {
    const LightSet& lights = m_scene.lights();
    if (bounce == 0 && m_settings.pixel.film_transparent) {
        *alpha = 0.f;
    } else if (const WorldLight* world = lights.world()) {
        const uint32_t index = uint32_t(lights.world_light());
        add_emission(st, bounce, world->Le(ray.d),
                     nee_density(m_settings.direct, m_light_sampler, lights, st.origin, index, ray.d, k_inf), L);
    } else if (!is_black(lights.background())) {
        add_emission(st, bounce, lights.background(), 0.f, L);  // a constant world: never light-sampled, weight 1
    }
}

template <class ConcreteSampler>
void PathTracer::trace(Ray ray, PathState st, int bounce, ConcreteSampler& sampler, PathStats& stats, Color& L,
                       float* alpha, const TracedHit* first) const {
    for (;; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        bool found;
        if (first) {  // the camera ray, traced ahead in a packet
            found = first->found;
            if (found) hit = first->hit;
            first = nullptr;
        } else {
            found = m_scene.intersect(ray, &hit, st.from);
        }
        add_area_light_emission(ray, found ? hit.t : ray.tmax, bounce, st, L);
        if (!found) {
            add_world_emission(ray, bounce, st, L, alpha);
            return;
        }
        if (bounce == 0 && !camera_hit(m_scene, ray, hit, st.aov, alpha)) return;  // data passes, holdout

        const ShadingPoint sp = m_scene.shade(hit, -ray.d);  // the material here: textures, normal map
        if (!is_black(sp.emission)) {
            const float light_pdf = hit.light >= 0 ? nee_density(m_settings.direct, m_light_sampler, m_scene.lights(),
                                                                  st.origin, uint32_t(hit.light), ray.d, hit.t)
                                                   : 0.f;
            add_emission(st, bounce, sp.emission, light_pdf, L);
        }
        if (bounce > m_settings.max_bounces) return;
        if (!scatter(hit, sp, ray, st, bounce, sampler, stats, L, alpha)) return;
    }
}

template <class ConcreteSampler>
inline __attribute__((always_inline)) bool PathTracer::scatter(const SurfaceHit& hit, const ShadingPoint& sp, Ray& ray,
                                                               PathState& st, int bounce, ConcreteSampler& sampler,
                                                               PathStats& stats, Color& L, float* alpha) const {
    const PathSettings& cfg = m_settings;
    const LightSet& lights = m_scene.lights();
    const Vec3 wo = -ray.d;
    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
    const Vec3 wo_local = v.frame.to_local(wo);
    const Bsdf& bsdf = sp.bsdf();
    SpawnPoints spawn(hit.p, v.ng);

    // Named sample dimensions: each is the same sequence dimension for every sample of every pixel, so
    // skipping one never shifts another. draw_bounce draws the values this vertex needs (the Sobol sampler
    // draws all of them in one SIMD batch, which costs less than drawing two or three one at a time).
    const int dim = bounce + st.dim_offset;
    const bool nee_here = !lights.empty() && bsdf.has_non_delta();
    const bool roulette_here = cfg.rr_mode != RouletteMode::Off && bounce + 1 >= cfg.rr_start_bounce;
    // The discrete choice: which lobe, and for a dielectric (the one lobe that uses it) or a two-sided
    // hemisphere strategy, which side.
    const bool discrete_here = bsdf.size() > 1 || (bsdf.flags() & k_bsdf_transmission);
    const unsigned needs = (nee_here && !m_light_sampler.exhaustive() ? k_need_light_select : 0u) |
                           (nee_here ? k_need_light : 0u) | (roulette_here ? k_need_roulette : 0u) |
                           (discrete_here ? k_need_lobe : 0u);
    const BounceSample u = draw_bounce(sampler, dim, needs);
    const float u_select = (needs & k_need_light_select) ? u.light_select : 0.5f;
    const Vec2 u_light = nee_here ? u.light : Vec2{0.5f, 0.5f};
    const Vec2 u_bsdf = u.bsdf;
    const float u_rr = roulette_here ? u.roulette : 0.5f;
    const float u_lobe = discrete_here ? u.lobe : 0.5f;

    // Cycles' roulette decides on arrival, before this vertex's shadow rays (common/roulette.h).
    const bool arrival_roulette = roulette_here && cfg.rr_mode == RouletteMode::SqrtThroughput;
    if (arrival_roulette) {
        const float survive = arrival_survival(st.beta, st.eta_scale);
        if (!(survive > 0.f) || u_rr >= survive) return false;
        st.beta /= survive;
    }

    // Continue the path (at the first surface, in branching_factor stratified branches). The first (usually
    // only) continuation direction is drawn here, before next-event estimation, although it is used after:
    // nothing in between depends on it, and its latency chain (a division, a polynomial, a square root for a
    // diffuse lobe) then overlaps the light sample instead of stalling the continuation.
    const int branches = bounce == 0 ? cfg.branching_factor : 1;
    const BsdfSample first_continuation =
        sample_continuation(cfg.hemisphere_sampling, bsdf, wo_local, light_sample_u(u_bsdf, 0u, uint32_t(branches)),
                            light_select_u(u_lobe, 0u, uint32_t(branches)));

    // Next-event estimation (common/direct_light.h).
    const LightSampleContext ctx{hit.p, v.ns};
    int ward_tested = 0;
    if (nee_here) {
        ward_tested = next_event_estimation(
            cfg.direct, m_light_sampler, lights, ctx, u_select, u_light,
            [&](uint32_t li, float pmf, Vec2 u_li) __attribute__((always_inline)) {
                DirectLightSample d = sample_direct_light(
                    m_scene, cfg.direct, hit, v, spawn, ctx, bsdf, wo_local, st.beta, li, pmf, u_li,
                    [&](const Vec3& wi_local) __attribute__((always_inline)) {
                        return continuation_pdf(cfg.hemisphere_sampling, bsdf, wo_local, wi_local);
                    },
                    stats.rays);
                if (bounce >= 1) clamp_contribution(d.contribution, cfg.clamp_indirect);
                L += d.contribution;
                return d.visible;
            });
    }

    auto continuation = [&](int j, Ray* next_ray, PathState* next) __attribute__((always_inline)) {
        const BsdfSample bs = j == 0 ? first_continuation
                                     : sample_continuation(cfg.hemisphere_sampling, bsdf, wo_local,
                                                           light_sample_u(u_bsdf, uint32_t(j), uint32_t(branches)),
                                                           light_select_u(u_lobe, uint32_t(j), uint32_t(branches)));
        if (!bs.valid() || is_black(bs.f)) return false;
        const Vec3 wi = v.frame.to_world(bs.wi);
        // The sampled side (reflection: +ng, transmission: −ng) must agree with the geometry: a leak else.
        const float cos_g = dot(wi, v.ng);
        if (leaks(cos_g, bs.wi.z)) return false;
        next->beta = st.beta * bs.f * (std::fabs(bs.wi.z) / (bs.pdf * float(branches)));
        next->origin.bsdf_pdf = bs.pdf;
        next->origin.specular = bs.is_delta();
        // Radiance mode scales β by 1/η² at each refraction; undo it for the roulette only
        // (docs/robustness-notes.md §5).
        next->eta_scale = st.eta_scale * (bs.is_transmission() ? bs.eta * bs.eta : 1.f);
        next->from = hit.primitive;
        next->origin.point = ctx;
        next->origin.ward_tested = ward_tested;
        // Branches draw from their own sample dimensions (else they would repeat each other).
        next->dim_offset = st.dim_offset + j * (cfg.max_bounces + 2);
        if (roulette_here && !arrival_roulette) {
            const float survive = continuation_survival(cfg.rr_mode, next->beta, branches, next->eta_scale,
                                                        [&] { return bsdf.albedo(wo_local); });
            if (!(survive > 0.f) || light_select_u(u_rr, uint32_t(j), uint32_t(branches)) >= survive) return false;
            next->beta /= survive;
        }
        if (is_black(next->beta) || !is_finite(next->beta)) return false;
        *next_ray = Ray{spawn.origin(cos_g > 0.f), wi, 0.f, k_inf, continuation_ray_type(bs, ray.type)};
        return true;
    };
    if (branches == 1) return continuation(0, &ray, &st);  // the common case: the caller keeps looping
    for (int j = 0; j < branches; ++j) {
        Ray next_ray;
        PathState next;
        if (continuation(j, &next_ray, &next)) trace(next_ray, next, bounce + 1, sampler, stats, L, alpha);
    }
    return false;
}

}  // namespace candela
