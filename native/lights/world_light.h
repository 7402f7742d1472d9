// The world background as a light: constant radiance from every direction (Cycles' Background shader,
// or the world colour). Sampled uniformly over the sphere (p = 1/4π) and combined with BSDF sampling by
// MIS. (Importance-sampled environment maps belong to the scene-fidelity work.)
#pragma once

#include <limits>

#include "core/math.h"
#include "lights/light_sample.h"
#include "sampling/warp.h"

namespace candela {

struct WorldLight {
    Color radiance;
    float scene_radius = 1.f;

    LightSample sample_li(const LightSampleContext&, Vec2 u) const {
        LightSample s;
        s.wi = sample_uniform_sphere(u);
        s.pdf = uniform_sphere_pdf();
        s.dist = std::numeric_limits<float>::infinity();
        s.Li = radiance;
        return s;
    }
    float pdf_li(const Vec3&) const { return uniform_sphere_pdf(); }
    Color Le(const Vec3&) const { return radiance; }
    float power() const { return 4.f * k_pi * k_pi * scene_radius * scene_radius * luminance(radiance); }
};

}  // namespace candela
