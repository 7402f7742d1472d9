// The density of a bilinearly filtered equirectangular image on the sphere: on (u, v) ∈ [0, 1)², periodic in u,
//     p_uv(u, v) ∝ g(u, v) · sin(π v),
// g the bilinear interpolant of non-negative knot values. Knots lie at texel centres, u_i = (i + ½)/nu (periodic:
// the interval between the last and the first knot wraps across u = 0), and in v at 0, v_j = (j + ½)/nv and 1
// (nv + 2 rows of knots; the first and last intervals are half as tall). sin(π v) = sin θ is the Jacobian of the
// lat-long map (dω = 2π² sin θ du dv), so the solid-angle density p_ω = p_uv/(2π² sin θ) ∝ g exactly: with g the
// texels' luminance it follows the image as Linear interpolation renders it, a sun's filtered footprint included.
//
// Sampled exactly by inversion (the marginal/conditional construction of pbrt-v3 §13.6.7, with linear pieces):
// the marginal of v on knot interval k is (a + (b − a)·t)·sin(π v), a and b the means of knot rows k and k + 1
// (t the fraction of the interval), whose cdf has a closed form (∫ t sin = sin/c² − t cos/c) inverted by
// safeguarded Newton steps; given v, the conditional in u is piecewise linear with knot values (1 − t)·g_k + t·g_{k+1}
// (the sin θ factor cancels), its cdf the same blend of the two rows' tabulated cdfs (a binary search on the blend,
// O(log nu)); inside an interval a linear density from a to b is inverted in closed form,
// x = ξ(a + b)/(a + √(a² + ξ(b² − a²))).
#pragma once

#include <cstddef>
#include <vector>

#include "core/vec.h"

namespace candela {

class BilinearSphereDistribution {
public:
    BilinearSphereDistribution() = default;
    /// knots: nv + 2 rows of nu non-negative values (row 0 at v = 0, row j + 1 at v = (j + ½)/nv, row nv + 1 at
    /// v = 1), column i at u = (i + ½)/nu. Throws InvalidScene on a negative or non-finite value.
    BilinearSphereDistribution(std::vector<float> knots, size_t nu, size_t nv);

    size_t nu() const { return m_nu; }
    size_t nv() const { return m_nv; }
    /// ∫∫ g(u, v)·sin(π v) du dv; 0 = nothing to sample (do not call sample()).
    double integral() const { return m_integral; }
    /// Memory its tables take.
    size_t bytes() const {
        return (m_knots.capacity() + m_row_cdf.capacity() + m_row_mean.capacity()) * sizeof(float) +
               m_marginal_cdf.capacity() * sizeof(double);
    }

    /// Weights ω_k of the knot rows: ∫∫ g·sin(π v) du dv = Σ_k ω_k · (mean of row k's knots) for any knot values.
    static std::vector<double> row_weights(size_t nv);

    /// A point with density pdf(point) (written to *pdf); u in [0, 1)².
    Vec2 sample(Vec2 u, float* pdf) const;
    float pdf(Vec2 p) const;
    /// g(p)/integral(): the density divided by sin(π v) (p_ω·2π², without the division by sin θ).
    float pdf_over_sin(Vec2 p) const;

private:
    size_t m_nu = 0, m_nv = 0;
    std::vector<float> m_knots;          // (nv + 2) × nu
    std::vector<float> m_row_cdf;        // (nv + 2) × (nu + 1): each knot row's cumulative interval integrals
    std::vector<float> m_row_mean;       // nv + 2: each knot row's mean (∫ over u)
    std::vector<double> m_marginal_cdf;  // nv + 2: cumulative masses of the v-intervals (first entry 0)
    double m_integral = 0.0;
};

}  // namespace candela
