// The world background as a light: Cycles' Background shader. A constant colour is sampled uniformly over
// the sphere (p = 1/4π); a varying one (an Environment Texture, lights/environment_light.h) by its
// luminance. Either combines with BSDF sampling by MIS.
#pragma once

#include <limits>
#include <memory>

#include "core/math.h"
#include "lights/environment_light.h"
#include "lights/light_sample.h"
#include "sampling/warp.h"

namespace candela {

struct WorldLight {
    Color radiance;  // the constant colour; with an environment its mean radiance (power, bounds)
    float scene_radius = 1.f;
    std::shared_ptr<const EnvironmentMap> environment;  // null: constant

    /// `compensated`: the environment's MIS-compensated map (next-event estimation beside BSDF sampling).
    LightSample sample_li(const LightSampleContext&, Vec2 u, bool compensated = false) const {
        if (environment) return environment->sample(u, compensated);
        LightSample s;
        s.wi = sample_uniform_sphere(u);
        s.pdf = uniform_sphere_pdf();
        s.dist = std::numeric_limits<float>::infinity();
        s.Li = radiance;
        return s;
    }
    float pdf_li(const Vec3& wi, bool compensated = false) const {
        return environment ? environment->pdf(wi, compensated) : uniform_sphere_pdf();
    }
    Color Le(const Vec3& d) const { return environment ? environment->Le(d) : radiance; }
    float power() const { return 4.f * k_pi * k_pi * scene_radius * scene_radius * luminance(radiance); }
};

}  // namespace candela
