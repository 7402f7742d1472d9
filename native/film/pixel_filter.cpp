#include "film/pixel_filter.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "sampling/distribution_1d.h"

namespace candela {

const std::vector<std::string>& PixelFilter::names() {
    static const std::vector<std::string> n = {"BOX", "GAUSSIAN", "BLACKMAN_HARRIS"};
    return n;
}

PixelFilter::PixelFilter(const std::string& name, float width)
    : m_kind(name == "GAUSSIAN"          ? Kind::Gaussian
             : name == "BLACKMAN_HARRIS" ? Kind::BlackmanHarris
                                         : Kind::Box),
      m_width(width),
      m_support(width * (name == "GAUSSIAN"          ? 3.f
                         : name == "BLACKMAN_HARRIS" ? 2.f
                                                     : 1.f)) {
    bool known = false;
    for (const auto& n : names()) known |= n == name;
    if (!known) throw InvalidParameter("unknown pixel_filter '" + name + "' (BOX, GAUSSIAN, BLACKMAN_HARRIS)");
    if (!(width > 0.f) || width > 64.f) throw InvalidParameter("filter_width must be in (0, 64] pixels");
    // 1024 bins resolve the profile far below the noise of any practical sample count.
    constexpr int k_bins = 1024;
    std::vector<float> f(k_bins);
    for (int i = 0; i < k_bins; ++i) f[i] = evaluate((float(i) + 0.5f) / k_bins * m_support - 0.5f * m_support);
    const Distribution1D table(std::move(f));
    m_inverse_cdf.resize(k_inverse_size + 1);
    for (int i = 0; i <= k_inverse_size; ++i) {
        const float u = std::min(float(i) / k_inverse_size, k_one_minus_epsilon);
        m_inverse_cdf[i] = (table.sample_continuous(u) - 0.5f) * m_support;
    }
    m_inverse_cdf[k_inverse_size] = 0.5f * m_support;
    // sample_1d maps u ∈ [i, i+1]/N linearly onto [inv[i], inv[i+1]]: density (1/N)/(inv[i+1] − inv[i]) there.
    m_segment_pdf.resize(k_inverse_size);
    for (int i = 0; i < k_inverse_size; ++i) {
        const float w = m_inverse_cdf[i + 1] - m_inverse_cdf[i];
        m_segment_pdf[i] = w > 0.f ? (1.f / k_inverse_size) / w : 0.f;
    }
    m_cells_per_unit = float(k_pdf_cells) / m_support;
    m_cell_segment.resize(k_pdf_cells);
    for (int c = 0; c < k_pdf_cells; ++c) m_cell_segment[c] = uint16_t(segment_by_search(cell_left(c)));
}

float PixelFilter::cell_left(int c) const { return float(c) / m_cells_per_unit - 0.5f * m_support; }

size_t PixelFilter::segment_by_search(float x) const {
    const auto it = std::upper_bound(m_inverse_cdf.begin(), m_inverse_cdf.end(), x);
    return std::min(size_t(std::max<std::ptrdiff_t>(it - m_inverse_cdf.begin() - 1, 0)), size_t(k_inverse_size - 1));
}

float PixelFilter::sample_1d(float u) const {
    const float pos = u * k_inverse_size;
    const int i = std::min(static_cast<int>(pos), k_inverse_size - 1);
    return lerp(pos - float(i), m_inverse_cdf[i], m_inverse_cdf[i + 1]);
}

float PixelFilter::evaluate(float x) const {
    const float half = 0.5f * m_support;
    if (std::fabs(x) > half) return 0.f;
    if (m_kind == Kind::Box) return 1.f;
    if (m_kind == Kind::Gaussian) {
        // Cycles: exp(−2 v²) with v = x·6/support: σ = support/12 = width/4.
        const float v = x * 6.f / m_support;
        return std::exp(-2.f * v * v);
    }
    // Blackman–Harris window over the support (Cycles filter_func_blackman_harris).
    const float v = 2.f * k_pi * (x / m_support + 0.5f);
    return 0.35875f - 0.48829f * std::cos(v) + 0.14128f * std::cos(2.f * v) - 0.01168f * std::cos(3.f * v);
}

float PixelFilter::pdf(float x) const {
    const float half = 0.5f * m_support;
    if (!(std::fabs(x) <= half)) return 0.f;
    if (m_kind == Kind::Box) return 1.f / m_support;
    // The segment i with inv[i] ≤ x < inv[i + 1] (the last one with inv[i] ≤ x, clamped to [0, N − 1], as
    // segment_by_search finds it): from the segment of the left end of the cell before x's (one cell of margin
    // for rounding: that left end is ≤ x, so its segment is ≤ x's), forward while the next knot is ≤ x.
    const int c = std::clamp(int((x + half) * m_cells_per_unit) - 1, 0, k_pdf_cells - 1);
    size_t i = m_cell_segment[size_t(c)];
    while (i + 1 <= size_t(k_inverse_size) && m_inverse_cdf[i + 1] <= x) ++i;
    return m_segment_pdf[std::min(i, size_t(k_inverse_size - 1))];
}

Vec2 PixelFilter::sample(Vec2 u) const {
    if (m_kind == Kind::Box) return {(u.x - 0.5f) * m_support, (u.y - 0.5f) * m_support};
    return {sample_1d(u.x), sample_1d(u.y)};
}

}  // namespace candela
