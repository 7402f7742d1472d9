// An environment: the world shader (Background colour × strength, e.g. an equirectangular Environment
// Texture) evaluated for every direction, importance-sampled by its luminance.
//
// Estimates: the radiance arriving from the world along a direction, for next-event estimation with a
// solid-angle pdf that MIS can combine with BSDF sampling (pbrt-v3 §14.2.4, "Infinite Area Lights").
// The world shader is baked once into an equirectangular grid (Blender's mapping, u = ½ − φ/2π,
// v = 1 − θ/π) at the resolution of the environment image it reads (at most 2048 × 1024). Cell (i, j) gets
// the weight luminance(L(centre))·sin θ_j plus a floor of 10⁻³ of the mean, so every direction keeps a
// positive density (the filtered image is non-zero a little beyond a bright texel's cell). A direction is
// drawn from the 2-D piecewise-constant distribution over (u, v) and
//     p_ω(ω) = p_uv(u, v) / (2π² sin θ)        (dω = sin θ dθ dφ = 2π² sin θ du dv).
// The radiance itself is always the shader's exact value, never the bake, so the bake only shapes the
// variance.
//
// A sun disc (a Nishita Sky Texture's: ShaderLibrary::sun_disc) is far smaller than a bake cell, so the bake
// barely sees it: it is sampled as a strategy of its own, uniformly over its cone, with probability q (its share of
// the power, kept within [0.05, 0.95]), and the map with 1 − q. The pdf of a direction is the mixture
// q·p_cone + (1 − q)·p_map, which MIS with BSDF sampling uses as it is (one-sample mixture, Veach 1997 §9.2).
#pragma once

#include <cstdint>
#include <memory>

#include "lights/light_sample.h"
#include "sampling/distribution_2d.h"
#include "texture/shader_program.h"

namespace candela {

class EnvironmentMap {
public:
    /// The world radiance is register `reg` of program `program`; `threads` bake the distribution.
    EnvironmentMap(std::shared_ptr<const ShaderLibrary> shaders, uint32_t program, uint32_t reg, int threads);

    /// Radiance arriving along −d (d points from the scene toward the sky).
    Color Le(const Vec3& d) const;
    /// A direction toward the environment and its solid-angle pdf.
    LightSample sample(Vec2 u) const;
    /// The solid-angle density with which sample() produces direction d.
    float pdf(const Vec3& d) const;
    /// The radiance averaged over all directions (power estimates, light-selection bounds).
    Color mean_radiance() const { return m_mean; }
    /// Bake resolution (width = 2·height).
    uint32_t width() const { return uint32_t(m_distribution.nu()); }
    uint32_t height() const { return uint32_t(m_distribution.nv()); }

private:
    std::shared_ptr<const ShaderLibrary> m_shaders;
    uint32_t m_program, m_reg;
    Distribution2D m_distribution;
    Color m_mean{0.f};
    // The sun disc strategy (q = 0: none).
    Vec3 m_sun{0.f, 0.f, 1.f};
    float m_sun_cos = 1.f, m_sun_q = 0.f;

    LightSample sample_map(Vec2 u) const;
    float pdf_map(const Vec3& d) const;
};

}  // namespace candela
