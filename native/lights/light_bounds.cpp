#include "lights/light_bounds.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "lights/spherical_sampling.h"

namespace candela {
namespace {

/// cos(max(0, θ_a − θ_b)) from the cosines of θ_a, θ_b ∈ [0, π].
float cos_sub_clamped(float cos_a, float cos_b) {
    if (cos_a >= cos_b) return 1.f;
    const float sin_a = safe_sqrt(1.f - cos_a * cos_a), sin_b = safe_sqrt(1.f - cos_b * cos_b);
    return clamp(cos_a * cos_b + sin_a * sin_b, -1.f, 1.f);
}

float angle_between_unit(const Vec3& a, const Vec3& b) {
    if (dot(a, b) < 0.f) return k_pi - 2.f * std::asin(clamp(length(a + b) * 0.5f, 0.f, 1.f));
    return 2.f * std::asin(clamp(length(a - b) * 0.5f, 0.f, 1.f));
}

/// Smallest (up to a tiny slack) cone containing cones (wa, θa) and (wb, θb).
void union_cones(const Vec3& wa, float cos_a, const Vec3& wb, float cos_b, Vec3* w, float* cos_out) {
    const float ta = acos_clamped(cos_a), tb = acos_clamped(cos_b);
    const float td = angle_between_unit(wa, wb);
    if (std::min(td + tb, k_pi) <= ta) {
        *w = wa;
        *cos_out = cos_a;
        return;
    }
    if (std::min(td + ta, k_pi) <= tb) {
        *w = wb;
        *cos_out = cos_b;
        return;
    }
    const float to = 0.5f * (ta + td + tb) + 1e-5f;
    Vec3 axis = cross(wa, wb);
    const float al = length(axis);
    if (to >= k_pi || !(al > 1e-7f)) {
        *w = wa;
        *cos_out = -1.f;
        return;
    }
    axis = axis / al;
    const float tr = to - ta;  // rotate wa toward wb by tr (Rodrigues, axis ⟂ wa)
    *w = normalize(wa * std::cos(tr) + cross(axis, wa) * std::sin(tr));
    *cos_out = std::cos(to);
}

/// |cos| bound of n against any direction in the cone (axis, cos_half): cos(max(0, θ_n − θ_half)).
float cos_bound(const Vec3& n, const Vec3& axis, float cos_half) {
    if (is_black(n)) return 1.f;
    if (cos_half <= 0.f) return 1.f;
    return cos_sub_clamped(std::fabs(dot(n, axis)) / length(n), cos_half);
}

/// Solid angle and direction cone of a convex planar polygon seen from p.
float polygon_bound(const Vec3* v, int count, const LightSampleContext& ctx) {
    double omega = 0.0;
    for (int i = 1; i + 1 < count; ++i) omega += spherical_triangle_solid_angle(ctx.p, v[0], v[i], v[i + 1]);
    if (!(omega > 0.0)) return 0.f;
    Vec3 dirs[4];
    Vec3 sum(0.f);
    for (int i = 0; i < count; ++i) {
        dirs[i] = normalize(v[i] - ctx.p);
        sum += dirs[i];
    }
    float cos_half = -1.f;
    Vec3 axis(0.f, 0.f, 1.f);
    if (length_squared(sum) > 1e-12f) {
        axis = normalize(sum);
        cos_half = 1.f;
        for (int i = 0; i < count; ++i) cos_half = std::min(cos_half, dot(axis, dirs[i]));
        cos_half -= 1e-6f;  // slack for rounding
    }
    return float(omega) * cos_bound(ctx.n, axis, cos_half);
}

}  // namespace

float LightBounds::importance(const Vec3& p, const Vec3& n) const { return LightImportance(*this)(p, n); }

LightImportance::LightImportance(const LightBounds& b)
    : centre(b.bounds.centroid()),
      w(b.w),
      cos_o(b.cos_theta_o),
      cos_e(b.cos_theta_e),
      phi(b.phi),
      two_sided(b.two_sided) {
    radius2 = 0.25f * length_squared(b.bounds.diagonal());
    radius = std::sqrt(radius2);
    // pbrt-v4's clamp of d² at |diagonal|/2 (a length, not its square): keeps a point inside a cluster from
    // starving the sibling without flattening large clusters as a squared clamp does.
    d2_min = std::max(radius, 1e-12f);
    sin_o = safe_sqrt(1.f - cos_o * cos_o);
}

float LightImportance::operator()(const Vec3& p, const Vec3& n) const {
    if (!(phi > 0.f)) return 0.f;
    const Vec3 to_p = p - centre;
    const float d2_raw = length_squared(to_p);
    const float lp = std::sqrt(d2_raw);
    const float d2 = std::max(d2_raw, d2_min);
    // θ_w: angle between the cone axis and the direction light → p; two-sided emitters fold it.
    float cos_w = lp > 0.f ? dot(w, to_p) / lp : 1.f;
    if (two_sided) cos_w = std::fabs(cos_w);
    cos_w = clamp(cos_w, -1.f, 1.f);
    // θ_b: half-angle of the bounding sphere seen from p (p inside: every direction, θ′ = 0 below).
    const bool inside = d2_raw <= radius2 * (1.f + 1e-5f);
    const float sin_b = inside ? 0.f : radius / lp, cos_b = inside ? -1.f : safe_sqrt(1.f - sin_b * sin_b);
    // θ′ = max(0, θ_w − θ_o − θ_b), through θ_x = max(0, θ_w − θ_o): cos and sin of differences of angles in [0, π].
    float cos_x = 1.f, sin_x = 0.f;
    if (cos_w < cos_o) {
        const float sin_w = safe_sqrt(1.f - cos_w * cos_w);
        cos_x = clamp(cos_w * cos_o + sin_w * sin_o, -1.f, 1.f);
        sin_x = std::max(sin_w * cos_o - cos_w * sin_o, 0.f);
    }
    const float cos_p = cos_x >= cos_b ? 1.f : clamp(cos_x * cos_b + sin_x * sin_b, -1.f, 1.f);
    if (cos_p <= cos_e) return 0.f;
    float imp = phi * cos_p / d2;
    if (!is_black(n) && lp > 0.f) {
        // θ_i′ = max(0, θ_i − θ_b): the receiver's cosine bound.
        const float cos_i = clamp(std::fabs(dot(n, to_p)) / (lp * length(n)), 0.f, 1.f);
        if (cos_i < cos_b) imp *= clamp(cos_i * cos_b + safe_sqrt(1.f - cos_i * cos_i) * sin_b, -1.f, 1.f);
    }
    return std::isfinite(imp) ? imp : std::numeric_limits<float>::max() * 1e-3f;
}

LightBounds union_bounds(const LightBounds& a, const LightBounds& b) {
    if (!(a.phi > 0.f)) return b;
    if (!(b.phi > 0.f)) return a;
    LightBounds r;
    r.bounds = a.bounds;
    r.bounds.extend(b.bounds);
    union_cones(a.w, a.cos_theta_o, b.w, b.cos_theta_o, &r.w, &r.cos_theta_o);
    r.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
    r.phi = a.phi + b.phi;
    r.two_sided = a.two_sided || b.two_sided;
    return r;
}

std::optional<LightBounds> light_bounds(const Light& light) {
    return std::visit(
        [](const auto& l) -> std::optional<LightBounds> {
            using T = std::decay_t<decltype(l)>;
            LightBounds b;
            b.phi = l.power();
            if constexpr (std::is_same_v<T, PointLight>) {
                b.bounds.extend(l.position - Vec3(l.radius));
                b.bounds.extend(l.position + Vec3(l.radius));
                if (l.spot.cos_half >= -1.f) {
                    b.w = l.spot.direction;
                    b.cos_theta_o = l.spot.cos_half;
                } else {
                    b.cos_theta_o = -1.f;
                }
                b.cos_theta_e = 0.f;  // conservative: cos(π/2)
                return b;
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                for (float su : {-0.5f, 0.5f})
                    for (float sv : {-0.5f, 0.5f}) b.bounds.extend(l.center + l.u * su + l.v * sv);
                b.w = l.normal;
                b.cos_theta_o = 1.f;
                b.cos_theta_e = 0.f;
                return b;
            } else if constexpr (std::is_same_v<T, TriangleLight>) {
                b.bounds.extend(l.p0);
                b.bounds.extend(l.p1);
                b.bounds.extend(l.p2);
                b.w = l.normal;
                b.cos_theta_o = 1.f;
                b.cos_theta_e = 0.f;
                b.two_sided = true;
                return b;
            } else {
                return std::nullopt;  // sun, world
            }
        },
        light);
}

float light_irradiance_bound(const Light& light, const LightSampleContext& ctx) {
    return std::visit(
        [&](const auto& l) -> float {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight>) {
                const Vec3 to = l.position - ctx.p;
                const float d2 = length_squared(to);
                if (!(d2 > 0.f)) return std::numeric_limits<float>::max() * 1e-3f;
                const float d = std::sqrt(d2);
                const Vec3 axis = to / d;
                // The spot factor is evaluated per sampled disk point (point_light.h): bound it over the disk.
                const float spread = l.radius > 0.f ? std::atan(l.radius / d) : 0.f;
                const float att = l.spot.max_attenuation(-axis, spread);
                if (!(att > 0.f)) return 0.f;
                const float I = luminance(l.intensity) * att;
                if (l.radius <= 0.f) return I * cos_bound(ctx.n, axis, 1.f) / d2;
                const float r2 = l.radius * l.radius;
                const float omega = 2.f * k_pi * (1.f - d / std::sqrt(d2 + r2));
                const float cos_half = d / std::sqrt(d2 + r2) - 1e-6f;
                return I / (k_pi * r2) * omega * cos_bound(ctx.n, axis, cos_half);
            } else if constexpr (std::is_same_v<T, SunLight>) {
                const float cos_half = 1.f / std::sqrt(1.f + l.tan_half_angle * l.tan_half_angle) - 1e-6f;
                return luminance(l.irradiance) * cos_bound(ctx.n, l.to_sun, cos_half);
            } else if constexpr (std::is_same_v<T, WorldLight>) {
                return luminance(l.radiance) * (is_black(ctx.n) ? 4.f * k_pi : 2.f * k_pi);
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                if (dot(ctx.p - l.center, l.normal) <= 0.f) return 0.f;
                // A rectangle, or the parallelogram around an ellipse.
                const Vec3 v[4] = {l.center - l.u * 0.5f - l.v * 0.5f, l.center + l.u * 0.5f - l.v * 0.5f,
                                   l.center + l.u * 0.5f + l.v * 0.5f, l.center - l.u * 0.5f + l.v * 0.5f};
                return luminance(l.radiance) * polygon_bound(v, 4, ctx);
            } else {  // TriangleLight
                const Vec3 v[3] = {l.p0, l.p1, l.p2};
                return luminance(l.radiance) * polygon_bound(v, 3, ctx);
            }
        },
        light);
}

}  // namespace candela
