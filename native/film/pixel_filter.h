// Pixel reconstruction filters applied by filter importance sampling (Ernst et al. 2006, "Filter
// Importance Sampling"): each camera sample's offset from the pixel centre is drawn from the filter
// itself, so every sample carries weight 1 and stays in its own pixel. Filters are separable, as in
// Cycles (one 1-D table sampled per axis), with Cycles' meaning of the width (intern/cycles/scene/film.cpp,
// filter_table): the user's width is the box's total support, while the Gaussian's support is 3× and the
// Blackman–Harris window's 2× the width (a Blackman–Harris of width 1.5 reaches 1.5 pixels each way).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"

namespace candela {

class PixelFilter {
public:
    /// name: BOX, GAUSSIAN or BLACKMAN_HARRIS; width: Blender's filter width in pixels (> 0).
    PixelFilter(const std::string& name, float width);

    /// Offset from the pixel centre for a canonical sample u ∈ [0, 1)².
    Vec2 sample(Vec2 u) const;

    /// The 1-D filter profile at offset x (not normalised; 0 outside ±support()/2).
    float evaluate(float x) const;
    /// The density of sample()'s offsets along one axis at offset x: the normalised filter exactly as filter
    /// importance sampling realises it (the derivative of the tabulated inverse CDF sample() interpolates), so a
    /// contribution splatted at a raster position with these weights (SplatBuffer) estimates what camera
    /// samples estimate. ∫ pdf = 1; 0 outside ±support()/2.
    float pdf(float x) const;
    float width() const { return m_width; }
    /// Total extent of the profile in pixels.
    float support() const { return m_support; }

    static const std::vector<std::string>& names();

private:
    enum class Kind { Box, Gaussian, BlackmanHarris };
    Kind m_kind;  // the name, resolved once: sample() runs per camera ray
    float m_width;
    float m_support;
    /// Inverse CDF of the profile over [−width/2, width/2] at k_inverse_size + 1 evenly spaced u, so a
    /// sample is one table lookup with linear interpolation instead of a binary search.
    static constexpr int k_inverse_size = 4096;
    std::vector<float> m_inverse_cdf;
    /// pdf() without a binary search (it runs for every pixel a splat covers, for every light-tracing splat): the
    /// density of each segment of the inverse CDF, and for each of k_pdf_cells equal cells of the support the
    /// segment that holds the cell's left end, from which a short forward scan finds the segment of any x in the
    /// cell — the same segment, and so the same value, as the binary search.
    static constexpr int k_pdf_cells = 2 * k_inverse_size;
    std::vector<float> m_segment_pdf;
    std::vector<uint16_t> m_cell_segment;
    float m_cells_per_unit = 0.f;
    float sample_1d(float u) const;
    float cell_left(int c) const;
    size_t segment_by_search(float x) const;
};

}  // namespace candela
