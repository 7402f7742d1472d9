// The pilot's path tracer (pilot.h): a compact copy of PATH's estimator at its defaults (MIS with the power
// heuristic, solid-angle light sampling, one shadow ray per vertex, the light tree) without the Light Paths
// settings, branching or data passes, which tallies each path's light by class (emitted, direct, indirect,
// caustic, and light blocked only by transmissive surfaces): the pilot estimates where light comes from, not the
// final image. Only pilot.cpp includes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/rng.h"
#include "integrators/auto/pilot.h"
#include "integrators/common/mis.h"
#include "integrators/common/roulette.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/ray_types.h"
#include "integrators/shadow_ray.h"
#include "lights/light.h"
#include "lights/light_sampler.h"

namespace candela::pilot {

constexpr float k_inf = std::numeric_limits<float>::infinity();
constexpr MisHeuristic k_heuristic = MisHeuristic::Power;
constexpr LightPdfMode k_pdf_mode = LightPdfMode::SolidAngle;
constexpr bool k_mis_compensated = true;  // its next-event estimation is always combined with BSDF sampling by MIS
constexpr int k_transmissive_probe_surfaces = 16;  // surfaces a blocked shadow ray's probe may cross
constexpr int k_transparent_passes = 64;           // Transparent surfaces a pilot path may pass through
constexpr int k_caustic_probes = 8;  // BSDF samples probing for caustics at a path's first non-delta vertex
constexpr int k_probe_chain = 16;    // delta bounces a probe follows at most

class Uniform {
public:
    Uniform(uint64_t seed, uint64_t stream) : m_rng(seed, stream) {}
    float next() { return std::min(float(m_rng.next_u32()) * 0x1p-32f, 0x1.fffffep-1f); }
    Vec2 next2() {
        const float a = next();
        return {a, next()};
    }

private:
    Pcg32 m_rng;
};

/// One path's contributions, by class.
struct PathTally {
    Color c[k_path_classes] = {Color(0.f), Color(0.f), Color(0.f), Color(0.f)};
    Color through_transmissive{0.f};
    Color specular_after_diffuse{0.f};
};

/// What the path so far says about the class of light its next vertex receives.
struct PathHistory {
    int non_delta = 0;                // non-delta scatterings so far
    bool delta_since = false;         // a delta scatter since the last non-delta one
    bool diffuse_then_delta = false;  // a delta scatter after a diffuse one (Cycles' caustics filter)
    bool diffuse_seen = false;
};

PathClass emission_class(const PathHistory& h) {
    if (h.non_delta == 0) return PathClass::Emitted;
    if (h.delta_since) return PathClass::Caustic;
    return h.non_delta == 1 ? PathClass::Direct : PathClass::Indirect;
}

bool is_transmissive(const Scene& scene, uint32_t material) {
    return (scene.material_flags(material) & (k_bsdf_transmission | k_bsdf_transparent)) != 0;
}

/// Whether the segment from `origin` toward light sample ls is blocked only by transmissive surfaces: walks the
/// hits along it (at most k_transmissive_probe_surfaces), false at the first opaque one.
bool blocked_only_by_transmissive(const Scene& scene, const SurfaceHit& from, const Vec3& origin, const LightSample& ls,
                                  uint64_t& rays) {
    Vec3 o = origin;
    PrimitiveRef skip = from.primitive;
    const Vec3 light_point = from.p + ls.wi * ls.dist;
    for (int i = 0; i < k_transmissive_probe_surfaces; ++i) {
        const float tmax = std::isfinite(ls.dist) ? length(light_point - o) * (1.f - k_shadow_epsilon) : k_inf;
        Ray r{o, ls.wi, 0.f, tmax, k_ray_shadow};
        SurfaceHit h;
        ++rays;
        if (!scene.intersect(r, &h, skip)) return true;
        if (!is_transmissive(scene, h.material)) return false;
        o = h.p;
        skip = h.primitive;
    }
    return false;
}

class PilotTracer {
public:
    PilotTracer(const Scene& scene, int max_bounces)
        : m_scene(scene),
          m_lights(scene.lights()),
          m_sampler(scene.light_sampler(parse_light_selection("TREE"))),
          m_max_bounces(max_bounces),
          m_transmissive(scene_has_transmission(scene)),
          m_has_delta(scene_has_delta(scene)) {}

    void trace(Ray ray, Uniform& u, PathTally& t, uint64_t& rays) const {
        Color beta(1.f);
        PathHistory h;
        bool last_delta = true;  // the camera ray: emission it finds counts with weight 1
        float last_pdf = 0.f;
        LightSampleContext last_ctx{};
        PrimitiveRef from;
        int passes = 0;  // Transparent pass-throughs
        for (int bounce = 0;; ++bounce) {
            SurfaceHit hit;
            ++rays;
            const bool found = m_scene.intersect(ray, &hit, from);
            // Area lights before the surface (they are not occluders).
            uint32_t li;
            float tl;
            if (!m_lights.area_lights().empty() &&
                m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit.t : ray.tmax, &li, &tl,
                                             ray.type == k_ray_camera))
                add_emission(t, h, beta, std::get<AreaLight>(m_lights[li]).radiance, last_delta, last_pdf, last_ctx, li,
                             ray.d, tl);
            if (!found) {
                if (const WorldLight* world = m_lights.world())
                    add_emission(t, h, beta, world->Le(ray.d), last_delta, last_pdf, last_ctx,
                                 uint32_t(m_lights.world_light()), ray.d, k_inf);
                else if (!is_black(m_lights.background()))
                    add_found(t, h, beta * m_lights.background());
                return;
            }
            const ShadingPoint sp = m_scene.shade(hit, -ray.d, nullptr);
            if (!is_black(sp.emission)) {
                if (hit.light >= 0)
                    add_emission(t, h, beta, sp.emission, last_delta, last_pdf, last_ctx, uint32_t(hit.light), ray.d,
                                 hit.t);
                else
                    add_found(t, h, beta * sp.emission);
            }
            if (bounce > m_max_bounces) return;  // max_bounces scatterings: the last vertex only emits
            const Bsdf& bsdf = sp.bsdf();
            const Vec3 wo = -ray.d;
            const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
            const Vec3 wo_local = v.frame.to_local(wo);
            SpawnPoints spawn(hit.p, v.ng);
            const LightSampleContext ctx{hit.p, v.ns};
            // Next-event estimation: the light arrives directly at this (non-delta) vertex.
            if (!m_lights.empty() && bsdf.has_non_delta()) {
                PathHistory here = h;
                ++here.non_delta;
                here.delta_since = false;
                next_event(t, here, hit, v, spawn, ctx, bsdf, wo_local, beta, u, rays);
            }
            if (h.non_delta == 0 && bsdf.has_non_delta() && m_has_delta)
                probe_caustics(t, beta, v, spawn, bsdf, wo_local, bounce, from_of(hit), u, rays);
            const float uc = u.next();
            const BsdfSample bs = bsdf.sample(wo_local, u.next2(), uc);
            if (!bs.valid() || is_black(bs.f)) return;
            const Vec3 wi = v.frame.to_world(bs.wi);
            const float cos_g = dot(wi, v.ng);
            if (leaks(cos_g, bs.wi.z)) return;
            beta *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
            if (bs.is_transparent()) {
                // A pass-through is not a scattering: the class and the MIS origin stay those of the vertex before
                // (the MIS distance is taken from the transparent surface, not summed as PATH does: a small bias in
                // the pilot's weights behind Transparent surfaces only).
                if (++passes > k_transparent_passes) return;
                --bounce;
            } else if (bs.is_delta()) {
                h.delta_since = true;
                h.diffuse_then_delta |= h.diffuse_seen;
                last_delta = true;
            } else {
                ++h.non_delta;
                h.delta_since = false;
                h.diffuse_seen |= (bs.flags & k_bsdf_diffuse) != 0;
                last_delta = false;
                last_pdf = bs.pdf;
                last_ctx = ctx;
            }
            if (bounce >= 2) {  // Russian roulette from the third bounce on: PATH's default THROUGHPUT rule
                const float survive =
                    continuation_survival(RouletteMode::Throughput, beta, 1, 1.f, [] { return Color(0.f); });
                if (!(survive > 0.f) || u.next() >= survive) return;
                beta /= survive;
            }
            if (!is_finite(beta) || is_black(beta)) return;
            ray = Ray{spawn.origin(cos_g > 0.f), wi, 0.f, k_inf, continuation_ray_type(bs, ray.type)};
            from = hit.primitive;
        }
    }

private:
    static PrimitiveRef from_of(const SurfaceHit& hit) { return hit.primitive; }

    /// The caustic light reaching this vertex — the first where the path can scatter non-delta — estimated by
    /// k_caustic_probes BSDF samples, each followed through delta bounces only to the emitter it finds (weight 1: no
    /// other strategy samples a path through a delta vertex), within the same bounce limit. A caustic is rare for a
    /// path tracer (its rays must hit the light through the glass): splitting here, where the image sees it,
    /// measures it with k_caustic_probes times the rays of one path.
    void probe_caustics(PathTally& t, const Color& beta, const SurfaceVertex& v, SpawnPoints& spawn, const Bsdf& bsdf,
                        const Vec3& wo_local, int bounce, PrimitiveRef from_prim, Uniform& u, uint64_t& rays) const {
        for (int j = 0; j < k_caustic_probes; ++j) {
            const float uc = u.next();
            const BsdfSample bs = bsdf.sample(wo_local, u.next2(), uc);
            if (!bs.valid() || bs.is_delta() || is_black(bs.f)) continue;
            const Vec3 wi = v.frame.to_world(bs.wi);
            const float cos_g = dot(wi, v.ng);
            if (leaks(cos_g, bs.wi.z)) continue;
            Color b = beta * bs.f * (std::fabs(bs.wi.z) / (bs.pdf * float(k_caustic_probes)));
            const bool diffuse = (bs.flags & k_bsdf_diffuse) != 0;
            Ray ray{spawn.origin(cos_g > 0.f), wi, 0.f, k_inf, continuation_ray_type(bs, k_ray_camera)};
            PrimitiveRef skip = from_prim;
            bool after_delta = false;  // emission counts only after at least one delta bounce
            for (int vertex = bounce + 1; vertex <= bounce + 1 + k_probe_chain; ++vertex) {
                SurfaceHit hit;
                ++rays;
                const bool found = m_scene.intersect(ray, &hit, skip);
                uint32_t li;
                float tl;
                if (after_delta && !m_lights.area_lights().empty() &&
                    m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit.t : ray.tmax, &li, &tl))
                    add_caustic(t, b * std::get<AreaLight>(m_lights[li]).radiance, diffuse);
                if (!found) {
                    if (!after_delta) break;
                    if (const WorldLight* world = m_lights.world())
                        add_caustic(t, b * world->Le(ray.d), diffuse);
                    else
                        add_caustic(t, b * m_lights.background(), diffuse);
                    break;
                }
                // Delta-only surfaces cost a shading; anything that can scatter non-delta ends the chain (after
                // its emission, if it follows a delta bounce).
                const ShadingPoint sp = m_scene.shade(hit, -ray.d, nullptr);
                if (after_delta && !is_black(sp.emission)) add_caustic(t, b * sp.emission, diffuse);
                if (vertex > m_max_bounces) break;
                const Bsdf& next = sp.bsdf();
                const SurfaceVertex w = SurfaceVertex::at(hit, sp.ns, -ray.d);
                const Vec3 wo = w.frame.to_local(-ray.d);
                const float uc2 = u.next();
                const BsdfSample d = next.sample(wo, u.next2(), uc2);
                if (!d.valid() || !d.is_delta() || is_black(d.f)) break;
                const Vec3 wd = w.frame.to_world(d.wi);
                const float cd = dot(wd, w.ng);
                if (leaks(cd, d.wi.z)) break;
                b *= d.f * (std::fabs(d.wi.z) / d.pdf);
                if (!is_finite(b) || is_black(b)) break;
                SpawnPoints sp2(hit.p, w.ng);
                ray = Ray{sp2.origin(cd > 0.f), wd, 0.f, k_inf, continuation_ray_type(d, ray.type)};
                skip = hit.primitive;
                after_delta = true;
            }
        }
    }

    static void add_caustic(PathTally& t, const Color& L, bool diffuse) {
        if (!is_finite(L) || is_black(L)) return;
        t.c[int(PathClass::Caustic)] += L;
        if (diffuse) t.specular_after_diffuse += L;
    }

    static bool scene_has_delta(const Scene& scene) {
        for (uint32_t m = 0; m < scene.materials().size(); ++m)
            if (scene.material_flags(m) & k_bsdf_specular) return true;
        return false;
    }

    static bool scene_has_transmission(const Scene& scene) {
        for (uint32_t m = 0; m < scene.materials().size(); ++m)
            if (is_transmissive(scene, m)) return true;
        return false;
    }

    // Emission the path's own rays find: the caustic of the first non-delta scattering (one non-delta vertex, then
    // delta bounces) is left to that vertex's probes (probe_caustics), which estimate the same expectation.
    static void add_found(PathTally& t, const PathHistory& h, const Color& L) {
        const PathClass c = emission_class(h);
        if (c == PathClass::Caustic && h.non_delta == 1) return;
        add(t, h, c, L);
    }

    static void add(PathTally& t, const PathHistory& h, PathClass c, const Color& L) {
        if (!is_finite(L)) return;
        t.c[int(c)] += L;
        if (h.diffuse_then_delta) t.specular_after_diffuse += L;
    }

    void add_emission(PathTally& t, const PathHistory& h, const Color& beta, const Color& Le, bool last_delta,
                      float last_pdf, const LightSampleContext& last_ctx, uint32_t light, const Vec3& d,
                      float dist) const {
        float w = 1.f;
        if (!last_delta) {
            const float p_light = m_sampler.nee_pmf(last_ctx, light) *
                                  light_pdf_li(m_lights[light], last_ctx, d, dist, k_pdf_mode, k_mis_compensated);
            w = mis_weight(k_heuristic, last_pdf, p_light);
        }
        add_found(t, h, beta * Le * w);
    }

    void next_event(PathTally& t, const PathHistory& h, const SurfaceHit& hit, const SurfaceVertex& v,
                    SpawnPoints& spawn, const LightSampleContext& ctx, const Bsdf& bsdf, const Vec3& wo_local,
                    const Color& beta, Uniform& u, uint64_t& rays) const {
        float pmf = 0.f;
        const uint32_t li = m_sampler.select(ctx, u.next(), &pmf);
        const Vec2 ul = u.next2();
        if (!(pmf > 0.f)) return;
        const LightSample ls = light_sample_li(m_lights[li], ctx, ul, k_pdf_mode, k_mis_compensated);
        if (!ls.valid()) return;
        const Vec3 wi_local = v.frame.to_local(ls.wi);
        const float cos_g = dot(ls.wi, v.ng);
        if (leaks(cos_g, wi_local.z)) return;
        const Color f = bsdf.f(wo_local, wi_local) * std::fabs(wi_local.z);
        if (is_black(f)) return;
        const float density = pmf * ls.pdf;
        const float w = ls.is_delta ? 1.f : mis_weight(k_heuristic, density, bsdf.pdf(wo_local, wi_local));
        const Color c = beta * f * ls.Li * (w / density);
        const Vec3 origin = spawn.origin(cos_g > 0.f);
        ++rays;
        if (!shadow_ray_blocked(m_scene, hit, origin, ls)) {
            add(t, h, h.non_delta == 1 ? PathClass::Direct : PathClass::Indirect, c);
        } else if (m_transmissive && blocked_only_by_transmissive(m_scene, hit, origin, ls, rays) && is_finite(c)) {
            t.through_transmissive += c;
        }
    }

    const Scene& m_scene;
    const LightSet& m_lights;
    const LightSampler& m_sampler;
    int m_max_bounces;
    bool m_transmissive;
    bool m_has_delta;  // some material has a delta lobe: caustics possible, probes worth shooting
};

}  // namespace candela::pilot
