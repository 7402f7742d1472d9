// Pixel reconstruction filters applied by filter importance sampling (Ernst et al. 2006, "Filter
// Importance Sampling"): each camera sample's offset from the pixel centre is drawn from the filter
// itself, so every sample carries weight 1 and stays in its own pixel. Filters are separable, as in
// Cycles (one 1-D table sampled per axis), with Cycles' definitions of width: the total support in pixels.
#pragma once

#include <string>
#include <vector>

#include "core/vec.h"

namespace candela {

class PixelFilter {
public:
    /// name: BOX, GAUSSIAN or BLACKMAN_HARRIS; width: total support in pixels (> 0).
    PixelFilter(const std::string& name, float width);

    /// Offset from the pixel centre for a canonical sample u ∈ [0, 1)².
    Vec2 sample(Vec2 u) const;

    /// The 1-D filter profile at offset x (not normalised; 0 outside ±width/2).
    float evaluate(float x) const;
    float width() const { return m_width; }

    static const std::vector<std::string>& names();

private:
    std::string m_name;
    float m_width;
    /// Inverse CDF of the profile over [−width/2, width/2] at k_inverse_size + 1 evenly spaced u, so a
    /// sample is one table lookup with linear interpolation instead of a binary search.
    static constexpr int k_inverse_size = 4096;
    std::vector<float> m_inverse_cdf;
    float sample_1d(float u) const;
};

}  // namespace candela
