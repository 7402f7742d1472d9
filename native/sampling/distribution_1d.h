// Piecewise-constant 1-D distribution: discrete sampling proportional to non-negative weights (light
// selection) and continuous sampling of a tabulated function on [0, 1] (pixel filter importance sampling).
// Zero-weight bins are never chosen, and u = 1 − ε maps to the last non-zero bin.
// Bin search: a linear scan of the cdf for up to k_linear_search_max bins (the usual light-selection table
// has a handful of lights: cheaper than a binary search), std::upper_bound beyond; both give the same bin, and
// zero-weight bins are skipped through a table built once. pmf(i) is tabulated at construction (the expression
// a per-call division would use, so values are unchanged).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace candela {

class Distribution1D {
public:
    static constexpr size_t k_linear_search_max = 8;

    Distribution1D() = default;
    /// Throws InvalidScene if a weight is negative or not finite. All-zero weights give an empty
    /// distribution (size() > 0, integral() == 0) that must not be sampled.
    explicit Distribution1D(std::vector<float> weights);

    size_t size() const { return m_func.size(); }
    /// Memory its tables take.
    size_t bytes() const {
        return (m_func.capacity() + m_cdf.capacity() + m_pmf.capacity()) * sizeof(float) +
               m_resolve.capacity() * sizeof(uint32_t);
    }
    float integral() const { return m_integral; }

    /// Picks bin i with probability weight_i / Σ weight; returns i, its probability and u re-scaled to
    /// [0, 1) within the bin.
    size_t sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const {
        const size_t i = find_bin(u);
        if (pmf) *pmf = m_pmf[i];
        if (u_remapped) *u_remapped = remap(u, i);
        return i;
    }
    /// weight_i / Σ weight (0 for an all-zero distribution).
    float pmf(size_t i) const { return m_pmf[i]; }

    /// Samples x in [0, 1) with density f(x)/∫f (piecewise constant over size() bins).
    float sample_continuous(float u, float* pdf = nullptr) const;

private:
    /// Largest i < n with cdf[i] <= u (cdf[0] = 0), moved off zero-weight bins. `!(u < c)` is std::upper_bound's
    /// comparison, so the linear and the binary search agree for every u.
    size_t find_bin(float u) const {
        const size_t n = m_func.size();
        size_t i = 0;
        if (n <= k_linear_search_max) {
            while (i + 1 < n && !(u < m_cdf[i + 1])) ++i;
        } else {
            i = find_bin_binary(u);
        }
        return m_resolve.empty() ? i : m_resolve[i];
    }
    size_t find_bin_binary(float u) const;
    float remap(float u, size_t i) const;

    std::vector<float> m_func;        // weights
    std::vector<float> m_cdf;         // size()+1 entries, m_cdf[0] = 0, m_cdf[n] = 1
    std::vector<float> m_pmf;         // weight_i / (integral · n)
    std::vector<uint32_t> m_resolve;  // bin found by the search → the non-zero bin it stands for; empty if
                                      // no weight is zero (identity)
    float m_integral = 0.f;           // mean weight (∫ of the step function over [0,1])
};

}  // namespace candela
