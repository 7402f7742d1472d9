#include "integrators/generators/one_bounce.h"

#include <cmath>
#include <variant>

#include "core/math.h"
#include "lights/light_emission.h"

namespace candela {

OneBounceLight one_bounce_light_of_sample(const LightSet& lights, uint32_t li, const Vec3& wi, float dist) {
    OneBounceLight y;
    y.light = int(li);
    y.emitter = int(li);  // EmitterSet index i < lights.size() is LightSet light i
    y.w = wi;
    y.dist = dist;
    const Light& l = lights[li];
    if (const auto* area = std::get_if<AreaLight>(&l))
        y.n = area->normal;
    else if (const auto* tri = std::get_if<TriangleLight>(&l))
        y.n = tri->normal;
    return y;
}

float OneBounceWeights::light_density(const VertexBsdf& z, const Vec3& w_c, const OneBounceLight& y) const {
    if (y.light < 0) return z.pdf_camera(w_c, y.w);  // found by z's BSDF sampling only
    const Light& l = m_scene.lights()[size_t(y.light)];
    const ShadingPoint& sp = z.shading(w_c);
    const SurfaceVertex v = SurfaceVertex::at(z.hit(), sp.ns, w_c);
    const LightSampleContext ctx{z.hit().p, v.ns};
    const float k_pmf = float(m_settings.direct.light_samples) * m_light_sampler.nee_pmf(ctx, uint32_t(y.light));
    if (!light_hittable(l)) return k_pmf;
    return k_pmf * light_pdf_li(l, ctx, y.w, y.dist, m_settings.direct.light_pdf);
}

float OneBounceWeights::source_density(const VertexBsdf& z, const OneBounceLight& y) const {
    if (y.emitter < 0) return 0.f;
    const Light& l = m_emitters[size_t(y.emitter)];
    const float P = m_emitters.pmf(uint32_t(y.emitter));
    const Vec3& zp = z.hit().p;
    const float cos_z = std::fabs(dot(y.w, z.hit().ng));
    const float R = m_emitters.bounds().radius;
    if (const auto* point = std::get_if<PointLight>(&l)) {
        const Vec3 cz = zp - point->position;
        const float d2 = length_squared(cz);
        if (!(d2 > 0.f)) return 0.f;
        const Vec3 d = cz / std::sqrt(d2);
        return P * light_center_direction_pdf(l, d) * std::fabs(dot(d, z.hit().ng)) / d2;
    }
    if (std::holds_alternative<SunLight>(l)) return P * cos_z / (k_pi * R * R);
    float pos = 0.f, dir = 0.f;
    if (!std::isfinite(y.dist)) {  // the world: a direction, then a point on the disk across it
        light_pdf_le(l, zp, Vec3(0.f), -y.w, m_emitters.bounds(), &pos, &dir);
        return P * dir * pos * cos_z;
    }
    const Vec3 yp = zp + y.w * y.dist;
    const Vec3 n = dot(y.n, y.w) > 0.f ? -y.n : y.n;  // the side the light leaves toward z
    const float cos_y = std::fabs(dot(y.n, y.w));
    if (!(cos_y > 0.f)) return 0.f;
    light_pdf_le(l, yp, n, -y.w, m_emitters.bounds(), &pos, &dir);
    return P * pos * dir * cos_z / cos_y;
}

float OneBounceWeights::weight(PathGenerator generator, const VertexBsdf& x, const Vec3& wo_x, const VertexBsdf& z,
                               const OneBounceLight& y) const {
    const Vec3 xz = z.hit().p - x.hit().p;
    const float d2 = length_squared(xz);
    if (!(d2 > 0.f)) return 0.f;
    const Vec3 w_xz = xz / std::sqrt(d2);
    const float Y = light_density(z, -w_xz, y);
    const float p_rg = x.pdf_camera(wo_x, w_xz) * std::fabs(dot(w_xz, z.hit().ng)) / d2 * Y;
    const float p_surf = m_surfaces ? m_surfaces->pdf(z.hit()) * Y : 0.f;
    const float p_ss = source_density(z, y);
    const float p = generator == PathGenerator::ReceiverGathering ? p_rg
                    : generator == PathGenerator::SurfaceSampling ? p_surf
                                                                  : p_ss;
    auto h = [&](float q) { return m_settings.combine_heuristic == MisHeuristic::Power ? q * q : q; };
    const float sum = h(p_rg) + h(p_surf) + h(p_ss);
    return sum > 0.f && std::isfinite(sum) ? h(p) / sum : 0.f;
}

}  // namespace candela
