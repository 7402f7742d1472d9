// Blender sun light (Cycles 3.4): irradiance E = S W/m² on a surface facing it. With angle > 0 Cycles
// samples a disk of radius tan(angle/2) at unit distance around the sun direction with
// pdf = 1/(π tan²(angle/2)) / cos³(θ) and evaluates the same value, so every sample contributes
// exactly S; we reproduce that estimator (Li/pdf = S per sample). Sampled by NEE only.
#pragma once

#include <cmath>
#include <limits>

#include "core/frame.h"
#include "core/math.h"
#include "lights/light_sample.h"
#include "sampling/warp.h"

namespace candela {

struct SunLight {
    Vec3 to_sun;       // unit direction toward the sun (−light direction)
    Color irradiance;  // S
    float tan_half_angle = 0.f;
    float scene_radius = 1.f;  // for power(): the flux through the scene's bounding disk

    LightSample sample_li(const LightSampleContext&, Vec2 u) const {
        LightSample s;
        s.dist = std::numeric_limits<float>::infinity();
        if (tan_half_angle <= 0.f) {
            s.wi = to_sun;
            s.pdf = 1.f;
            s.is_delta = true;
            s.Li = irradiance;
            return s;
        }
        const Frame frame(to_sun);
        const Vec2 q = sample_uniform_disk_concentric(u);
        const Vec3 w = normalize(to_sun + (frame.s * q.x + frame.t * q.y) * tan_half_angle);
        const float cos_t = dot(w, to_sun);
        const float inv_area = 1.f / (k_pi * tan_half_angle * tan_half_angle);
        s.wi = w;
        s.pdf = inv_area / (cos_t * cos_t * cos_t);
        s.Li = irradiance * s.pdf;  // Li/pdf = S for every sample
        s.is_delta = true;          // not hittable by BSDF rays in this renderer: weight 1
        return s;
    }

    float power() const { return k_pi * scene_radius * scene_radius * luminance(irradiance); }
};

}  // namespace candela
