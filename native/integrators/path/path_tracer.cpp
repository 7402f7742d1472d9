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

/// MIS weight of strategy a against b (pdfs already scaled by their sample counts); a delta a weighs 1.
inline __attribute__((always_inline)) float mis_weight(MisHeuristic h, float a, float b) {
    if (std::isinf(a)) return 1.f;
    if (h == MisHeuristic::Power) {
        a *= a;
        b *= b;
    }
    const float sum = a + b;
    return sum > 0.f && std::isfinite(sum) ? a / sum : 0.f;
}

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

template <class ConcreteSampler>
void PathTracer::trace(Ray ray, PathState st, int bounce, ConcreteSampler& sampler, PathStats& stats, Color& L,
                       float* alpha, const TracedHit* first) const {
    const LightSet& lights = m_scene.lights();
    const PathSettings& cfg = m_settings;
    const int k = cfg.light_samples;
    const bool nee_enabled = !lights.empty();
    const WardLightSampler* ward = m_light_sampler.ward();

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
        const float t_surface = found ? hit.t : ray.tmax;

        // Emission found by this ray: MIS against light sampling (weight 1 after a camera ray or a delta
        // scatter; 0 when only light sampling estimates direct light). Indirect light (found after at least
        // one diffuse/glossy bounce from the first surface) may be clamped.
        auto add_emission = [&](const Color& Le, float light_pdf) __attribute__((always_inline)) {
            float w = 1.f;
            if (!st.specular) {
                if (cfg.light_sampling == LightSampling::LightOnly) w = light_pdf > 0.f ? 0.f : 1.f;
                else if (cfg.light_sampling == LightSampling::Mis) w = mis_weight(cfg.mis_heuristic, st.bsdf_pdf, light_pdf);
            }
            Color c = st.beta * Le * w;
            if (cfg.clamp_indirect > 0.f && bounce >= 2 && max_component(c) > cfg.clamp_indirect)
                c *= cfg.clamp_indirect / max_component(c);
            L += c;
        };
        // Density with which next-event estimation at the previous vertex would have produced this ray
        // toward light `index` (k shadow rays; with BSDF_ONLY nothing but delta lights is light-sampled).
        auto light_pdf = [&](uint32_t index, float t) __attribute__((always_inline)) {
            if (cfg.light_sampling == LightSampling::BsdfOnly || st.specular) return 0.f;
            const float pmf = ward ? ward->adaptive_pmf(st.origin, index, size_t(st.ward_tested))
                                   : m_light_sampler.nee_pmf(st.origin, index);
            return float(k) * pmf * light_pdf_li(lights[index], st.origin, ray.d, t, cfg.light_pdf);
        };

        // Area lights are not occluders: any emitting side before the surface adds its radiance.
        if (!lights.area_lights().empty()) {
            uint32_t li;
            float tl;
            if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, t_surface, &li, &tl, /*camera_ray=*/bounce == 0)) {
                const auto& area = std::get<AreaLight>(lights[li]);
                add_emission(area.radiance, light_pdf(li, tl));
            }
        }

        if (!found) {
            if (bounce == 0 && cfg.pixel.film_transparent) {
                *alpha = 0.f;
            } else if (const WorldLight* world = lights.world()) {
                add_emission(world->Le(ray.d), light_pdf(uint32_t(lights.world_light()), k_inf));
            } else if (!is_black(lights.background())) {
                add_emission(lights.background(), 0.f);  // a constant world: never light-sampled, weight 1
            }
            return;
        }

        if (bounce == 0 && !camera_hit(m_scene, ray, hit, st.aov, alpha)) return;  // data passes, holdout

        const ShadingPoint sp = m_scene.shade(hit, -ray.d);  // the material here: textures, normal map
        if (!is_black(sp.emission)) {
            add_emission(sp.emission, hit.light >= 0 ? light_pdf(uint32_t(hit.light), hit.t) : 0.f);
        }
        if (bounce > cfg.max_bounces) return;

        // Local shading frame on the side the path arrives from (surfaces are two-sided).
        const Vec3 wo = -ray.d;
        Vec3 ng = hit.ng, ns = sp.ns;
        const bool backfacing = dot(wo, ng) < 0.f;  // arriving against the winding normal (glass: from inside)
        if (backfacing) {
            ng = -ng;
            ns = -ns;
        }
        const Frame frame(dot(wo, ns) > 0.f ? ns : ng);  // a shading normal facing away: fall back
        const Vec3 wo_local = frame.to_local(wo);
        const Bsdf& bsdf = sp.bsdf();
        // Ray origins off the surface, on the side of ng (index 0: reflection, the side wo is on) or of −ng (1):
        // made on first use, then shared by every shadow ray and the continuation leaving that side.
        Vec3 spawn[2];
        bool spawned[2] = {false, false};
        auto spawn_origin = [&](bool front) __attribute__((always_inline)) -> const Vec3& {
            const int side = front ? 0 : 1;
            if (!spawned[side]) {
                spawn[side] = offset_ray_origin(hit.p, front ? ng : -ng);
                spawned[side] = true;
            }
            return spawn[side];
        };

        // Named sample dimensions: each is the same sequence dimension for every sample of every pixel, so
        // skipping one never shifts another. draw_bounce draws the values this vertex needs (the Sobol sampler
        // draws all of them in one SIMD batch, which costs less than drawing two or three one at a time).
        // The lambdas below are always_inline: called from several places, GCC otherwise keeps them out of line,
        // and their prologues and captured-state reloads cost ~5 % of a sample.
        const int dim = bounce + st.dim_offset;
        const bool nee_here = nee_enabled && bsdf.has_non_delta();
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

        // Cycles' roulette decides on arrival, before this vertex's shadow rays: with probability
        // q = min(1, √(max β·Πη²)) the vertex is shaded with β/q, else the path ends here (its emission, added
        // above, was the last term). E[1{u<q}/q] = 1, so the estimate stays unbiased; the square root keeps dim
        // paths alive longer than THROUGHPUT does (Cycles: "roughly match typical view transform").
        const bool arrival_roulette = roulette_here && cfg.rr_mode == RouletteMode::SqrtThroughput;
        if (arrival_roulette) {
            const float survive = min_num(1.f, std::sqrt(max_component(st.beta) * st.eta_scale));
            if (!(survive > 0.f) || u_rr >= survive) return;
            st.beta /= survive;
        }

        // Next-event estimation: k stratified shadow rays, each choosing one light (or, for ALL, k for every
        // light). The contribution of light i is f·Li·|cos|/(k·pmf·pdf), MIS-weighted against the continuation.
        // Returns the sample's visible irradiance share, luminance(Li)·|cos θ|/(k·pdf) (0 if occluded), the
        // quantity Ward's bounds bound.
        const LightSampleContext ctx{hit.p, ns};
        auto estimate_light = [&](uint32_t li, float pmf, Vec2 u) __attribute__((always_inline)) -> double {
            const LightSample ls = light_sample_li(lights[li], ctx, u, cfg.light_pdf);
            if (!ls.valid() || (cfg.light_sampling == LightSampling::BsdfOnly && !ls.is_delta)) return 0.0;
            const Vec3 wi_local = frame.to_local(ls.wi);
            // Both hemispheres (transmission); the geometric and shading sides must agree (no leaks).
            const float cos_g = dot(ls.wi, ng);
            if (cos_g == 0.f || (cos_g > 0.f) != (wi_local.z > 0.f)) return 0.0;
            const Color f = bsdf.f(wo_local, wi_local) * std::fabs(wi_local.z);
            if (is_black(f)) return 0.0;
            ++stats.rays;
            if (shadow_ray_blocked(m_scene, hit, spawn_origin(cos_g > 0.f), ls)) return 0.0;
            const float density = float(k) * pmf * ls.pdf;
            float w = 1.f;
            if (!ls.is_delta && cfg.light_sampling == LightSampling::Mis)
                w = mis_weight(cfg.mis_heuristic, density, continuation_pdf(cfg.hemisphere_sampling, bsdf, wo_local, wi_local));
            Color c = st.beta * f * ls.Li * (w / density);
            if (cfg.clamp_indirect > 0.f && bounce >= 1 && max_component(c) > cfg.clamp_indirect)
                c *= cfg.clamp_indirect / max_component(c);
            L += c;
            return double(luminance(ls.Li)) * std::fabs(wi_local.z) / (double(k) * double(ls.pdf));
        };
        // Continue the path (at the first surface, in branching_factor stratified branches). The first (usually
        // only) continuation direction is drawn here, before next-event estimation, although it is used after:
        // nothing in between depends on it, and its latency chain (a division, a polynomial, a square root for a
        // diffuse lobe) then overlaps the light sample instead of stalling the continuation.
        const int branches = bounce == 0 ? cfg.branching_factor : 1;
        const BsdfSample first_continuation =
            sample_continuation(cfg.hemisphere_sampling, bsdf, wo_local, light_sample_u(u_bsdf, 0u, uint32_t(branches)),
                                light_select_u(u_lobe, 0u, uint32_t(branches)));

        int ward_tested = 0;
        if (nee_here) {
            if (ward) {
                // Ward 1991, adaptive shadow testing: lights in decreasing order of their contribution bound are
                // estimated exactly (every light sample, selection probability 1) until the untested bounds sum
                // to at most ward_threshold × the visible irradiance found so far; the untested tail is then
                // estimated without bias by k samples of one tail light ∝ bound (WardList). The stopping index
                // depends only on lights already tested, so each tested estimate stays unbiased (optional
                // stopping), and the tail estimate uses fresh numbers.
                const WardList list = ward->candidates(ctx);
                double visible = 0.0;
                size_t tested = 0;
                while (!list.should_stop(tested, visible, double(cfg.ward_threshold))) {
                    const uint32_t li = list.candidates()[tested].light;
                    for (int i = 0; i < k; ++i) visible += estimate_light(li, 1.f, light_sample_u(u_light, uint32_t(i), uint32_t(k)));
                    ++tested;
                }
                ward_tested = int(tested);
                if (tested < list.size()) {
                    for (int i = 0; i < k; ++i) {
                        float q = 0.f;
                        const size_t j = list.select_tail(tested, light_select_u(u_select, uint32_t(i), uint32_t(k)), &q);
                        if (q > 0.f && j < list.size())
                            estimate_light(list.candidates()[j].light, q, light_sample_u(u_light, uint32_t(i), uint32_t(k)));
                    }
                }
            } else if (m_light_sampler.exhaustive()) {
                for (uint32_t li = 0; li < lights.size(); ++li)
                    for (int i = 0; i < k; ++i) estimate_light(li, 1.f, light_sample_u(u_light, uint32_t(i), uint32_t(k)));
            } else {
                for (int i = 0; i < k; ++i) {
                    float pmf = 0.f;
                    const uint32_t li = m_light_sampler.select(ctx, light_select_u(u_select, uint32_t(i), uint32_t(k)), &pmf);
                    if (pmf > 0.f) estimate_light(li, pmf, light_sample_u(u_light, uint32_t(i), uint32_t(k)));
                }
            }
        }

        auto continuation = [&](int j, Ray* next_ray, PathState* next) __attribute__((always_inline)) {
            const BsdfSample bs = j == 0 ? first_continuation
                                         : sample_continuation(cfg.hemisphere_sampling, bsdf, wo_local,
                                                               light_sample_u(u_bsdf, uint32_t(j), uint32_t(branches)),
                                                               light_select_u(u_lobe, uint32_t(j), uint32_t(branches)));
            if (!bs.valid() || is_black(bs.f)) return false;
            const Vec3 wi = frame.to_world(bs.wi);
            // The sampled side (reflection: +ng, transmission: −ng) must agree with the geometry: a leak else.
            const float cos_g = dot(wi, ng);
            if (bs.is_transmission() ? cos_g >= 0.f : cos_g <= 0.f) return false;
            next->beta = st.beta * bs.f * (std::fabs(bs.wi.z) / (bs.pdf * float(branches)));
            next->bsdf_pdf = bs.pdf;
            next->specular = bs.is_delta();
            // Radiance mode scales β by 1/η² at each refraction; undo it for the roulette only (robustness §5).
            next->eta_scale = st.eta_scale * (bs.is_transmission() ? bs.eta * bs.eta : 1.f);
            next->from = hit.primitive;
            next->origin = ctx;
            next->ward_tested = ward_tested;
            // Branches draw from their own sample dimensions (else they would repeat each other).
            next->dim_offset = st.dim_offset + j * (cfg.max_bounces + 2);
            if (roulette_here && !arrival_roulette) {
                const float survive = cfg.rr_mode == RouletteMode::Albedo
                                          ? min_num(1.f, max_component(bsdf.albedo(wo_local)))
                                          : min_num(1.f, max_component(next->beta) * float(branches) * next->eta_scale);
                if (!(survive > 0.f) || light_select_u(u_rr, uint32_t(j), uint32_t(branches)) >= survive) return false;
                next->beta /= survive;
            }
            if (is_black(next->beta) || !is_finite(next->beta)) return false;
            *next_ray = Ray{spawn_origin(cos_g > 0.f), wi, 0.f, k_inf,
                            continuation_ray_type(bs, ray.type)};
            return true;
        };
        if (branches == 1) {  // the common case: keep looping instead of recursing
            if (!continuation(0, &ray, &st)) return;
            continue;
        }
        for (int j = 0; j < branches; ++j) {
            Ray next_ray;
            PathState next;
            if (continuation(j, &next_ray, &next)) trace(next_ray, next, bounce + 1, sampler, stats, L, alpha);
        }
        return;
    }
}

}  // namespace candela
