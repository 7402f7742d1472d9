// Blender area light (Cycles 3.4): a one-sided Lambertian emitter facing `normal` (the light's −Z),
// radiance L = S/(4A) where A is the world-space area (object scale included; ellipse A = π/4·|u||v|).
// Sampled uniformly by area (p_ω = d²/(A cos θ_l)); BSDF rays hit it analytically and are MIS-weighted.
// Lights are not occluders: a ray passes through and continues to the next surface.
#pragma once

#include <cmath>

#include "core/math.h"
#include "lights/light_sample.h"
#include "sampling/warp.h"

namespace candela {

struct AreaLight {
    Vec3 center;
    Vec3 u, v;       // full edge vectors (rectangle) or diameters (ellipse)
    Vec3 normal;     // emitting side
    Color radiance;
    bool ellipse = false;
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

    float power() const { return k_pi * area * luminance(radiance); }
};

}  // namespace candela
