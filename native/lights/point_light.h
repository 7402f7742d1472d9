// Blender point and spot lights with Cycles 3.4's units (docs/conventions.md §2.1, §2.2):
//   intensity I = S/(4π) W/sr for power S (colour × energy);
//   radius r > 0: a disk of radius r facing the shading point with radiance L = S/(4π²r²) — the same
//   flux, with soft shadows; spot: I(θ) = S/(4π)·cosθ·smoothstep(...) (the extra cosθ is 3.4's), where θ is
//   the angle of the direction from the SAMPLED disk point to the shading point (Cycles 3.4
//   kernel/light/light.h evaluates spot_light_attenuation at −ls->D), which softens the cone's edge by the
//   disk's angular size; with r = 0 that is the direction from the centre.
// These lights are sampled by next-event estimation only (they are not hit by BSDF rays), so their
// contribution carries weight 1 and stays unbiased.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "core/math.h"
#include "lights/light_sample.h"
#include "sampling/warp.h"

namespace candela {

struct SpotShape {
    Vec3 direction;         // where the spot points (unit)
    float cos_half = -2.f;  // cos(spot_size/2); -2 = no cone (a point light)
    float smooth = 0.f;     // (1 − cos_half)·blend
    bool cycles34_cosine = false;

    /// Cycles 3.4 spot attenuation for a unit direction from the light toward the shaded point.
    float attenuation(const Vec3& to_point) const { return attenuation_cos(dot(direction, to_point)); }

    /// An upper bound of attenuation(w) over the directions w within angle `spread` of `to_point` (the
    /// directions from the points of a disk light toward the shaded point): the attenuation is
    /// non-decreasing in cos(angle to the spot axis), so evaluate it at the axis-most of those directions.
    float max_attenuation(const Vec3& to_point, float spread) const {
        if (cos_half < -1.f) return 1.f;
        const float theta = std::acos(clamp(dot(direction, to_point), -1.f, 1.f));
        return attenuation_cos(std::cos(std::max(theta - spread, 0.f)));
    }

    /// The attenuation as a function of c = cos(angle between the spot axis and the direction).
    float attenuation_cos(float c) const {
        if (cos_half < -1.f) return 1.f;
        if (c <= cos_half) return 0.f;
        float f = 1.f;
        if (c - cos_half < smooth) {
            const float x = (c - cos_half) / smooth;
            f = x * x * (3.f - 2.f * x);
        }
        return cycles34_cosine ? f * c : f;
    }
};

struct PointLight {
    Vec3 position;
    Color intensity;  // S/(4π)
    float radius = 0.f;
    SpotShape spot;

    LightSample sample_li(const LightSampleContext& ctx, Vec2 u) const {
        LightSample s;
        Vec3 to_light = position - ctx.p;
        const float d2 = length_squared(to_light);
        if (!(d2 > 0.f)) return s;
        const float d = std::sqrt(d2);
        const Vec3 axis = to_light / d;  // shading point → light centre
        if (radius <= 0.f) {
            s.wi = axis;
            s.dist = d;
            s.pdf = 1.f;
            s.is_delta = true;
            s.Li = intensity * (spot.attenuation(-axis) / d2);
            return s;
        }
        // Disk of radius r perpendicular to the axis, sampled uniformly by area.
        const Frame frame(axis);
        const Vec2 q = sample_uniform_disk_concentric(u);
        const Vec3 p = position + (frame.s * q.x + frame.t * q.y) * radius;
        Vec3 w = p - ctx.p;
        const float dist2 = length_squared(w);
        if (!(dist2 > 0.f)) return s;
        const float dist = std::sqrt(dist2);
        w = w / dist;
        const float area = k_pi * radius * radius;
        s.pdf = area_to_solid_angle(1.f / area, dist2, dot(w, axis));  // the disk faces the shading point
        if (s.pdf <= 0.f) return s;
        s.wi = w;
        s.dist = dist;
        // L = S/(4π·πr²) = I/(πr²); the spot factor depends on the direction from the sampled point (Cycles).
        s.Li = intensity * (spot.attenuation(-w) / area);
        s.is_delta = true;  // not hit by BSDF rays: weight 1
        return s;
    }

    float power() const { return 4.f * k_pi * luminance(intensity); }
};

}  // namespace candela
