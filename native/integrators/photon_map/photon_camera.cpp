#include "integrators/photon_map/photon_camera.h"

#include <cmath>
#include <limits>

#include "integrators/camera_hit.h"
#include "integrators/common/light_path.h"
#include "integrators/common/lobe_classes.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/ray_types.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

BounceSample draw(Sampler& sampler, int bounce, unsigned needs) {
    return std::visit([&](auto& concrete) { return draw_bounce(concrete, bounce, needs); }, sampler);
}

Vec2 rng_2d(Pcg32& rng) {
    const float a = rng.next_float();
    return {a, rng.next_float()};
}

}  // namespace

Color PhotonCameraTracer::direct(const SurfaceHit& hit, const Vec3& ns, const Vec3& wo, const Bsdf& part,
                                 const DirectLightRules& rules, float u_select, Vec2 u_light, PathStats& stats) const {
    const LightSet& lights = m_scene.lights();
    if (lights.empty() || !part.has_non_delta()) return Color(0.f);
    const SurfaceVertex v = SurfaceVertex::at(hit, ns, wo);
    const Vec3 wo_local = v.frame.to_local(wo);
    SpawnPoints spawn(hit.p, v.ng);
    const LightSampleContext ctx{hit.p, v.ns};
    Color L(0.f);
    next_event_estimation(rules, m_light_sampler, lights, ctx, u_select, u_light, [&](uint32_t li, float pmf, Vec2 u) {
        const DirectLightSample d = sample_direct_light(
            m_scene, rules, hit, v, spawn, ctx, part, wo_local, Color(1.f), li, pmf, u,
            [&](const Vec3& wi_local) { return part.pdf(wo_local, wi_local); }, stats.rays);
        L += d.contribution;
        return d.visible;
    });
    return L;
}

Color PhotonCameraTracer::map_estimate(const SurfaceHit& hit, const ShadingPoint& sp, const Vec3& wo,
                                       std::vector<PhotonNeighbor>& scratch, bool global) const {
    const LobeSubset estimated{m_settings.alpha_threshold(), false};
    const VertexBsdf vb(m_scene, hit, wo, sp, &estimated);
    Color L = radiance_estimate(m_caustic, vb, wo, m_lookup, scratch);
    if (global) L += radiance_estimate(m_global, vb, wo, m_lookup, scratch);
    return L;
}

Color PhotonCameraTracer::close_hit(const SurfaceHit& hit, const ShadingPoint& sp, const Vec3& wo, uint32_t traced,
                                    Pcg32& rng, PathStats& stats, std::vector<PhotonNeighbor>& scratch) const {
    const Bsdf part = lobe_subset(sp.bsdf(), traced, false);
    const float u_select = rng.next_float();
    Color L = direct(hit, sp.ns, wo, part, m_direct_e, u_select, rng_2d(rng), stats);
    L += map_estimate(hit, sp, wo, scratch, /*global=*/false);
    const LobeSubset estimated{m_settings.alpha_threshold(), false};
    const VertexBsdf vb(m_scene, hit, wo, sp, &estimated);
    const Vec2 u = rng_2d(rng);
    const VertexBsdf::Sample s = vb.sample_camera(wo, u, rng.next_float());
    if (s.valid()) L += s.weight * gather(ray_leaving(hit, s.w), hit.primitive, false, rng, stats, scratch);
    return L;
}

Color PhotonCameraTracer::gather(Ray ray, PrimitiveRef from, bool close_rule, Pcg32& rng, PathStats& stats,
                                 std::vector<PhotonNeighbor>& scratch) const {
    const LightSet& lights = m_scene.lights();
    const float alpha_t = m_settings.alpha_threshold();
    const float close = m_settings.gather_distance * m_lookup.max_radius;
    Color L(0.f), beta(1.f);
    for (int chain = 0; chain <= m_settings.max_bounces; ++chain) {
        SurfaceHit hit;
        ++stats.rays;
        if (!m_scene.intersect(ray, &hit, from)) {
            // A constant background is no light-sampled emitter: only rays find it. After T scatterings it is a
            // caustic of the caustic map.
            if (chain == 0 && !lights.world()) L += beta * lights.background();
            return L;
        }
        const Vec3 wo = -ray.d;
        const ShadingPoint sp = m_scene.shade(hit, wo);
        const Bsdf& bsdf = sp.bsdf();
        const uint32_t traced = traced_lobe_mask(bsdf, alpha_t);
        const bool has_estimated = bsdf.size() > __builtin_popcount(traced);
        if (has_estimated) {
            if (close_rule && chain == 0 && hit.t < close)
                L += beta * close_hit(hit, sp, wo, traced, rng, stats, scratch);
            else
                L += beta * map_estimate(hit, sp, wo, scratch);
        }
        if (traced == 0) return L;
        const LobeSubset traced_part{alpha_t, true};
        const VertexBsdf vb(m_scene, hit, wo, sp, has_estimated ? &traced_part : nullptr);
        const Vec2 u = rng_2d(rng);
        const VertexBsdf::Sample s = vb.sample_camera(wo, u, rng.next_float());
        if (!s.valid()) return L;
        beta *= s.weight;
        // Russian roulette on long glass chains (the throughput of a T chain stays ≤ 1 but rarely ends by itself).
        if (chain >= 3) {
            const float q = min_num(1.f, max_component(beta));
            if (!(q > 0.f) || rng.next_float() >= q) return L;
            beta /= q;
        }
        if (is_black(beta) || !is_finite(beta)) return L;
        ray = ray_leaving(hit, s.w);
        from = hit.primitive;
    }
    return L;
}

Color PhotonCameraTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha,
                             AovSample* aov) const {
    *alpha = 1.f;
    const LightSet& lights = m_scene.lights();
    const float alpha_t = m_settings.alpha_threshold();
    const int dims = m_settings.max_bounces + 2;  // dimension sets per role: the chain's, T's light, the gathers'
    std::vector<PhotonNeighbor> scratch(size_t(m_lookup.k));
    Color L(0.f), beta(1.f);
    Ray ray = camera_ray;
    PrimitiveRef from;
    EmissionOrigin origin;  // specular: weight 1 for the camera ray
    for (int bounce = 0;; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        const bool found = m_scene.intersect(ray, &hit, from);
        if (!lights.area_lights().empty()) {
            uint32_t li;
            float tl;
            if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit.t : ray.tmax, &li, &tl, bounce == 0)) {
                const float p = nee_density(m_direct_t, m_light_sampler, lights, origin, li, ray.d, tl);
                L += beta * std::get<AreaLight>(lights[li]).radiance * emission_weight(m_direct_t, origin, p);
            }
        }
        if (!found) {
            if (bounce == 0 && m_settings.pixel.film_transparent)
                *alpha = 0.f;
            else if (const WorldLight* world = lights.world()) {
                const float p = nee_density(m_direct_t, m_light_sampler, lights, origin, uint32_t(lights.world_light()),
                                            ray.d, k_inf);
                L += beta * world->Le(ray.d) * emission_weight(m_direct_t, origin, p);
            } else {
                L += beta * lights.background();
            }
            return L;
        }
        if (bounce == 0 && !camera_hit(m_scene, ray, hit, aov, alpha)) return L;
        const Vec3 wo = -ray.d;
        const ShadingPoint sp = m_scene.shade(hit, wo);
        if (!is_black(sp.emission)) {
            const float p = hit.light >= 0 ? nee_density(m_direct_t, m_light_sampler, lights, origin,
                                                         uint32_t(hit.light), ray.d, hit.t)
                                           : 0.f;
            L += beta * sp.emission * emission_weight(m_direct_t, origin, p);
        }
        if (bounce > m_settings.max_bounces) return L;
        const Bsdf& bsdf = sp.bsdf();
        const uint32_t traced = traced_lobe_mask(bsdf, alpha_t);
        const bool has_estimated = bsdf.size() > __builtin_popcount(traced);
        const BounceSample u =
            draw(sampler, bounce, k_need_light_select | k_need_light | k_need_lobe | k_need_roulette);
        if (has_estimated) {
            // Direct light, caustics and final gathering through E.
            const Bsdf part = lobe_subset(bsdf, traced, false);
            Color Le = direct(hit, sp.ns, wo, part, m_direct_e, u.light_select, u.light, stats);
            Le += map_estimate(hit, sp, wo, scratch, /*global=*/false);
            const LobeSubset estimated{alpha_t, false};
            const VertexBsdf vb(m_scene, hit, wo, sp, &estimated);
            const BounceSample ug = draw(sampler, bounce + 2 * dims, k_need_lobe | k_need_roulette);
            const uint32_t n = uint32_t(m_settings.final_gather_rays);
            Color gathered(0.f);
            Pcg32 rng(hash_combine(uint64_t(ug.roulette * 16777216.f), uint64_t(bounce)), 0x67617468ULL);
            for (uint32_t j = 0; j < n; ++j) {
                const VertexBsdf::Sample s =
                    vb.sample_camera(wo, light_sample_u(ug.bsdf, j, n), light_select_u(ug.lobe, j, n));
                if (!s.valid()) continue;
                gathered += s.weight * gather(ray_leaving(hit, s.w), hit.primitive, true, rng, stats, scratch);
            }
            L += beta * (Le + gathered / float(n));
        }
        if (traced == 0) return L;
        // The traced lobes: next-event estimation for the non-delta ones, then the camera path goes on through them.
        const Bsdf part = lobe_subset(bsdf, traced, true);
        if (part.has_non_delta()) {
            const BounceSample ut = draw(sampler, bounce + dims, k_need_light_select | k_need_light);
            L += beta * direct(hit, sp.ns, wo, part, m_direct_t, ut.light_select, ut.light, stats);
        }
        const LobeSubset traced_part{alpha_t, true};
        const VertexBsdf vb(m_scene, hit, wo, sp, has_estimated ? &traced_part : nullptr);
        const VertexBsdf::Sample s = vb.sample_camera(wo, u.bsdf, u.lobe);
        if (!s.valid()) return L;
        beta *= s.weight;
        if (bounce >= 3) {
            const float q = min_num(1.f, max_component(beta));
            if (!(q > 0.f) || u.roulette >= q) return L;
            beta /= q;
        }
        if (is_black(beta) || !is_finite(beta)) return L;
        origin.specular = s.delta;
        origin.bsdf_pdf = s.pdf;
        origin.point = LightSampleContext{hit.p, SurfaceVertex::at(hit, sp.ns, wo).ns};
        Ray next = ray_leaving(hit, s.w);
        next.type = continuation_ray_type(s.bsdf, ray.type);
        ray = next;
        from = hit.primitive;
    }
}

}  // namespace candela
