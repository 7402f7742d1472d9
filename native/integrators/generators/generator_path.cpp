#include "integrators/generators/generator_path.h"

#include <cmath>
#include <limits>

#include "integrators/camera_hit.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/roulette.h"
#include "integrators/ray_types.h"

namespace candela {

namespace {
constexpr float k_inf = std::numeric_limits<float>::infinity();
}  // namespace

GeneratorTracer::GeneratorTracer(const Scene& scene, const GeneratorSettings& settings,
                                 const LightSampler& light_sampler, const EmitterSet& emitters,
                                 const SurfaceSampler* surfaces)
    : m_scene(scene),
      m_settings(settings),
      m_light_sampler(light_sampler),
      m_emitters(emitters),
      m_surfaces(surfaces),
      m_weights(scene, light_sampler, emitters, surfaces, settings) {
    m_light_only = settings.direct;
    m_light_only.light_sampling = LightSampling::LightOnly;
    for (uint32_t k = 0; k < scene.materials().size(); ++k)
        if (scene.material_flags(k) & k_bsdf_specular) m_any_delta = true;
    m_unsampled_emission = !scene.lights().world() && !is_black(scene.lights().background());
    m_source_slot = 3 * (settings.max_bounces + 2);
}

Color GeneratorTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha,
                          AovSample* aov) const {
    *alpha = 1.f;
    GeneratorPath path(*this, sampler, stats);
    return path.run(camera_ray, alpha, aov);
}

Color GeneratorPath::run(const Ray& camera_ray, float* alpha, AovSample* aov) {
    receiver_walk(camera_ray, Color(1.f), 0, RayOrigin{}, true, alpha, aov);
    return m_L;
}

BounceSample GeneratorPath::draw(int slot_index, unsigned needs) {
    return std::visit([&](auto& s) { return draw_bounce(s, slot_index, needs); }, m_sampler);
}

Ray GeneratorPath::continuation_ray(const SurfaceVertex& v, SpawnPoints& spawn, const BsdfSample& bs,
                                    uint8_t previous_type) const {
    const Vec3 wi = v.frame.to_world(bs.wi);
    return Ray{spawn.origin(dot(wi, v.ng) > 0.f), wi, 0.f, k_inf, continuation_ray_type(bs, previous_type)};
}

float GeneratorPath::emitter_weight(const RayOrigin& o, int light, int emitter, const Vec3& d, float t,
                                    const Vec3& n) const {
    if (o.e.specular) return 1.f;
    const LightSet& lights = m_t.m_scene.lights();
    const DirectLightRules& rules = o.gathered ? m_t.m_light_only : m_cfg.direct;
    const float pdf = light >= 0 ? nee_density(rules, m_t.m_light_sampler, lights, o.e, uint32_t(light), d, t) : 0.f;
    const float w = emission_weight(rules, o.e, pdf);
    if (!(w > 0.f) || !o.gathered || !o.one_bounce.x) return w;
    const OneBounceLight y{light, emitter, d, t, n};
    return m_t.m_weights.weight(o.one_bounce.generator, *o.one_bounce.x, o.one_bounce.wo_x, *o.one_bounce.z, y);
}

bool GeneratorPath::trace_emission(const Ray& ray, const Color& beta, const RayOrigin& origin, bool camera,
                                   SurfaceHit* hit, ShadingPoint* sp, float* alpha, AovSample* aov) {
    const Scene& scene = m_t.m_scene;
    const LightSet& lights = scene.lights();
    ++m_stats.rays;
    const bool found = scene.intersect(ray, hit, origin.from);
    // Area lights are not occluders: any emitting side before the surface adds its radiance.
    if (!lights.area_lights().empty()) {
        uint32_t li;
        float tl;
        if (scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit->t : ray.tmax, &li, &tl, camera)) {
            const auto& area = std::get<AreaLight>(lights[li]);
            m_L += beta * area.radiance * emitter_weight(origin, int(li), int(li), ray.d, tl, area.normal);
        }
    }
    if (!found) {
        if (camera && m_cfg.pixel.film_transparent) {
            *alpha = 0.f;
        } else if (const WorldLight* world = lights.world()) {
            const int index = lights.world_light();
            m_L += beta * world->Le(ray.d) * emitter_weight(origin, index, index, ray.d, k_inf, Vec3(0.f));
        } else if (!is_black(lights.background())) {
            m_L += beta * lights.background() *
                   emitter_weight(origin, -1, m_t.m_emitters.world(), ray.d, k_inf, Vec3(0.f));
        }
        return false;
    }
    if (camera && !camera_hit(scene, ray, *hit, aov, alpha)) return false;
    *sp = scene.shade(*hit, -ray.d);
    if (!is_black(sp->emission))
        m_L += beta * sp->emission * emitter_weight(origin, hit->light, hit->light, ray.d, hit->t, hit->ng);
    return true;
}

void GeneratorPath::receiver_walk(Ray ray, Color beta, int n, RayOrigin origin, bool camera, float* alpha,
                                  AovSample* aov) {
    const Scene& scene = m_t.m_scene;
    for (;; ++n) {
        SurfaceHit hit;
        ShadingPoint sp;
        if (!trace_emission(ray, beta, origin, camera, &hit, &sp, alpha, aov)) return;
        if (n > m_cfg.max_bounces) return;
        const Vec3 wo = -ray.d;
        const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
        const VertexBsdf vb(scene, hit, wo, sp);
        const Bsdf& bsdf = sp.bsdf();
        SpawnPoints spawn(hit.p, v.ng);
        const BounceSample u = draw(slot(n, 0), k_need_light_select | k_need_light | k_need_lobe);
        const Receiver r{&vb, wo, beta, n};
        int ward_tested = 0;
        if (bsdf.has_non_delta()) at_receiver(r, hit, v, spawn, u, &ward_tested);
        const BsdfSample bs = bsdf.sample(v.frame.to_local(wo), u.bsdf, u.lobe);
        if (!bs.valid() || is_black(bs.f)) return;
        const Ray next = continuation_ray(v, spawn, bs, ray.type);
        if (leaks(dot(next.d, v.ng), bs.wi.z)) return;
        const Color next_beta = beta * bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        if (is_black(next_beta) || !is_finite(next_beta)) return;
        RayOrigin next_origin;
        next_origin.e.specular = bs.is_delta();
        next_origin.e.bsdf_pdf = bs.pdf;
        next_origin.e.point = LightSampleContext{hit.p, v.ns};
        next_origin.e.ward_tested = ward_tested;
        next_origin.from = hit.primitive;
        if (!bs.is_delta()) {  // left the receiver by a non-delta lobe: the generator's or a delta chain's light
            if (m_cfg.generator == PathGenerator::ReceiverGathering)
                gather_walk(next, next_beta, n + 1, next_origin, r);
            else
                passed_vertex(next, next_beta, n + 1, next_origin, &r, true);
            return;
        }
        ray = next;
        beta = next_beta;
        origin = next_origin;
        camera = false;
        aov = nullptr;
    }
}

void GeneratorPath::at_receiver(const Receiver& r, const SurfaceHit& hit, const SurfaceVertex& v, SpawnPoints& spawn,
                                const BounceSample& u, int* ward_tested) {
    const Scene& scene = m_t.m_scene;
    const LightSet& lights = scene.lights();
    const ShadingPoint& sp = r.vertex->shading(r.wo);
    const Bsdf& bsdf = sp.bsdf();
    const Vec3 wo_local = v.frame.to_local(r.wo);
    if (!lights.empty()) {  // D(x): next-event estimation, MIS against the BSDF ray (common/direct_light.h)
        const LightSampleContext ctx{hit.p, v.ns};
        *ward_tested = next_event_estimation(
            m_cfg.direct, m_t.m_light_sampler, lights, ctx, u.light_select, u.light,
            [&](uint32_t li, float pmf, Vec2 u_li) {
                const DirectLightSample d = sample_direct_light(
                    scene, m_cfg.direct, hit, v, spawn, ctx, bsdf, wo_local, r.beta, li, pmf, u_li,
                    [&](const Vec3& wi_local) { return bsdf.pdf(wo_local, wi_local); }, m_stats.rays);
                m_L += d.contribution;
                return d.visible;
            });
    }
    if (r.n + 1 > m_cfg.max_bounces) return;  // I(x) needs one more scattering vertex
    const PathGenerator g = m_cfg.generator;
    if (g == PathGenerator::SourceShooting) connect_light_path(r, false);
    if (g == PathGenerator::SurfaceSampling) surface_indirect(*r.vertex, r.wo, r.beta, r.n, &r, false);
    if (m_cfg.combine) {  // the other generators' one-bounce estimates (receiver gathering's: at the BSDF ray's hit)
        if (g != PathGenerator::SourceShooting) connect_light_path(r, true);
        if (g != PathGenerator::SurfaceSampling) surface_indirect(*r.vertex, r.wo, r.beta, r.n, &r, true);
    }
}

void GeneratorPath::gathered_direct(const VertexBsdf& z, const Vec3& w_c, const SurfaceVertex& v, SpawnPoints& spawn,
                                    const Color& beta, const BounceSample& u, const OneBounceRef& one_bounce) {
    const Scene& scene = m_t.m_scene;
    const LightSet& lights = scene.lights();
    if (lights.empty()) return;
    const SurfaceHit& hit = z.hit();
    const Bsdf& bsdf = z.shading(w_c).bsdf();
    const Vec3 wo_local = v.frame.to_local(w_c);
    const LightSampleContext ctx{hit.p, v.ns};
    next_event_estimation(m_t.m_light_only, m_t.m_light_sampler, lights, ctx, u.light_select, u.light,
                          [&](uint32_t li, float pmf, Vec2 u_li) {
                              const DirectLightSample d = sample_direct_light_weighted(
                                  scene, m_t.m_light_only, hit, v, spawn, ctx, bsdf, wo_local, beta, li, pmf, u_li,
                                  [&](const LightSample& ls, const Vec3&, float) {
                                      if (!one_bounce.x) return 1.f;
                                      return m_t.m_weights.weight(
                                          one_bounce.generator, *one_bounce.x, one_bounce.wo_x, z,
                                          one_bounce_light_of_sample(lights, li, ls.wi, ls.dist));
                                  },
                                  m_stats.rays);
                              m_L += d.contribution;
                              return d.visible;
                          });
}

void GeneratorPath::passed_vertex(const Ray& ray, const Color& beta, int n, const RayOrigin& origin, const Receiver* r,
                                  bool chains) {
    const Scene& scene = m_t.m_scene;
    SurfaceHit hit;
    ShadingPoint sp;
    if (!trace_emission(ray, beta, origin, false, &hit, &sp, nullptr, nullptr)) return;
    const bool rg_one_bounce = r && m_cfg.combine && m_cfg.generator != PathGenerator::ReceiverGathering;
    if (n > m_cfg.max_bounces || (!chains && !rg_one_bounce)) return;
    const Vec3 wo = -ray.d;
    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
    const VertexBsdf vb(scene, hit, wo, sp);
    const Bsdf& bsdf = sp.bsdf();
    const Vec3 wo_local = v.frame.to_local(wo);
    SpawnPoints spawn(hit.p, v.ng);
    const BounceSample u = draw(slot(n, 0), k_need_light_select | k_need_light | k_need_lobe);
    const OneBounceRef ob =
        rg_one_bounce ? OneBounceRef{r->vertex, r->wo, &vb, PathGenerator::ReceiverGathering} : OneBounceRef{};
    if (rg_one_bounce && bsdf.has_non_delta()) gathered_direct(vb, wo, v, spawn, beta, u, ob);
    const BsdfSample bs = bsdf.sample(wo_local, u.bsdf, u.lobe);
    if (!bs.valid() || is_black(bs.f)) return;
    const Ray next = continuation_ray(v, spawn, bs, ray.type);
    if (leaks(dot(next.d, v.ng), bs.wi.z)) return;
    const Color next_beta = beta * bs.f * (std::fabs(bs.wi.z) / bs.pdf);
    if (is_black(next_beta) || !is_finite(next_beta)) return;
    RayOrigin next_origin;
    next_origin.e.specular = bs.is_delta();
    next_origin.e.bsdf_pdf = bs.pdf;
    next_origin.e.point = LightSampleContext{hit.p, v.ns};
    next_origin.from = hit.primitive;
    if (bs.is_delta()) {  // a delta chain: its next non-delta vertex receives
        if (chains) receiver_walk(next, next_beta, n + 1, next_origin, false, nullptr, nullptr);
        return;
    }
    if (rg_one_bounce && m_t.m_unsampled_emission) {  // receiver gathering's one bounce to a constant world
        next_origin.gathered = true;
        next_origin.one_bounce = ob;
        SurfaceHit h;
        ShadingPoint s;
        trace_emission(next, next_beta, next_origin, false, &h, &s, nullptr, nullptr);
    }
}

void GeneratorPath::gather_walk(Ray ray, Color beta, int n, RayOrigin origin, const Receiver& r) {
    const Scene& scene = m_t.m_scene;
    const GeneratorSettings& cfg = m_cfg;
    SurfaceHit z1_hit;  // the first gathered point, kept for the weight of the emitter its ray finds
    std::optional<VertexBsdf> z1;
    float eta_scale = 1.f;
    for (bool first = true;; ++n, first = false) {
        SurfaceHit hit;
        ShadingPoint sp;
        if (!trace_emission(ray, beta, origin, false, &hit, &sp, nullptr, nullptr)) return;
        if (n > cfg.max_bounces) return;
        const Vec3 wo = -ray.d;
        std::optional<VertexBsdf> local;
        const VertexBsdf* vb;
        if (first) {
            z1_hit = hit;
            vb = &z1.emplace(scene, z1_hit, wo, sp);
        } else {
            vb = &local.emplace(scene, hit, wo, sp);
        }
        const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
        const Bsdf& bsdf = sp.bsdf();
        const Vec3 wo_local = v.frame.to_local(wo);
        SpawnPoints spawn(hit.p, v.ng);
        const bool roulette_here = cfg.rr_mode != RouletteMode::Off && n + 1 >= cfg.rr_start_bounce;
        const BounceSample u =
            draw(slot(n, 0), k_need_light_select | k_need_light | k_need_lobe | (roulette_here ? k_need_roulette : 0u));
        const bool arrival = roulette_here && cfg.rr_mode == RouletteMode::SqrtThroughput;
        if (arrival) {
            const float q = arrival_survival(beta, eta_scale);
            if (!(q > 0.f) || u.roulette >= q) return;
            beta /= q;
        }
        const OneBounceRef ob =
            first && cfg.combine ? OneBounceRef{r.vertex, r.wo, vb, PathGenerator::ReceiverGathering} : OneBounceRef{};
        if (bsdf.has_non_delta()) gathered_direct(*vb, wo, v, spawn, beta, u, ob);
        const BsdfSample bs = bsdf.sample(wo_local, u.bsdf, u.lobe);
        if (!bs.valid() || is_black(bs.f)) return;
        const Ray next = continuation_ray(v, spawn, bs, ray.type);
        if (leaks(dot(next.d, v.ng), bs.wi.z)) return;
        beta *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        eta_scale *= bs.is_transmission() ? bs.eta * bs.eta : 1.f;
        if (roulette_here && !arrival) {
            const float q =
                continuation_survival(cfg.rr_mode, beta, 1, eta_scale, [&] { return bsdf.albedo(wo_local); });
            if (!(q > 0.f) || u.roulette >= q) return;
            beta /= q;
        }
        if (is_black(beta) || !is_finite(beta)) return;
        origin = RayOrigin{};
        origin.e.specular = bs.is_delta();
        origin.e.bsdf_pdf = bs.pdf;
        origin.e.point = LightSampleContext{hit.p, v.ns};
        origin.gathered = true;
        origin.from = hit.primitive;
        if (first && !bs.is_delta()) origin.one_bounce = ob;
        ray = next;
    }
}

}  // namespace candela
