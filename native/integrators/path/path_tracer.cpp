#include "integrators/path/path_tracer.h"

#include <cmath>
#include <limits>

#include "bsdf/bsdf_filters.h"
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
    const float p =
        mode == HemisphereSampling::Uniform ? uniform_hemisphere_pdf() : cosine_hemisphere_pdf(std::fabs(wi.z));
    return both_sides ? 0.5f * p : p;
}

/// The largest α of the BSDF's dielectric lobes (Film > Transparent Glass compares it with its roughness threshold).
float transmission_alpha(const Bsdf& b) {
    float a = 0.f;
    for (int i = 0; i < b.size(); ++i)
        if (const auto* g = std::get_if<MicrofacetDielectric>(&b[i].lobe))
            a = std::fmax(a, std::fmax(g->distribution.alpha_x, g->distribution.alpha_y));
    return a;
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
// only light sampling estimates direct light), then the clamp of its kind (common/light_paths.h).
inline __attribute__((always_inline)) void PathTracer::add_emission(const PathState& st, const Color& Le,
                                                                    float light_pdf, Color& L) const {
    Color c = st.beta * Le * emission_weight(m_settings.direct, st.origin, light_pdf);
    clamp_contribution(c, m_settings.paths, st.lp.depth.bounce - 1);
    L += c;
}

// Area lights are not occluders: any emitting side before the surface adds its radiance. The camera's visibility
// of a light holds for the camera ray and its continuations through transparent surfaces.
inline __attribute__((always_inline)) void PathTracer::add_area_light_emission(const Ray& ray, float t_surface,
                                                                               const PathState& st, Color& L) const {
    const LightSet& lights = m_scene.lights();
    if (lights.area_lights().empty()) return;
    uint32_t li;
    float tl;
    if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, t_surface, &li, &tl,
                                     /*camera_ray=*/ray.type == k_ray_camera)) {
        const auto& area = std::get<AreaLight>(lights[li]);
        add_emission(st, area.radiance,
                     nee_density(m_settings.direct, m_light_sampler, lights, st.origin, li, ray.d, st.mis_t + tl), L);
    }
}

inline __attribute__((always_inline)) void PathTracer::add_world_emission(const Ray& ray, const PathState& st, Color& L,
                                                                          float* alpha) const {
    const LightSet& lights = m_scene.lights();
    if (st.lp.transparent_background && m_settings.pixel.film_transparent) {
        // The background seen through nothing but transparent surfaces (and, with Transparent Glass, smooth
        // refractions) is transparent: alpha loses the throughput's average, as Cycles' transparent background does.
        *alpha = st.lp.depth.bounce == 0 && st.lp.depth.transparent == 0
                     ? 0.f
                     : std::fmax(0.f, *alpha - (st.beta.x + st.beta.y + st.beta.z) / 3.f);
    } else if (const WorldLight* world = lights.world()) {
        const uint32_t index = uint32_t(lights.world_light());
        const Color Le =
            m_scene.world_reads_light_path() ? m_scene.world_radiance(ray.d, st.lp.info(k_inf)) : world->Le(ray.d);
        add_emission(st, Le, nee_density(m_settings.direct, m_light_sampler, lights, st.origin, index, ray.d, k_inf),
                     L);
    } else if (m_scene.world_reads_light_path()) {
        add_emission(st, m_scene.world_radiance(ray.d, st.lp.info(k_inf)), 0.f, L);  // constant but path-dependent
    } else if (!is_black(lights.background())) {
        add_emission(st, lights.background(), 0.f, L);  // a constant world: never light-sampled, weight 1
    }
}

template <class ConcreteSampler>
void PathTracer::trace(Ray ray, PathState st, int vertex, ConcreteSampler& sampler, PathStats& stats, Color& L,
                       float* alpha, const TracedHit* first) const {
    const LightPathSettings& paths = m_settings.paths;
    const bool light_path = m_scene.reads_light_path();
    for (;; ++vertex) {
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
        add_area_light_emission(ray, found ? hit.t : ray.tmax, st, L);
        if (!found) {
            add_world_emission(ray, st, L, alpha);
            return;
        }
        if (vertex == 0 && !camera_hit(m_scene, ray, hit, st.aov, alpha)) return;  // data passes, holdout

        // The material here (textures, normal map), shaded for this ray's Light Path inputs where a shader reads them.
        LightPathInfo info;
        if (light_path) info = st.lp.info(hit.t * length(ray.d));
        const ShadingPoint sp = m_scene.shade(hit, -ray.d, light_path ? &info : nullptr);
        if (!is_black(sp.emission)) {
            const float light_pdf = hit.light >= 0
                                        ? nee_density(m_settings.direct, m_light_sampler, m_scene.lights(), st.origin,
                                                      uint32_t(hit.light), ray.d, st.mis_t + hit.t)
                                        : 0.f;
            add_emission(st, sp.emission, light_pdf, L);
        }
        if (!may_scatter(paths, st.lp.depth)) {
            // Out of bounces: the path goes on only through Transparent closures, to the next emitter it finds.
            if (!may_pass_transparent(paths, st.lp.depth) ||
                !(m_scene.material_flags(hit.material) & k_bsdf_transparent))
                return;
            const Color through = transparency(sp.bsdf());
            if (is_black(through)) return;
            st.beta *= through;
            ++st.lp.depth.transparent;
            st.mis_t += hit.t;
            st.from = hit.primitive;
            ray.o = offset_ray_origin(hit.p, dot(ray.d, hit.ng) > 0.f ? hit.ng : -hit.ng);
            ray.tmin = 0.f;
            ray.tmax = k_inf;
            continue;
        }
        if (!scatter(hit, sp, ray, st, vertex, sampler, stats, L, alpha)) return;
    }
}

template <class ConcreteSampler>
inline __attribute__((always_inline)) bool PathTracer::scatter(const SurfaceHit& hit, const ShadingPoint& sp, Ray& ray,
                                                               PathState& st, int vertex, ConcreteSampler& sampler,
                                                               PathStats& stats, Color& L, float* alpha) const {
    const PathSettings& cfg = m_settings;
    const LightSet& lights = m_scene.lights();
    const Vec3 wo = -ray.d;
    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
    const Vec3 wo_local = v.frame.to_local(wo);
    // The BSDF, with the Light Paths rules (Filter Glossy, Caustics) and bump shadowing where they apply.
    BsdfSlot slot;
    const Bsdf& bsdf =
        (sp.bent || modifies_bsdfs(cfg.paths))
            ? vertex_scattering_bsdf(sp.bsdf(), cfg.paths, st.lp, wo_local.z, v.bump_shadowing(sp.bent, hit.ns), slot)
            : sp.bsdf();
    SpawnPoints spawn(hit.p, v.ng);
    const int bounce = st.lp.depth.bounce;  // scatterings so far (transparent pass-throughs excluded)

    // Named sample dimensions: each is the same sequence dimension for every sample of every pixel, so
    // skipping one never shifts another. draw_bounce draws the values this vertex needs (the Sobol sampler
    // draws all of them in one SIMD batch, which costs less than drawing two or three one at a time).
    const int dim = vertex + st.dim_offset;
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
    const int branches = vertex == 0 ? cfg.branching_factor : 1;
    const BsdfSample first_continuation =
        sample_continuation(cfg.hemisphere_sampling, bsdf, wo_local, light_sample_u(u_bsdf, 0u, uint32_t(branches)),
                            light_select_u(u_lobe, 0u, uint32_t(branches)));

    // Next-event estimation (common/direct_light.h); shadow rays pass Transparent surfaces.
    const LightSampleContext ctx{hit.p, v.ns};
    int ward_tested = 0;
    if (nee_here) {
        const ShadowRayInputs shadow{st.lp.shadow_info(), cfg.paths.transparent_bounces - st.lp.depth.transparent};
        ward_tested = next_event_estimation(
            cfg.direct, m_light_sampler, lights, ctx, u_select,
            u_light, [&](uint32_t li, float pmf, Vec2 u_li) __attribute__((always_inline)) {
                DirectLightSample d = sample_direct_light(
                    m_scene, cfg.direct, hit, v, spawn, ctx, bsdf, wo_local, st.beta, li, pmf, u_li,
                    [&](const Vec3& wi_local) __attribute__((always_inline)) {
                        return continuation_pdf(cfg.hemisphere_sampling, bsdf, wo_local, wi_local);
                    },
                    stats.rays, &shadow);
                clamp_contribution(d.contribution, cfg.paths, bounce);
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
        next->lp = st.lp;
        if (bs.is_transparent()) {
            // The same ray carried on: MIS still weighs what it finds against the vertex before (at the summed
            // distance), and nothing else of the path changes.
            next->origin = st.origin;
            next->mis_t = st.mis_t + hit.t;
            next->eta_scale = st.eta_scale;
            after_scatter(next->lp, bs);
        } else {
            next->origin.bsdf_pdf = bs.pdf;
            next->origin.specular = bs.is_delta();
            next->origin.point = ctx;
            next->origin.ward_tested = ward_tested;
            next->mis_t = 0.f;
            // Radiance mode scales β by 1/η² at each refraction; undo it for the roulette only
            // (docs/robustness-notes.md §5).
            next->eta_scale = st.eta_scale * (bs.is_transmission() ? bs.eta * bs.eta : 1.f);
            const bool see_through = cfg.pixel.transparent_glass && bs.is_transmission() &&
                                     !(bs.flags & k_bsdf_diffuse) &&
                                     transmission_alpha(bsdf) <= cfg.pixel.transparent_roughness;
            after_scatter(next->lp, bs, see_through);
        }
        next->from = hit.primitive;
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
        if (continuation(j, &next_ray, &next)) trace(next_ray, next, vertex + 1, sampler, stats, L, alpha);
    }
    return false;
}

}  // namespace candela
