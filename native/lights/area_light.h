// Blender area light (Cycles 3.4): a one-sided Lambertian emitter facing `normal` (the light's −Z),
// radiance L = S/(4A) where A is the world-space area (object scale included; ellipse A = π/4·|u||v|).
// `light_pdf = AREA` (the two-argument sample_li/pdf_li): uniform by area, p_ω = d²/(A cos θ_l).
// `light_pdf = SOLID_ANGLE`: spherical-rectangle sampling (Ureña et al. 2013), p_ω = 1/S, with area sampling
// for ellipses, non-orthogonal (sheared) edges, S ≤ 1e-4 sr and grazing views; pdf_li(ctx, ...) mirrors it.
// BSDF rays hit the light analytically and are MIS-weighted. Camera rays see it only when `visible_camera`
// (Blender's Object > Visibility > Camera, off by default for lights in 3.4: Cycles then shows no light).
// Lights are not occluders: a ray passes through and continues to the next surface.
#pragma once

#include <cmath>

#include "core/math.h"
#include "lights/light_sample.h"
#include "lights/spherical_sampling.h"
#include "sampling/warp.h"

namespace candela {

struct AreaLight {
    Vec3 center;
    Vec3 u, v;    // full edge vectors (rectangle) or diameters (ellipse)
    Vec3 normal;  // emitting side
    Color radiance;
    bool ellipse = false;
    bool visible_camera = false;
    float area = 0.f;

    LightSample sample_li(const LightSampleContext& ctx, Vec2 s2) const {
        Vec3 p;
        if (ellipse) {
            const Vec2 d = sample_uniform_disk_concentric(s2);
            p = center + (u * d.x + v * d.y) * 0.5f;
        } else {
            p = center + u * (s2.x - 0.5f) + v * (s2.y - 0.5f);
        }
        return sample_from_area_point(ctx.p, p, normal, area, radiance, /*two_sided=*/false);
    }

    /// Ray–light intersection within (tmin, tmax); only the emitting side counts.
    bool intersect(const Vec3& o, const Vec3& d, float tmin, float tmax, float* t_hit) const {
        const float denom = dot(d, normal);
        if (denom >= 0.f) return false;
        const float t = dot(center - o, normal) / denom;
        if (!(t > tmin && t < tmax)) return false;
        const Vec3 q = o + d * t - center;
        const float a = dot(q, u) / length_squared(u), b = dot(q, v) / length_squared(v);
        const bool inside = ellipse ? (4.f * (a * a + b * b) <= 1.f) : (std::fabs(a) <= 0.5f && std::fabs(b) <= 0.5f);
        if (!inside) return false;
        *t_hit = t;
        return true;
    }

    /// Solid-angle pdf of sampling direction d that hits the light at distance t.
    float pdf_li(const Vec3& d, float t) const { return area_to_solid_angle(1.f / area, t * t, -dot(d, normal)); }

    /// The spherical rectangle seen from p (valid only for rectangles whose edges are orthogonal).
    SphericalRectangle spherical_rectangle(const Vec3& p) const {
        return SphericalRectangle::make(p, center - u * 0.5f - v * 0.5f, u, v);
    }
    bool rectangular() const { return !ellipse && std::fabs(dot(u, v)) <= 1e-4f * length(u) * length(v); }

    LightSample sample_li(const LightSampleContext& ctx, Vec2 s2, LightPdfMode mode) const {
        if (mode == LightPdfMode::Area || !rectangular()) return sample_li(ctx, s2);
        if (dot(ctx.p - center, normal) <= 0.f) return {};  // behind the emitting side (or in its plane)
        const SphericalRectangle rect = spherical_rectangle(ctx.p);
        if (!rect.usable()) return sample_li(ctx, s2);
        LightSample s;
        const Vec3 p = rect.sample_point(s2);
        Vec3 w = p - ctx.p;
        const float d2 = length_squared(w);
        if (!(d2 > 0.f)) return s;
        const float d = std::sqrt(d2);
        w = w / d;
        if (!(-dot(w, normal) > 0.f)) return s;
        const float pdf = 1.f / rect.solid_angle();
        if (!(pdf > 0.f) || !std::isfinite(pdf)) return s;
        s.wi = w;
        s.dist = d;
        s.pdf = pdf;
        s.Li = radiance;
        return s;
    }

    /// Solid-angle pdf of direction d from ctx.p that hits the emitting side at distance t, in `mode`.
    float pdf_li(const LightSampleContext& ctx, const Vec3& d, float t, LightPdfMode mode) const {
        if (mode == LightPdfMode::Area || !rectangular()) return pdf_li(d, t);
        if (dot(ctx.p - center, normal) <= 0.f) return 0.f;
        const SphericalRectangle rect = spherical_rectangle(ctx.p);
        if (!rect.usable()) return pdf_li(d, t);
        const float pdf = 1.f / rect.solid_angle();
        return std::isfinite(pdf) ? pdf : 0.f;
    }

    float power() const { return k_pi * area * luminance(radiance); }
};

}  // namespace candela
