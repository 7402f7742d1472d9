// Piecewise-constant 1-D distribution: discrete sampling proportional to non-negative weights (light
// selection) and continuous sampling of a tabulated function on [0, 1] (pixel filter importance sampling).
// Zero-weight bins are never chosen, and u = 1 − ε maps to the last non-zero bin.
#pragma once

#include <cstddef>
#include <vector>

namespace candela {

class Distribution1D {
public:
    Distribution1D() = default;
    /// Throws InvalidScene if a weight is negative or not finite. All-zero weights give an empty
    /// distribution (size() > 0, integral() == 0) that must not be sampled.
    explicit Distribution1D(std::vector<float> weights);

    size_t size() const { return m_func.size(); }
    float integral() const { return m_integral; }

    /// Picks bin i with probability weight_i / Σ weight; returns i, its probability and u re-scaled to
    /// [0, 1) within the bin.
    size_t sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;
    float pmf(size_t i) const { return m_integral > 0.f ? m_func[i] / (m_integral * size()) : 0.f; }

    /// Samples x in [0, 1) with density f(x)/∫f (piecewise constant over size() bins).
    float sample_continuous(float u, float* pdf = nullptr) const;

private:
    size_t find_bin(float u) const;

    std::vector<float> m_func;  // weights
    std::vector<float> m_cdf;   // size()+1 entries, m_cdf[0] = 0, m_cdf[n] = 1
    float m_integral = 0.f;     // mean weight (∫ of the step function over [0,1])
};

}  // namespace candela
