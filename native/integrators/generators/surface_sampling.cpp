// Surface sampling (generator_tracer.h): a point z uniform over all surfaces by area (scene/surface_sampler.h),
// joined to the vertex before it by a visibility check, and the light z reflects toward it by a point on a light
// (light-only next-event estimation: the second visibility check):
//     I(x) ≈ β_x · f_x(wo, ω) · |ω·n_x| · |ω·ng_z| / (d² · p_A(z)) · V(x, z) · L_r(z → x),
// ω the unit direction x → z. For longer paths L_r(z → x) adds a further surface point the same way (Russian
// roulette on the throughput); the light reaching z through delta chains (z's BSDF ray hitting a delta-scattering
// vertex), and from a constant world (which next-event estimation does not sample), is found by one BSDF ray from z
// — traced only where the scene has such materials or such a world.
#include <cmath>

#include "integrators/common/connection.h"
#include "integrators/common/roulette.h"
#include "integrators/generators/generator_path.h"

namespace candela {

void GeneratorPath::surface_indirect(const VertexBsdf& from, const Vec3& wo, const Color& beta, int n,
                                     const Receiver* r, bool one_bounce_only) {
    const SurfaceSampler* surfaces = m_t.m_surfaces;
    if (!surfaces || n + 1 > m_cfg.max_bounces) return;
    const BounceSample u = draw(slot(n + 1, 1), k_need_light_select | k_need_light);
    const SurfaceSample s = surfaces->sample(u.light_select, u.light);
    if (!(s.pdf_area > 0.f)) return;
    const SurfaceHit& x = from.hit();
    const Vec3 xz = s.hit.p - x.p;
    const float d2 = length_squared(xz);
    if (!(d2 > 0.f)) return;
    const Vec3 w = xz / std::sqrt(d2);
    const Color f_x = from.f(wo, w);
    if (is_black(f_x)) return;
    const float g = from.camera_cosine(wo, w) * std::fabs(dot(w, s.hit.ng)) / (d2 * s.pdf_area);
    if (!(g > 0.f)) return;
    const Vec3 w_c = -w;
    const ShadingPoint sp = m_t.m_scene.shade(s.hit, w_c);
    if (!sp.bsdf().has_non_delta()) return;  // z's delta lobes are S(x)'s (a ray from x finds them)
    ++m_stats.rays;
    if (!surfaces_connect(m_t.m_scene, x, s.hit)) return;
    const Color beta_z = beta * f_x * g;
    if (is_black(beta_z) || !is_finite(beta_z)) return;
    const VertexBsdf z(m_t.m_scene, s.hit, w_c, sp);
    gathered_point(z, w_c, beta_z, n + 1, r, one_bounce_only);
}

void GeneratorPath::gathered_point(const VertexBsdf& z, const Vec3& w_c, const Color& beta, int n, const Receiver* r,
                                   bool one_bounce_only) {
    const GeneratorSettings& cfg = m_cfg;
    const SurfaceHit& hit = z.hit();
    const ShadingPoint& sp = z.shading(w_c);
    const Bsdf& bsdf = sp.bsdf();
    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, w_c);
    SpawnPoints spawn(hit.p, v.ng);
    const bool own = cfg.generator == PathGenerator::SurfaceSampling && !one_bounce_only;
    const bool roulette_here = own && cfg.rr_mode != RouletteMode::Off && n + 1 >= cfg.rr_start_bounce;
    const BounceSample u =
        draw(slot(n, 2), k_need_light_select | k_need_light | k_need_lobe | (roulette_here ? k_need_roulette : 0u));
    const OneBounceRef ob =
        r && cfg.combine ? OneBounceRef{r->vertex, r->wo, &z, PathGenerator::SurfaceSampling} : OneBounceRef{};
    gathered_direct(z, w_c, v, spawn, beta, u, ob);

    // Light arriving at z along its BSDF ray: a constant world's, and (longer paths) what delta chains bring.
    const bool chains = own && m_t.m_any_delta;
    if (chains || m_t.m_unsampled_emission) {
        const Vec3 wo_local = v.frame.to_local(w_c);
        const BsdfSample bs = bsdf.sample(wo_local, u.bsdf, u.lobe);
        if (bs.valid() && !is_black(bs.f) && !bs.is_delta()) {
            const Ray next = continuation_ray(v, spawn, bs, k_ray_diffuse);
            const Color next_beta = beta * bs.f * (std::fabs(bs.wi.z) / bs.pdf);
            if (!leaks(dot(next.d, v.ng), bs.wi.z) && is_finite(next_beta)) {
                RayOrigin origin;
                origin.e.specular = false;
                origin.e.bsdf_pdf = bs.pdf;
                origin.e.point = LightSampleContext{hit.p, v.ns};
                origin.gathered = true;
                origin.one_bounce = ob;
                origin.from = hit.primitive;
                passed_vertex(next, next_beta, n + 1, origin, nullptr, chains);
            }
        }
    }
    if (!own || n + 1 > cfg.max_bounces) return;
    Color b = beta;
    if (roulette_here) {
        const float q = cfg.rr_mode == RouletteMode::SqrtThroughput ? arrival_survival(b, 1.f)
                        : cfg.rr_mode == RouletteMode::Albedo
                            ? min_num(1.f, max_component(bsdf.albedo(v.frame.to_local(w_c))))
                            : min_num(1.f, max_component(b));
        if (!(q > 0.f) || u.roulette >= q) return;
        b /= q;
    }
    surface_indirect(z, w_c, b, n, nullptr, false);
}

}  // namespace candela
