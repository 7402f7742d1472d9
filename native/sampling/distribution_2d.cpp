#include "sampling/distribution_2d.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/math.h"

namespace candela {

Distribution2D::Distribution2D(const std::vector<float>& weights, size_t nu, size_t nv) : m_nu(nu), m_nv(nv) {
    if (nu == 0 || nv == 0 || weights.size() != nu * nv)
        throw InvalidScene("a 2-D distribution needs nu·nv = " + std::to_string(nu * nv) + " weights, got " +
                           std::to_string(weights.size()));
    m_rows.reserve(nv);
    std::vector<float> row_integrals(nv);
    for (size_t j = 0; j < nv; ++j) {
        m_rows.emplace_back(std::vector<float>(weights.begin() + j * nu, weights.begin() + (j + 1) * nu));
        row_integrals[j] = m_rows.back().integral();
    }
    m_marginal = Distribution1D(std::move(row_integrals));
}

Vec2 Distribution2D::sample(Vec2 u, float* pdf) const {
    float pmf_row = 0.f, pmf_col = 0.f, rv = 0.f, ru = 0.f;
    const size_t row = m_marginal.sample_discrete(u.y, &pmf_row, &rv);
    const size_t col = m_rows[row].sample_discrete(u.x, &pmf_col, &ru);
    *pdf = pmf_row * pmf_col * float(m_nu * m_nv);
    return {std::min((float(col) + ru) / float(m_nu), k_one_minus_epsilon),
            std::min((float(row) + rv) / float(m_nv), k_one_minus_epsilon)};
}

float Distribution2D::pdf(Vec2 p) const {
    if (!(p.x >= 0.f && p.x < 1.f && p.y >= 0.f && p.y < 1.f)) return 0.f;
    const size_t row = std::min(size_t(p.y * float(m_nv)), m_nv - 1);
    const size_t col = std::min(size_t(p.x * float(m_nu)), m_nu - 1);
    return m_marginal.pmf(row) * m_rows[row].pmf(col) * float(m_nu * m_nv);
}

}  // namespace candela
