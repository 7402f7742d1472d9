// An emissive mesh triangle (Cycles: emission closure, both sides emit radiance L = strength·colour),
// in world space, sampled uniformly by area: p_ω = d²/(A |cos θ_l|). (Spherical-triangle sampling by
// solid angle is the `light_pdf = SOLID_ANGLE` option of the sampling toolbox.)
#pragma once

#include <cmath>

#include "core/math.h"
#include "lights/light_sample.h"
#include "sampling/warp.h"

namespace candela {

struct TriangleLight {
    Vec3 p0, p1, p2;
    Vec3 normal;  // unit geometric normal
    Color radiance;
    float area = 0.f;

    LightSample sample_li(const LightSampleContext& ctx, Vec2 u) const {
        const Vec2 b = sample_uniform_triangle(u);
        const Vec3 p = p0 * b.x + p1 * b.y + p2 * (1.f - b.x - b.y);
        return sample_from_area_point(ctx.p, p, normal, area, radiance, /*two_sided=*/true);
    }

    float pdf_li(const Vec3& d, float t) const { return area_to_solid_angle(1.f / area, t * t, std::fabs(dot(d, normal))); }

    float power() const { return 2.f * k_pi * area * luminance(radiance); }  // two-sided
};

}  // namespace candela
