// The records' side of the irradiance cache integrator (ic_tracer.h): a camera path vertex's gather, the R rules
// applied to it (pixel footprints), and the pre-pass's walk from a pixel's centre to the surface that needs one.
#include <cmath>
#include <limits>

#include "core/math.h"
#include "core/rng.h"
#include "integrators/irradiance_cache/ic_lobe_split.h"
#include "integrators/irradiance_cache/ic_tracer.h"
#include "integrators/ray_types.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

}  // namespace

PixelFootprint PixelFootprint::of(const Camera& camera) {
    const Vec2 c{0.5f * float(camera.full_width()), 0.5f * float(camera.full_height())};
    const Ray r0 = camera.generate_ray(c), r1 = camera.generate_ray({c.x + 1.f, c.y});
    PixelFootprint f;
    f.d_origin = r1.o - r0.o;
    f.d_dir = r1.d - r0.d;
    return f;
}

float IcTracer::surface_footprint(float distance, const Vec3& d, const Vec3& ng) const {
    // The pixel's extent across the surface along its steepest direction: the footprint over |cos| of the angle
    // the ray meets the surface at (at most 20 footprints, at grazing incidence).
    return m_footprint.at(distance) / std::fmax(std::fabs(dot(d, ng)), 0.05f);
}

IcRecord IcTracer::make_record(const SurfaceHit& hit, const SurfaceVertex& v, float footprint, uint64_t key,
                               PathStats& stats) const {
    HemisphereSamples hs;
    hs.strata = m_strata;
    const size_t n = size_t(m_strata.count());
    hs.dir.resize(n);
    hs.L.assign(n, Color(0.f));
    hs.r.assign(n, k_inf);
    PathState start;
    start.origin.specular = false;
    start.origin.point = LightSampleContext{hit.p, v.ns};
    start.rules = &m_rules_gathered;
    start.from = hit.primitive;
    SpawnPoints spawn(hit.p, v.ng);
    for (int j = 0; j < m_strata.M; ++j)
        for (int k = 0; k < m_strata.N; ++k) {
            poll_gather();
            const size_t i = size_t(j * m_strata.N + k);
            Pcg32 jitter(hash_combine(key, i), 0x6a6974746572ULL /* "jitter" */);
            const float u1 = jitter.next_float(), u2 = jitter.next_float();
            const Vec3 wl = gather_direction(m_strata, j, k, u1, u2);
            hs.dir[i] = wl;
            const Vec3 wi = v.frame.to_world(wl);
            const float cos_g = dot(wi, v.ng);
            if (leaks(cos_g, wl.z)) continue;  // through the surface: no light, no distance (as PATH)
            start.origin.bsdf_pdf = wl.z * k_inv_pi;
            const Ray ray{spawn.origin(cos_g > 0.f), wi, 0.f, k_inf, k_ray_diffuse};
            hs.L[i] = trace_gather(ray, start, hash_combine(key, i + (uint64_t(1) << 40)), stats, &hs.r[i]);
        }
    RecordRules rules;
    rules.a = m_settings.error;
    rules.gradients = m_settings.gradients;
    rules.footprint = footprint;
    rules.min_spacing = m_settings.min_spacing;
    rules.max_spacing = m_settings.max_spacing;
    rules.max_R = 2.f * m_scene.bounds().radius;
    return record_from_gather(estimate_gather(hs), hit.p, v.frame, rules);
}

// ---------------------------------------------------------------------------------------------------------------
// The pre-pass.

bool IcTracer::prepass_record(int fx, int fy, uint64_t key, PathStats& stats, IcRecord* record) const {
    Ray ray = m_scene.camera().generate_ray({float(fx) + 0.5f, float(fy) + 0.5f});
    PrimitiveRef from;
    float distance = 0.f;
    for (int bounce = 0; bounce <= m_settings.max_bounces; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        if (!m_scene.intersect(ray, &hit, from)) return false;
        distance += hit.t;
        const ShadingPoint sp = m_scene.shade(hit, -ray.d);
        const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, -ray.d);
        const Vec3 wo_local = v.frame.to_local(-ray.d);
        const Bsdf& bsdf = sp.bsdf();
        const LobeSplit split(bsdf);
        if (!is_black(split.rho_d) && wo_local.z > 0.f) {
            if (m_cache.covered(hit.p, v.frame.n)) return false;
            *record = make_record(hit, v, surface_footprint(distance, ray.d, hit.ng), key, stats);
            record->pixel_x = fx;
            record->pixel_y = fy;
            return true;
        }
        // Through mirrors and clear glass (the likelier side of a Fresnel choice); glossy surfaces get their
        // records while rendering.
        if (!bsdf.is_delta()) return false;
        const BsdfSample bs = bsdf.sample(wo_local, {0.5f, 0.5f}, 0.5f);
        if (!bs.valid()) return false;
        const Vec3 wi = v.frame.to_world(bs.wi);
        const float cos_g = dot(wi, v.ng);
        if (leaks(cos_g, bs.wi.z)) return false;
        ray = Ray{offset_ray_origin(hit.p, cos_g > 0.f ? v.ng : -v.ng), wi, 0.f, k_inf,
                  continuation_ray_type(bs, ray.type)};
        from = hit.primitive;
    }
    return false;
}

}  // namespace candela
