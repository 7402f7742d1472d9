// The density-estimation kernels of the photon map (docs/photon-mapping.md, "Kernels and their bias"): radially
// symmetric weights on the disc of radius r around the query point, normalised so that ∫_disc K dA = 1, so a
// radiance estimate Σ_p K(d_p)·f·Φ_p is the flux density the photons' distribution has, smoothed by K:
//
//   BOX       K = 1/(πr²)                                    (uniform)
//   CONE      K = 3/(πr²)·(1 − d/r)                          (Jensen's cone filter with k = 1: ∫(1 − d/r)dA = πr²/3)
//   GAUSSIAN  K = (e^(−β t/2) − e^(−β/2))/(πr²·I₀),  t = d²/r², β = 1.953 (Jensen's width), shifted to vanish at r,
//             I₀ = (2/β)(1 − e^(−β/2)) − e^(−β/2)
//
// With the second moment m₂ = ∫K d² dA, a smooth irradiance E is estimated as E + (m₂/4)·ΔE + O(r⁴): on a plane
// under a point light at height h (E ∝ (1 + d²/h²)^(−3/2), ΔE/E = −6/h² at the foot) the relative bias is
// −(3/2)·m₂/h², i.e. −(3/4)(r/h)² for BOX (m₂ = r²/2), −(9/20)(r/h)² for CONE (m₂ = 3r²/10) and −0.45693(r/h)²
// for GAUSSIAN (m₂ = 0.30462 r²); the next term is +(15/8)·m₄/h⁴ with m₄ = r⁴/3, r⁴/7, 0.14427 r⁴. The weight
// functions below are in terms of t = d²/r², per unit of πr².
#pragma once

#include <cmath>
#include <string>

namespace candela {

enum class DensityKernel { Box, Cone, Gaussian };

inline constexpr float k_gaussian_kernel_beta = 1.953f;

/// πr²·K at t = d²/r² ∈ [0, 1] (0 outside): the kernel's weight per unit of the disc's area.
inline float kernel_weight(DensityKernel kernel, float t) {
    if (!(t <= 1.f)) return 0.f;
    switch (kernel) {
    case DensityKernel::Box: return 1.f;
    case DensityKernel::Cone: return 3.f * (1.f - std::sqrt(t));
    default: {
        const float b = 0.5f * k_gaussian_kernel_beta;
        const float tail = std::exp(-b);
        const float i0 = (1.f - tail) / b - tail;
        return (std::exp(-b * t) - tail) / i0;
    }
    }
}

inline DensityKernel parse_density_kernel(const std::string& id) {
    return id == "BOX" ? DensityKernel::Box : id == "GAUSSIAN" ? DensityKernel::Gaussian : DensityKernel::Cone;
}

}  // namespace candela
