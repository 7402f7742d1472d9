#include "integrators/path/path_tracer.h"

#include <cmath>
#include <limits>

#include "core/frame.h"
#include "core/math.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

/// Probability that next-event estimation would have produced direction d toward the given emitter.
template <typename LightT>
float nee_pdf(const LightSet& lights, uint32_t index, const LightT& light, const Vec3& d, float t) {
    return lights.selection_pmf(index) * light.pdf_li(d, t);
}

}  // namespace

Color PathTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha) const {
    const LightSet& lights = m_scene.lights();
    const bool has_nee = !lights.empty();
    const auto& materials = m_scene.materials();
    constexpr float k_inf = std::numeric_limits<float>::infinity();

    Color L(0.f), beta(1.f);
    Ray ray = camera_ray;
    float prev_bsdf_pdf = 0.f;  // solid-angle pdf of the BSDF sample that produced `ray`
    bool prev_delta = true;     // camera rays and delta scatters see emitters with weight 1
    float eta_scale = 1.f;      // Π η² over refractions so far (Russian roulette only)
    *alpha = 1.f;

    for (int bounce = 0;; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        const bool found = m_scene.intersect(ray, &hit);
        const float t_surface = found ? hit.t : ray.tmax;

        // MIS weight for emission found by the BSDF-sampled ray (1 for camera rays and delta scatters).
        auto emission_weight = [&](float light_pdf) {
            return prev_delta ? 1.f : power_heuristic(prev_bsdf_pdf, light_pdf);
        };

        // Area lights are not occluders: any emitting side before the surface adds its radiance.
        if (!lights.area_lights().empty()) {
            uint32_t li;
            float tl;
            if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, t_surface, &li, &tl)) {
                const auto& area = std::get<AreaLight>(lights[li]);
                L += beta * area.radiance * emission_weight(nee_pdf(lights, li, area, ray.d, tl));
            }
        }

        if (!found) {
            if (const WorldLight* world = lights.world()) {
                if (bounce == 0 && m_settings.pixel.film_transparent) {
                    *alpha = 0.f;
                } else {
                    const float pdf = lights.selection_pmf(uint32_t(lights.world_light())) * world->pdf_li(ray.d);
                    L += beta * world->Le(ray.d) * emission_weight(pdf);
                }
            } else if (bounce == 0 && m_settings.pixel.film_transparent) {
                *alpha = 0.f;
            }
            break;
        }

        const Material& material = materials[hit.material];
        if (material.is_emissive()) {
            float light_pdf = 0.f;
            if (hit.light >= 0) {
                const auto& tri = std::get<TriangleLight>(lights[uint32_t(hit.light)]);
                light_pdf = nee_pdf(lights, uint32_t(hit.light), tri, ray.d, hit.t);
            }
            L += beta * material.emission * emission_weight(light_pdf);
        }
        if (bounce > m_settings.max_bounces) break;

        // Local shading frame on the side the path arrives from (surfaces are two-sided).
        const Vec3 wo = -ray.d;
        Vec3 ng = hit.ng, ns = hit.ns;
        const bool backfacing = dot(wo, ng) < 0.f;  // arriving against the winding normal (glass: from inside)
        if (backfacing) {
            ng = -ng;
            ns = -ns;
        }
        const Frame frame(dot(wo, ns) > 0.f ? ns : ng);  // a shading normal facing away: fall back
        const Vec3 wo_local = frame.to_local(wo);
        const Bsdf& bsdf = material.bsdf(backfacing);

        // Named sample dimensions: each is the same sequence dimension for every sample of every pixel.
        const float u_select = get_1d(sampler, Dim::LightSelect, bounce);
        const Vec2 u_light = get_2d(sampler, Dim::Light, bounce);
        const Vec2 u_bsdf = get_2d(sampler, Dim::Bsdf, bounce);
        const float u_rr = get_1d(sampler, Dim::Roulette, bounce);
        const float u_lobe = get_1d(sampler, Dim::BsdfLobe, bounce);

        // Next-event estimation.
        if (has_nee && !bsdf.is_delta()) {  // a purely specular BSDF gets its light from BSDF sampling
            float pmf;
            const uint32_t li = lights.select(u_select, &pmf);
            if (pmf > 0.f) {
                const LightSample ls = light_sample_li(lights[li], {hit.p, ns}, u_light);
                const Vec3 wi_local = frame.to_local(ls.wi);
                // Both hemispheres (transmission); the geometric and shading sides must agree (no leaks).
                const float cos_g = dot(ls.wi, ng);
                if (ls.valid() && cos_g != 0.f && (cos_g > 0.f) == (wi_local.z > 0.f)) {
                    const Color f = bsdf_f(bsdf, wo_local, wi_local) * std::fabs(wi_local.z);
                    if (!is_black(f)) {
                        const Vec3 origin = offset_ray_origin(hit.p, cos_g > 0.f ? ng : -ng);
                        const float tmax = std::isfinite(ls.dist) ? ls.dist * (1.f - 1e-4f) : k_inf;
                        ++stats.rays;
                        if (!m_scene.occluded(origin, ls.wi, tmax)) {
                            const float light_pdf = pmf * ls.pdf;
                            const float w = ls.is_delta ? 1.f : power_heuristic(light_pdf, bsdf_pdf(bsdf, wo_local, wi_local));
                            L += beta * f * ls.Li * (w / light_pdf);
                        }
                    }
                }
            }
        }

        // Continue the path by sampling the BSDF.
        const BsdfSample bs = bsdf_sample(bsdf, wo_local, u_bsdf, u_lobe, TransportMode::Radiance);
        if (!bs.valid()) break;
        const Vec3 wi = frame.to_world(bs.wi);
        // The sampled side (reflection: +ng, transmission: −ng) must agree with the geometry: a leak else.
        const float cos_g = dot(wi, ng);
        if (bs.is_transmission() ? cos_g >= 0.f : cos_g <= 0.f) break;
        beta *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        prev_bsdf_pdf = bs.pdf;
        prev_delta = bs.is_delta();
        // Radiance mode scales β by 1/η² at each refraction; undo it for the roulette only (robustness §5).
        if (bs.is_transmission()) eta_scale *= bs.eta * bs.eta;

        if (bounce + 1 >= m_settings.rr_start_bounce) {
            const float survive = std::fmin(1.f, max_component(beta) * eta_scale);
            if (!(survive > 0.f) || u_rr >= survive) break;
            beta /= survive;
        }
        if (is_black(beta)) break;
        ray.o = offset_ray_origin(hit.p, cos_g > 0.f ? ng : -ng);
        ray.d = wi;
        ray.tmin = 0.f;
        ray.tmax = k_inf;
    }
    return L;
}

}  // namespace candela
