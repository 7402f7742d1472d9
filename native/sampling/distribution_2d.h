// Piecewise-constant 2-D distribution on [0, 1)² (pbrt's marginal/conditional construction): a row v is
// drawn from the marginal ∝ the rows' integrals, then a column u from that row's conditional. The density of
// (u, v) is weight(cell)/mean weight; cells of zero weight are never drawn.
#pragma once

#include <cstddef>
#include <vector>

#include "core/vec.h"
#include "sampling/distribution_1d.h"

namespace candela {

class Distribution2D {
public:
    Distribution2D() = default;
    /// weights: nv rows of nu non-negative values (row j covers v ∈ [j/nv, (j+1)/nv)).
    Distribution2D(const std::vector<float>& weights, size_t nu, size_t nv);

    size_t nu() const { return m_nu; }
    size_t nv() const { return m_nv; }
    /// Mean weight (the integral of the step function over the unit square); 0 = nothing to sample.
    float integral() const { return m_marginal.integral(); }
    /// Memory its tables take.
    size_t bytes() const {
        size_t b = m_marginal.bytes() + m_rows.capacity() * sizeof(Distribution1D);
        for (const Distribution1D& r : m_rows) b += r.bytes();
        return b;
    }

    /// A point with density pdf(point) (written to *pdf); u in [0, 1)².
    Vec2 sample(Vec2 u, float* pdf) const;
    float pdf(Vec2 p) const;

private:
    size_t m_nu = 0, m_nv = 0;
    std::vector<Distribution1D> m_rows;
    Distribution1D m_marginal;
};

}  // namespace candela
