// An environment: the world shader (Background colour × strength, e.g. an equirectangular Environment
// Texture) evaluated for every direction, importance-sampled by its luminance.
//
// Estimates: the radiance arriving from the world along a direction, for next-event estimation with a
// solid-angle pdf that MIS can combine with BSDF sampling (pbrt-v3 §14.2.4, "Infinite Area Lights").
// The world shader is baked once into importance maps over the equirectangular domain (Blender's mapping,
// u = ½ − φ/2π, v = 1 − θ/π) that follow the radiance as rendered — piecewise bilinear with knots at the texel
// centres for an image read with Linear interpolation, piecewise constant over texels for Closest and for
// procedural worlds (lights/environment_bake.h) — and a direction is drawn from one and
//     p_ω(ω) = p_uv(u, v) / (2π² sin θ)        (dω = sin θ dθ dφ = 2π² sin θ du dv).
// Two maps: `plain` (every direction keeps a positive density) for strategies that stand alone, and the MIS-
// compensated one (the radiance less its mean, clamped at 0; Karlík et al. 2019) for next-event estimation
// combined with BSDF sampling (sample(u, true), pdf(d, true)). The radiance itself is always the shader's exact
// value, never the bake, so the bake only shapes the variance.
//
// A sun disc (a Nishita Sky Texture's: ShaderLibrary::sun_disc) is far smaller than a bake cell, so the bake
// barely sees it: it is sampled as a strategy of its own, uniformly over its cone, with probability q (its share of
// the power, kept within [0.05, 0.95]), and the map with 1 − q. The pdf of a direction is the mixture
// q·p_cone + (1 − q)·p_map, which MIS with BSDF sampling uses as it is (one-sample mixture, Veach 1997 §9.2).
#pragma once

#include <cstdint>
#include <memory>

#include "lights/environment_bake.h"
#include "lights/light_sample.h"
#include "texture/shader_program.h"

namespace candela {

class EnvironmentMap {
public:
    /// The world radiance is register `reg` of program `program`; `threads` bake the distribution.
    EnvironmentMap(std::shared_ptr<const ShaderLibrary> shaders, uint32_t program, uint32_t reg, int threads);

    /// Radiance arriving along −d (d points from the scene toward the sky).
    Color Le(const Vec3& d) const;
    /// A direction toward the environment and its solid-angle pdf; `compensated`: from the MIS-compensated map
    /// (next-event estimation beside BSDF sampling; 0 density where the radiance is below its mean).
    LightSample sample(Vec2 u, bool compensated = false) const;
    /// The solid-angle density with which sample(·, compensated) produces direction d.
    float pdf(const Vec3& d, bool compensated = false) const;
    /// The radiance averaged over all directions (power estimates, light-selection bounds).
    Color mean_radiance() const { return m_mean; }
    /// Map resolution: bake cells, or the knot columns and rows between the poles of a bilinear map.
    uint32_t width() const { return m_maps[0].width(); }
    uint32_t height() const { return m_maps[0].height(); }
    /// Whether the maps are piecewise bilinear (an image read with Linear interpolation).
    bool bilinear() const { return m_maps[0].bilinear(); }

private:
    std::shared_ptr<const ShaderLibrary> m_shaders;
    uint32_t m_program, m_reg;
    EnvironmentDensity m_maps[2];  // plain, MIS-compensated
    Color m_mean{0.f};
    // The sun disc strategy (q = 0: none).
    Vec3 m_sun{0.f, 0.f, 1.f};
    float m_sun_cos = 1.f, m_sun_q = 0.f;

    LightSample sample_map(Vec2 u, const EnvironmentDensity& map) const;
    float pdf_map(const Vec3& d, const EnvironmentDensity& map) const;
};

}  // namespace candela
