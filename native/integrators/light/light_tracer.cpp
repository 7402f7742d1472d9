#include "integrators/light/light_tracer.h"

#include <cmath>
#include <limits>

#include "integrators/camera_hit.h"
#include "integrators/common/light_walk.h"
#include "integrators/common/roulette.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/ray_types.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

/// Adds light path vertex x's connection to the camera: v = β·f(w_cam, w_l)·|w_cam·ng|·c(w_l)·K at the raster
/// position the connection lands on.
void connect_to_camera(const Scene& scene, const VertexBsdf& vb, const Vec3& w_l, const Color& beta, Vec2 u_lens,
                       float margin, uint32_t replicate, SplatBuffer& splats, PathStats& stats) {
    const SurfaceHit& hit = vb.hit();
    if (!scene.visible_to(hit, k_ray_camera)) return;
    CameraConnection c;
    if (!scene.camera().connect(hit.p, u_lens, &c, margin)) return;
    const Color f = vb.f(c.wi, w_l);
    if (is_black(f)) return;
    const float cos_g = dot(c.wi, hit.ng);
    if (cos_g == 0.f) return;
    const Vec3 origin = offset_ray_origin(hit.p, cos_g > 0.f ? hit.ng : -hit.ng);
    ++stats.rays;
    // The segment to the lens is a camera ray: objects hidden from the camera do not block it.
    if (scene.occluded(origin, c.lens_point - origin, 1.f - 1e-4f, k_ray_camera, hit.primitive)) return;
    float visible = 1.f;
    if (scene.has_holdouts()) visible -= scene.holdout(hit, c.wi);  // the camera sees the surface's holdout share
    const Color v = beta * f * (std::fabs(cos_g) * vb.adjoint_factor(c.wi, w_l) * c.importance * visible);
    if (!is_finite(v) || min_component(v) < 0.f) {
        ++stats.nan_samples;
        return;
    }
    if (!is_black(v)) splats.add(c.raster, v, replicate);
}

}  // namespace

void LightTracer::trace(Sampler& sampler, int dim_bounce, uint32_t replicate, SplatBuffer& splats,
                        PathStats& stats) const {
    std::visit([&](auto& s) { trace_path(s, dim_bounce, replicate, splats, stats); }, sampler);
}

template <class S>
void LightTracer::trace_path(S& sampler, int dim_bounce, uint32_t replicate, SplatBuffer& splats,
                             PathStats& stats) const {
    const LightSettings& cfg = m_settings;
    // The path has max_bounces + 1 scattering vertices at most.
    const LightWalkRules rules{cfg.max_bounces + 1, cfg.rr_mode, cfg.rr_start_bounce};
    // Up to half the filter's support beyond the frame, as the camera rays of the border pixels reach.
    const float margin = 0.5f * cfg.pixel.filter.support();
    walk_light_path(
        m_scene, m_emitters, rules, sampler, dim_bounce, stats, [](const EmissionSample&, uint32_t) {},
        [&](const VertexBsdf& vb, const Vec3& w_l, const Color& beta, int, const BounceSample& u) {
            connect_to_camera(m_scene, vb, w_l, beta, u.light, margin, replicate, splats, stats);
        });
}

Color SpecularCameraTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha,
                               AovSample* aov) const {
    *alpha = 1.f;
    Color L(0.f), beta(1.f);
    Ray ray = camera_ray;
    PrimitiveRef from;
    const LightSet& lights = m_scene.lights();
    for (int bounce = 0;; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        const bool found = m_scene.intersect(ray, &hit, from);
        // Emission found by the camera ray or after delta scattering only: weight 1 (nothing else estimates it).
        if (!lights.area_lights().empty()) {
            uint32_t li;
            float tl;
            if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit.t : ray.tmax, &li, &tl, bounce == 0))
                L += beta * std::get<AreaLight>(lights[li]).radiance;
        }
        if (!found) {
            if (bounce == 0 && m_settings.pixel.film_transparent)
                *alpha = 0.f;
            else if (const WorldLight* world = lights.world())
                L += beta * world->Le(ray.d);
            else
                L += beta * lights.background();
            return L;
        }
        if (bounce == 0 && !camera_hit(m_scene, ray, hit, aov, alpha)) return L;
        const Vec3 wo = -ray.d;
        const ShadingPoint sp = m_scene.shade(hit, wo);
        L += beta * sp.emission;
        if (bounce > m_settings.max_bounces) return L;
        const Bsdf& bsdf = sp.bsdf();
        if (!(bsdf.flags() & k_bsdf_specular)) return L;  // no delta lobe: the rest is the light tracer's
        const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
        const Vec2 u_dir = get_2d(sampler, Dim::Bsdf, bounce);
        const float u_lobe = get_1d(sampler, Dim::BsdfLobe, bounce);
        const BsdfSample bs = bsdf.sample(v.frame.to_local(wo), u_dir, u_lobe);
        if (!bs.valid() || !bs.is_delta()) return L;  // a non-delta lobe was chosen: the light tracer's part
        const Vec3 wi = v.frame.to_world(bs.wi);
        const float cos_g = dot(wi, v.ng);
        if (leaks(cos_g, bs.wi.z)) return L;
        beta *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        if (is_black(beta) || !is_finite(beta)) return L;
        ray = Ray{offset_ray_origin(hit.p, cos_g > 0.f ? v.ng : -v.ng), wi, 0.f, k_inf,
                  continuation_ray_type(bs, ray.type)};
        from = hit.primitive;
    }
}

}  // namespace candela
