#include "sampling/distribution_1d.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/math.h"

namespace candela {

Distribution1D::Distribution1D(std::vector<float> weights) : m_func(std::move(weights)) {
    const size_t n = m_func.size();
    m_cdf.assign(n + 1, 0.f);
    double running = 0.0;  // double: thousands of lights must not lose small weights to rounding
    std::vector<double> cdf(n + 1, 0.0);
    bool any_zero = false;
    for (size_t i = 0; i < n; ++i) {
        if (!(m_func[i] >= 0.f) || !std::isfinite(m_func[i]))
            throw InvalidScene("distribution weight " + std::to_string(i) + " is negative or not finite");
        running += m_func[i];
        cdf[i + 1] = running;
        any_zero |= m_func[i] == 0.f;
    }
    m_integral = n ? static_cast<float>(running / n) : 0.f;
    for (size_t i = 1; i <= n; ++i) m_cdf[i] = running > 0.0 ? static_cast<float>(cdf[i] / running) : 0.f;
    if (n) m_cdf[n] = 1.f;
    m_pmf.resize(n);
    for (size_t i = 0; i < n; ++i) m_pmf[i] = m_integral > 0.f ? m_func[i] / (m_integral * n) : 0.f;
    if (any_zero) {
        // A search that lands on a zero-width bin: at the right edge of an empty run step back to the last
        // non-zero bin, before the first non-zero bin step forward to it.
        m_resolve.resize(n);
        for (size_t i = 0; i < n; ++i) {
            size_t j = i;
            while (j > 0 && m_func[j] == 0.f) --j;
            while (j + 1 < n && m_func[j] == 0.f) ++j;
            m_resolve[i] = static_cast<uint32_t>(j);
        }
    }
}

size_t Distribution1D::find_bin_binary(float u) const {
    const size_t n = m_func.size();
    return static_cast<size_t>(std::upper_bound(m_cdf.begin() + 1, m_cdf.begin() + n, u) - (m_cdf.begin() + 1));
}

float Distribution1D::remap(float u, size_t i) const {
    const float width = m_cdf[i + 1] - m_cdf[i];
    return width > 0.f ? std::min((u - m_cdf[i]) / width, k_one_minus_epsilon) : 0.f;
}

float Distribution1D::sample_continuous(float u, float* pdf) const {
    const size_t i = find_bin(u);
    const float width = m_cdf[i + 1] - m_cdf[i];
    const float du = width > 0.f ? (u - m_cdf[i]) / width : 0.f;
    if (pdf) *pdf = m_integral > 0.f ? m_func[i] / m_integral : 0.f;
    return std::min((static_cast<float>(i) + du) / static_cast<float>(size()), k_one_minus_epsilon);
}

}  // namespace candela
