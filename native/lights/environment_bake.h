// The environment light's importance maps (lights/environment_light.h): densities over the equirectangular
// domain (u, v) ∈ [0, 1)² (Blender's mapping, u = ½ − φ/2π, v = 1 − θ/π) that follow the radiance as rendered.
//
// - An image read with Linear (or Cubic) interpolation, at most 2048 × 2048 texels: the rendered radiance is the
//   bilinear interpolant of the texels, so the density is piecewise bilinear with knots at the texel centres
//   (sampling/bilinear_sphere_distribution.h), knot value luminance(L)·sin θ: p_uv follows L·sin θ up to the
//   curvature of sin θ inside one texel, i.e. p_ω = p_uv/(2π² sin θ) follows the filtered radiance, the footprint
//   of a sun of a few texels included. The knots at the poles are 0 (sin θ = 0), so p_ω stays finite there.
// - Anything else (Closest interpolation, several images of different sizes, a procedural world, images wider
//   than 2048): a piecewise-constant map over cells (sampling/distribution_2d.h), each cell weighted by
//   ∫ luminance(L)·sin θ over it by the midpoint rule on 2 × 2 points per texel it spans (exact for Closest when
//   cells are texels, the case of an image up to 2048 wide and twice as wide as tall).
//
// Each comes twice. `plain` adds a floor of 10⁻³ of the mean luminance to every direction, so that it can be
// the only strategy (light tracing, photon emission, next-event estimation without MIS). `compensated` is MIS
// compensation (Karlík, Šik, Vévoda, Skřivan, Křivánek 2019, "MIS compensation: optimizing sampling techniques in
// multiple importance sampling", ACM TOG 38(6), §4): the radiance less its mean over the sphere, clamped at 0
// (and 0 within 10⁻⁴ of the mean) — the map for next-event estimation combined by MIS with BSDF sampling, which
// already covers the dim sky, so the shadow rays go where the environment is brighter than average. Its density is
// 0 where L ≤ mean: valid only beside a strategy that covers those directions.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>

#include "core/vec.h"
#include "sampling/bilinear_sphere_distribution.h"
#include "sampling/distribution_2d.h"

namespace candela {

class ShaderLibrary;

/// One importance map over (u, v): piecewise bilinear or piecewise constant.
class EnvironmentDensity {
public:
    EnvironmentDensity() = default;
    explicit EnvironmentDensity(BilinearSphereDistribution d) : m_bilinear(true), m_linear(std::move(d)) {}
    explicit EnvironmentDensity(Distribution2D d) : m_constant(std::move(d)) {}

    bool bilinear() const { return m_bilinear; }
    /// Nothing to sample (an empty or all-zero map).
    bool empty() const {
        return m_bilinear ? !(m_linear.integral() > 0.0) : !(m_constant.nu() > 0 && m_constant.integral() > 0.f);
    }
    uint32_t width() const { return uint32_t(m_bilinear ? m_linear.nu() : m_constant.nu()); }
    uint32_t height() const { return uint32_t(m_bilinear ? m_linear.nv() : m_constant.nv()); }
    /// (u, v) with density *pdf_uv; call only if !empty().
    Vec2 sample(Vec2 u, float* pdf_uv) const {
        return m_bilinear ? m_linear.sample(u, pdf_uv) : m_constant.sample(u, pdf_uv);
    }
    float pdf(Vec2 uv) const {
        if (empty()) return 0.f;
        return m_bilinear ? m_linear.pdf(uv) : m_constant.pdf(uv);
    }
    /// The solid-angle density of the direction at (u, v): p_uv/(2π² sin θ), sin θ = sin(π v) (0 at the poles for
    /// the constant map; the bilinear map's sin θ factor cancels exactly).
    float solid_angle_pdf(Vec2 uv) const {
        if (empty()) return 0.f;
        constexpr float k_jacobian = 2.f * 3.14159265358979f * 3.14159265358979f;
        if (m_bilinear) return m_linear.pdf_over_sin(uv) / k_jacobian;
        const float sin_theta = std::sin(3.14159265358979f * uv.y);
        return sin_theta > 0.f ? m_constant.pdf(uv) / (k_jacobian * sin_theta) : 0.f;
    }
    /// Memory its tables take.
    size_t bytes() const { return m_linear.bytes() + m_constant.bytes(); }

private:
    bool m_bilinear = false;
    Distribution2D m_constant;
    BilinearSphereDistribution m_linear;
};

struct EnvironmentBake {
    EnvironmentDensity plain, compensated;
    Color mean{0.f};  // the radiance averaged over the sphere
};

/// Bakes the maps of the world program `program` of `lib`, whose radiance along a direction is Le(d).
EnvironmentBake bake_environment(const ShaderLibrary& lib, uint32_t program,
                                 const std::function<Color(const Vec3&)>& Le, int threads);

}  // namespace candela
