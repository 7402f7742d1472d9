#include "lights/light_emission.h"

#include <cmath>
#include <type_traits>

#include "core/frame.h"
#include "core/math.h"
#include "sampling/warp.h"

namespace candela {

namespace {

/// Direction of a point or spot light's emission: uniform on the sphere, or in the spot's cone; its density.
Vec3 sample_point_direction(const SpotShape& spot, Vec2 u, float* pdf) {
    if (spot.cos_half < -1.f) {
        *pdf = uniform_sphere_pdf();
        return sample_uniform_sphere(u);
    }
    const float cos_max = clamp(spot.cos_half, -1.f, 1.f);
    *pdf = uniform_cone_pdf(cos_max);
    return Frame(spot.direction).to_world(sample_uniform_cone(u, cos_max));
}

float point_direction_pdf(const SpotShape& spot, const Vec3& d) {
    if (spot.cos_half < -1.f) return uniform_sphere_pdf();
    const float cos_max = clamp(spot.cos_half, -1.f, 1.f);
    return dot(d, spot.direction) >= cos_max ? uniform_cone_pdf(cos_max) : 0.f;
}

EmissionSample sample_point_le(const PointLight& l, Vec2 u_pos, Vec2 u_dir) {
    EmissionSample s;
    float p_d = 0.f;
    s.d = sample_point_direction(l.spot, u_dir, &p_d);
    const float att = l.spot.attenuation(s.d);
    if (!(p_d > 0.f) || !(att > 0.f)) return s;
    if (l.radius <= 0.f) {
        s.p = l.position;
        s.Le = l.intensity * att;
        s.pdf_pos = 1.f;
        s.pdf_dir = p_d;
        s.delta_pos = true;
        return s;
    }
    // The sphere of radius r: a point uniform on the disk across d, lifted onto the hemisphere facing d.
    const Frame frame(s.d);
    const Vec2 q = sample_uniform_disk_concentric(u_pos);
    const float lift = std::sqrt(std::max(0.f, 1.f - q.x * q.x - q.y * q.y));
    s.n = normalize(frame.s * q.x + frame.t * q.y + s.d * lift);
    s.p = l.position + s.n * l.radius;
    const float cos_t = dot(s.n, s.d);
    if (!(cos_t > 0.f)) return {};
    s.Le = l.intensity * (att / (k_pi * l.radius * l.radius));
    s.pdf_pos = 1.f / (4.f * k_pi * l.radius * l.radius);
    s.pdf_dir = 4.f * cos_t * p_d;
    return s;
}

/// A point on the disk of the bounding sphere's radius across ω (toward the light), outside the scene: the origin of
/// a ray from a distant light travelling along −ω.
Vec3 distant_origin(const Vec3& omega, Vec2 u, const SceneSphere& b) {
    const Frame frame(omega);
    const Vec2 q = sample_uniform_disk_concentric(u);
    return b.center + (omega + frame.s * q.x + frame.t * q.y) * b.radius;
}

EmissionSample sample_distant(const Vec3& omega, const Color& Le, float pdf_omega, bool delta_dir, Vec2 u_pos,
                              const SceneSphere& b) {
    EmissionSample s;
    if (!(pdf_omega > 0.f)) return s;
    s.d = -omega;
    s.p = distant_origin(omega, u_pos, b);
    s.Le = Le;
    s.pdf_pos = 1.f / (k_pi * b.radius * b.radius);
    s.pdf_dir = pdf_omega;
    s.delta_dir = delta_dir;
    s.infinite = true;
    return s;
}

/// Cosine-weighted direction around n.
Vec3 cosine_direction(const Vec3& n, Vec2 u, float* pdf) {
    const Vec3 local = sample_cosine_hemisphere(u);
    *pdf = cosine_hemisphere_pdf(local.z);
    return Frame(n).to_world(local);
}

}  // namespace

float spot_solid_angle_integral(const SpotShape& spot) {
    if (spot.cos_half < -1.f) return 4.f * k_pi;
    // 2π ∫ attenuation(c) dc over c = cos θ ∈ [cos_half, 1] (midpoint rule; the smoothstep edge is smooth).
    const double lo = clamp(spot.cos_half, -1.f, 1.f);
    constexpr int n = 8192;
    const double h = (1.0 - lo) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += spot.attenuation_cos(float(lo + (i + 0.5) * h));
    return float(2.0 * M_PI * sum * h);
}

EmissionSample light_sample_le(const Light& light, Vec2 u_pos, Vec2 u_dir, float u_side, const SceneSphere& bounds) {
    return std::visit(
        [&](const auto& l) -> EmissionSample {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight>) {
                return sample_point_le(l, u_pos, u_dir);
            } else if constexpr (std::is_same_v<T, SunLight>) {
                if (l.tan_half_angle <= 0.f) return sample_distant(l.to_sun, l.irradiance, 1.f, true, u_pos, bounds);
                const LightSample ls = l.sample_li(LightSampleContext{}, u_dir);  // the angular disk, as NEE
                return sample_distant(ls.wi, ls.Li, ls.pdf, false, u_pos, bounds);
            } else if constexpr (std::is_same_v<T, WorldLight>) {
                const LightSample ls = l.sample_li(LightSampleContext{}, u_dir);
                return sample_distant(ls.wi, ls.Li, ls.pdf, false, u_pos, bounds);
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                EmissionSample s;
                if (!(l.area > 0.f)) return s;
                if (l.ellipse) {
                    const Vec2 q = sample_uniform_disk_concentric(u_pos);
                    s.p = l.center + (l.u * q.x + l.v * q.y) * 0.5f;
                } else {
                    s.p = l.center + l.u * (u_pos.x - 0.5f) + l.v * (u_pos.y - 0.5f);
                }
                s.n = l.normal;
                s.d = cosine_direction(l.normal, u_dir, &s.pdf_dir);
                s.pdf_pos = 1.f / l.area;
                s.Le = l.radiance;
                return s;
            } else {  // TriangleLight
                EmissionSample s;
                if (!(l.area > 0.f)) return s;
                const Vec2 b = sample_uniform_triangle(u_pos);
                s.p = l.p0 * b.x + l.p1 * b.y + l.p2 * (1.f - b.x - b.y);
                s.n = u_side < 0.5f ? l.normal : -l.normal;  // both sides emit
                s.d = cosine_direction(s.n, u_dir, &s.pdf_dir);
                s.pdf_dir *= 0.5f;
                s.pdf_pos = 1.f / l.area;
                s.b1 = b.y;
                s.b2 = 1.f - b.x - b.y;
                s.Le = l.Le(s.p, s.b1, s.b2, s.d);
                return s;
            }
        },
        light);
}

void light_pdf_le(const Light& light, const Vec3& p, const Vec3& n, const Vec3& d, const SceneSphere& bounds,
                  float* pdf_pos, float* pdf_dir) {
    *pdf_pos = 0.f;
    *pdf_dir = 0.f;
    std::visit(
        [&](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight>) {
                const float p_d = point_direction_pdf(l.spot, d);
                if (l.radius <= 0.f) {
                    *pdf_pos = 1.f;
                    *pdf_dir = p_d;
                } else {
                    *pdf_pos = 1.f / (4.f * k_pi * l.radius * l.radius);
                    *pdf_dir = 4.f * std::max(0.f, dot(n, d)) * p_d;
                }
            } else if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, WorldLight>) {
                *pdf_pos = 1.f / (k_pi * bounds.radius * bounds.radius);
                if constexpr (std::is_same_v<T, WorldLight>) {
                    *pdf_dir = l.pdf_li(-d);
                } else if (l.tan_half_angle <= 0.f) {
                    *pdf_dir = 1.f;  // delta direction
                } else {
                    // The angular disk's density (SunLight::sample_li): 1/(π tan²)/cos³ inside it.
                    const float c = dot(-d, l.to_sun);
                    const float cos_max = 1.f / std::sqrt(1.f + l.tan_half_angle * l.tan_half_angle);
                    *pdf_dir = c >= cos_max ? 1.f / (k_pi * l.tan_half_angle * l.tan_half_angle * c * c * c) : 0.f;
                }
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                if (!(l.area > 0.f)) return;
                *pdf_pos = 1.f / l.area;
                *pdf_dir = cosine_hemisphere_pdf(dot(l.normal, d));
            } else {  // TriangleLight
                if (!(l.area > 0.f)) return;
                *pdf_pos = 1.f / l.area;
                *pdf_dir = 0.5f * cosine_hemisphere_pdf(dot(n, d));
            }
        },
        light);
}

EmitterPoint light_sample_point(const Light& light, Vec2 u_pos, Vec2 u_dir, float u_side) {
    return std::visit(
        [&](const auto& l) -> EmitterPoint {
            using T = std::decay_t<decltype(l)>;
            EmitterPoint e;
            if constexpr (std::is_same_v<T, PointLight>) {
                if (l.radius <= 0.f) {
                    e.p = l.position;
                    e.pdf_pos = 1.f;
                    e.delta_pos = true;
                } else {
                    e.n = sample_uniform_sphere(u_pos);
                    e.p = l.position + e.n * l.radius;
                    e.pdf_pos = 1.f / (4.f * k_pi * l.radius * l.radius);
                }
            } else if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, WorldLight>) {
                const LightSample ls = l.sample_li(LightSampleContext{}, u_dir);
                if (!(ls.pdf > 0.f)) return e;
                e.infinite = true;
                e.omega = ls.wi;
                e.pdf_pos = ls.pdf;
                e.Le = ls.Li;
                if constexpr (std::is_same_v<T, SunLight>) e.delta_pos = l.tan_half_angle <= 0.f;
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                if (!(l.area > 0.f)) return e;
                if (l.ellipse) {
                    const Vec2 q = sample_uniform_disk_concentric(u_pos);
                    e.p = l.center + (l.u * q.x + l.v * q.y) * 0.5f;
                } else {
                    e.p = l.center + l.u * (u_pos.x - 0.5f) + l.v * (u_pos.y - 0.5f);
                }
                e.n = l.normal;
                e.pdf_pos = 1.f / l.area;
            } else {
                if (!(l.area > 0.f)) return e;
                const Vec2 b = sample_uniform_triangle(u_pos);
                e.p = l.p0 * b.x + l.p1 * b.y + l.p2 * (1.f - b.x - b.y);
                e.b1 = b.y;
                e.b2 = 1.f - b.x - b.y;
                e.n = l.normal;  // both sides emit: light_radiance takes the side d leaves by
                e.pdf_pos = 1.f / l.area;
            }
            return e;
        },
        light);
}

Color light_radiance(const Light& light, const EmitterPoint& pt, const Vec3& d) {
    return std::visit(
        [&](const auto& l) -> Color {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight>) {
                const float att = l.spot.attenuation(d);
                if (l.radius <= 0.f) return l.intensity * att;
                return dot(pt.n, d) > 0.f ? l.intensity * (att / (k_pi * l.radius * l.radius)) : Color(0.f);
            } else if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, WorldLight>) {
                return pt.Le;
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                return dot(l.normal, d) > 0.f ? l.radiance : Color(0.f);
            } else {
                return l.Le(pt.p, pt.b1, pt.b2, d);
            }
        },
        light);
}

float light_center_direction_pdf(const Light& light, const Vec3& d) {
    if (const auto* point = std::get_if<PointLight>(&light)) {
        if (point->radius <= 0.f || point->spot.cos_half < -1.f) return point_direction_pdf(point->spot, d);
        return uniform_cone_pdf(clamp(point->spot.cos_half, -1.f, 1.f));
    }
    return std::holds_alternative<SunLight>(light) ? 1.f : 0.f;
}

bool emission_arrives(const Light& light, const Vec3& x, const Vec3& d) {
    const auto* point = std::get_if<PointLight>(&light);
    if (!point || !(point->radius > 0.f)) return true;
    // v = c − x, |v| cos θ = −d·v, |v|² sin² θ = |v × d|²: |v| tan θ ≤ r ⇔ |v × d|²·|v|² ≤ r²·(d·v)², cos θ > 0.
    const Vec3 v = point->position - x;
    const float along = -dot(d, v);
    if (!(along > 0.f)) return false;
    return length_squared(cross(v, d)) * length_squared(v) <= point->radius * point->radius * along * along;
}

bool light_hittable(const Light& light) {
    return std::holds_alternative<AreaLight>(light) || std::holds_alternative<TriangleLight>(light) ||
           std::holds_alternative<WorldLight>(light);
}

float light_emitted_power(const Light& light, const SceneSphere& bounds) {
    return std::visit(
        [&](const auto& l) -> float {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight>)
                return luminance(l.intensity) * spot_solid_angle_integral(l.spot);
            else if constexpr (std::is_same_v<T, SunLight>)
                return k_pi * bounds.radius * bounds.radius * luminance(l.irradiance);
            else if constexpr (std::is_same_v<T, WorldLight>)
                return k_pi * bounds.radius * bounds.radius * 4.f * k_pi * luminance(l.radiance);
            else if constexpr (std::is_same_v<T, AreaLight>)
                return k_pi * l.area * luminance(l.radiance);
            else
                return 2.f * k_pi * l.area * luminance(l.radiance);
        },
        light);
}

}  // namespace candela
