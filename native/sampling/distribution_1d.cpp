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
    for (size_t i = 0; i < n; ++i) {
        if (!(m_func[i] >= 0.f) || !std::isfinite(m_func[i]))
            throw InvalidScene("distribution weight " + std::to_string(i) + " is negative or not finite");
        running += m_func[i];
        cdf[i + 1] = running;
    }
    m_integral = n ? static_cast<float>(running / n) : 0.f;
    for (size_t i = 1; i <= n; ++i) m_cdf[i] = running > 0.0 ? static_cast<float>(cdf[i] / running) : 0.f;
    if (n) m_cdf[n] = 1.f;
}

size_t Distribution1D::find_bin(float u) const {
    // Largest i with cdf[i] <= u, skipping zero-width bins (cdf[i] == cdf[i+1]).
    const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u);
    size_t i = static_cast<size_t>(std::max<std::ptrdiff_t>(0, (it - m_cdf.begin()) - 1));
    i = std::min(i, m_func.size() - 1);
    while (i > 0 && m_func[i] == 0.f) --i;              // u landed at the right edge of an empty run
    while (i + 1 < m_func.size() && m_func[i] == 0.f) ++i;  // leading empty bins
    return i;
}

size_t Distribution1D::sample_discrete(float u, float* pmf_out, float* u_remapped) const {
    const size_t i = find_bin(u);
    const float width = m_cdf[i + 1] - m_cdf[i];
    if (pmf_out) *pmf_out = pmf(i);
    if (u_remapped) *u_remapped = width > 0.f ? std::min((u - m_cdf[i]) / width, k_one_minus_epsilon) : 0.f;
    return i;
}

float Distribution1D::sample_continuous(float u, float* pdf) const {
    const size_t i = find_bin(u);
    const float width = m_cdf[i + 1] - m_cdf[i];
    const float du = width > 0.f ? (u - m_cdf[i]) / width : 0.f;
    if (pdf) *pdf = m_integral > 0.f ? m_func[i] / m_integral : 0.f;
    return std::min((static_cast<float>(i) + du) / static_cast<float>(size()), k_one_minus_epsilon);
}

}  // namespace candela
