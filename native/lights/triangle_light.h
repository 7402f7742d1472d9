// An emissive mesh triangle (Cycles: emission closure, both sides emit radiance L = strength·colour),
// in world space. `light_pdf = AREA`: uniform by area, p_ω = d²/(A |cos θ_l|) (the two-argument
// sample_li/pdf_li). `light_pdf = SOLID_ANGLE`: spherical-triangle sampling (Arvo 1995), p_ω = 1/Ω, used only
// where it pays off and is robust: the triangle is near (its longest edge is longer than the shading point's
// distance to its plane — farther away, area sampling's density is already close to uniform in solid angle
// and the spherical construction's trigonometry would be wasted; Cycles uses the same rule) and
// 3e-4 < Ω < 6.22 sr; else area sampling. pdf_li(ctx, ...) mirrors the choice exactly.
// A textured emitter (`source` set) evaluates its radiance at the sampled point (lights/emission_source.h); its
// `radiance` is then the triangle's average, used only for power and selection bounds.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "lights/emission_source.h"
#include "lights/light_sample.h"
#include "lights/spherical_sampling.h"
#include "sampling/warp.h"

namespace candela {

struct TriangleLight {
    Vec3 p0, p1, p2;
    Vec3 normal;     // unit geometric normal
    Color radiance;  // constant emission; a textured emitter's average (power and bounds only)
    float area = 0.f;
    const EmissionSource* source = nullptr;  // textured emission: radiance evaluated at each sampled point
    uint32_t source_id = 0;
    float longest_edge_sq = -1.f;  // cached by prepare(); < 0: computed per call

    /// Radiance leaving point p (barycentric weights b1, b2 of p1 and p2) toward wo.
    Color Le(const Vec3& p, float b1, float b2, const Vec3& wo) const {
        return source ? source->emission(source_id, p, normal, b1, b2, wo) : radiance;
    }

    LightSample sample_li(const LightSampleContext& ctx, Vec2 u) const {
        const Vec2 b = sample_uniform_triangle(u);
        const Vec3 p = p0 * b.x + p1 * b.y + p2 * (1.f - b.x - b.y);
        LightSample s = sample_from_area_point(ctx.p, p, normal, area, radiance, /*two_sided=*/true);
        if (source && s.pdf > 0.f) s.Li = Le(p, b.y, 1.f - b.x - b.y, -s.wi);
        return s;
    }

    /// Barycentric weights (of p1, p2) of a point in the triangle's plane, clamped into the triangle.
    Vec2 barycentrics(const Vec3& p) const {
        const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = p - p0;
        const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), dp1 = dot(d, e1), dp2 = dot(d, e2);
        const float det = d11 * d22 - d12 * d12;
        if (!(det > 0.f)) return {1.f / 3.f, 1.f / 3.f};
        float b1 = clamp((d22 * dp1 - d12 * dp2) / det, 0.f, 1.f), b2 = clamp((d11 * dp2 - d12 * dp1) / det, 0.f, 1.f);
        if (b1 + b2 > 1.f) {
            const float sum = b1 + b2;
            b1 /= sum;
            b2 /= sum;
        }
        return {b1, b2};
    }

    float pdf_li(const Vec3& d, float t) const {
        return area_to_solid_angle(1.f / area, t * t, std::fabs(dot(d, normal)));
    }

    /// Solid angle seen from p, and whether SOLID_ANGLE mode samples it spherically from there.
    bool uses_spherical_sampling(const Vec3& p, float* omega = nullptr) const {
        double sr = 0.0;
        const bool spherical = spherical_solid_angle(p, &sr);
        if (omega) *omega = float(is_near(p) ? sr : spherical_triangle_solid_angle(p, p0, p1, p2));
        return spherical;
    }

    /// Whether SOLID_ANGLE mode samples spherically from p; if so, *sr is the solid angle (else unset).
    bool spherical_solid_angle(const Vec3& p, double* sr) const {
        if (!is_near(p)) return false;
        *sr = spherical_triangle_solid_angle(p, p0, p1, p2);
        return in_spherical_range(*sr);
    }
    static bool in_spherical_range(double sr) {
        return sr > k_min_spherical_triangle_sr && sr < k_max_spherical_triangle_sr;
    }

    /// The longest edge², computed once (prepare()) or, for a light that was not prepared, per call.
    float longest_edge_squared() const {
        if (longest_edge_sq >= 0.f) return longest_edge_sq;
        return std::max(std::max(length_squared(p1 - p0), length_squared(p2 - p1)), length_squared(p0 - p2));
    }
    /// Caches the per-triangle constants the per-sample tests use; call after the vertices are set (LightSet::add
    /// does). The cached value is the per-call expression's (up to FMA contraction, a few ulps); sampling and pdf
    /// evaluation then read the same value, so their near/far decisions agree exactly.
    void prepare() {
        longest_edge_sq = -1.f;
        longest_edge_sq = longest_edge_squared();
    }

    /// Signed distance from p to the triangle's plane along the normal.
    float plane_distance(const Vec3& p) const { return dot(p0 - p, normal); }
    /// Longest edge² > (distance from p to the triangle's plane)².
    bool is_near(const Vec3& p) const { return is_near(plane_distance(p)); }
    bool is_near(float plane_dist) const { return longest_edge_squared() > plane_dist * plane_dist; }

    LightSample sample_li(const LightSampleContext& ctx, Vec2 u, LightPdfMode mode) const {
        if (mode == LightPdfMode::Area) return sample_li(ctx, u);
        const float plane_dist = plane_distance(ctx.p);
        if (!is_near(plane_dist)) return sample_li(ctx, u);
        return sample_li_near(ctx, u, plane_dist);
    }
    /// SOLID_ANGLE from a point where is_near() holds (plane_dist = plane_distance(ctx.p)): spherical sampling
    /// if Ω is in range, else area sampling. Out of line (triangle_light.cpp): most shading points are far from
    /// a mesh light, and the far path stays a small inlinable branch.
    LightSample sample_li_near(const LightSampleContext& ctx, Vec2 u, float plane_dist) const;

    /// Solid-angle pdf of direction wi from ctx.p that hits the triangle at distance t, in `mode`.
    float pdf_li(const LightSampleContext& ctx, const Vec3& wi, float t, LightPdfMode mode) const {
        double sr = 0.0;
        if (mode == LightPdfMode::Area || !spherical_solid_angle(ctx.p, &sr)) return pdf_li(wi, t);
        const float pdf = float(1.0 / sr);  // the expression SphericalTriangle::sample() uses
        return std::isfinite(pdf) ? pdf : 0.f;
    }

    float power() const { return 2.f * k_pi * area * luminance(radiance); }  // two-sided
};

}  // namespace candela
