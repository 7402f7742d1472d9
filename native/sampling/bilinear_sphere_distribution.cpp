#include "sampling/bilinear_sphere_distribution.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/math.h"

namespace candela {

namespace {

/// Position of knot row k of nv texel rows.
double knot_v(size_t k, size_t nv) {
    if (k == 0) return 0.0;
    if (k > nv) return 1.0;
    return (double(k) - 0.5) / double(nv);
}

/// The v-interval from v0 to v0 + w, c = πw, φ0 = π v0: I0(τ) = ∫₀^τ sin(φ0 + c t) dt and I1(τ) = ∫₀^τ t·sin(φ0 + c t)
/// dt, in forms without cancellation for small c.
struct SinMoments {
    double i0, i1;
};
SinMoments sin_moments(double phi0, double c, double tau) {
    const double phi = phi0 + c * tau;
    // cos φ0 − cos φ = 2 sin((φ0 + φ)/2) sin((φ − φ0)/2).
    const double i0 = 2.0 * std::sin(0.5 * (phi0 + phi)) * std::sin(0.5 * c * tau) / c;
    // ∫ t sin = −τ cos φ / c + (sin φ − sin φ0)/c², written as (τ·I0 − ∫₀^τ I0(t) dt) to stay accurate:
    // ∫₀^τ I0(t) dt = (τ cos φ0 − (sin φ − sin φ0)/c)/c.
    const double sin_diff = 2.0 * std::cos(0.5 * (phi0 + phi)) * std::sin(0.5 * c * tau);  // sin φ − sin φ0
    const double i1 = (sin_diff / c - tau * std::cos(phi)) / c;
    return {i0, i1};
}

/// x in [0, 1] with density ∝ (1 − x)·a + x·b (a, b ≥ 0, a + b > 0), for a uniform ξ: the root of the cdf
/// (a·x + (b − a)·x²/2) / ((a + b)/2) = ξ in the form without cancellation.
double invert_linear(double a, double b, double xi) {
    const double d = a + std::sqrt(std::fmax(a * a + xi * (b * b - a * a), 0.0));
    if (!(d > 0.0)) return xi;
    return std::min(std::max(xi * (a + b) / d, 0.0), 1.0);
}

}  // namespace

std::vector<double> BilinearSphereDistribution::row_weights(size_t nv) {
    // Interval k from row k to row k + 1 has mass w·(a·(I0 − I1) + b·I1) at τ = 1.
    std::vector<double> w(nv + 2, 0.0);
    for (size_t k = 0; k + 1 < nv + 2; ++k) {
        const double v0 = knot_v(k, nv), width = knot_v(k + 1, nv) - v0;
        const SinMoments m = sin_moments(k_pi * v0, k_pi * width, 1.0);
        w[k] += width * (m.i0 - m.i1);
        w[k + 1] += width * m.i1;
    }
    return w;
}

BilinearSphereDistribution::BilinearSphereDistribution(std::vector<float> knots, size_t nu, size_t nv)
    : m_nu(nu), m_nv(nv), m_knots(std::move(knots)) {
    const size_t rows = nv + 2;
    if (nu == 0 || nv == 0 || m_knots.size() != nu * rows)
        throw InvalidScene("a bilinear sphere distribution needs nu·(nv + 2) = " + std::to_string(nu * rows) +
                           " knots, got " + std::to_string(m_knots.size()));
    for (float k : m_knots)
        if (!(k >= 0.f) || !std::isfinite(k)) throw InvalidScene("a bilinear sphere distribution needs knots >= 0");
    m_row_cdf.assign(rows * (nu + 1), 0.f);
    m_row_mean.assign(rows, 0.f);
    for (size_t k = 0; k < rows; ++k) {
        const float* g = &m_knots[k * nu];
        float* c = &m_row_cdf[k * (nu + 1)];
        double sum = 0.0;
        for (size_t i = 0; i < nu; ++i) {  // interval i: knot i to knot i + 1 (mod nu), width 1/nu
            sum += 0.5 * (double(g[i]) + double(g[(i + 1) % nu])) / double(nu);
            c[i + 1] = float(sum);
        }
        m_row_mean[k] = float(sum);  // the row's integral over u = the mean of its knots
    }
    m_marginal_cdf.assign(rows, 0.0);
    for (size_t k = 0; k + 1 < rows; ++k) {
        const double v0 = knot_v(k, nv), width = knot_v(k + 1, nv) - v0;
        const SinMoments m = sin_moments(k_pi * v0, k_pi * width, 1.0);
        const double a = m_row_mean[k], b = m_row_mean[k + 1];
        m_marginal_cdf[k + 1] = m_marginal_cdf[k] + width * std::fmax(a * (m.i0 - m.i1) + b * m.i1, 0.0);
    }
    m_integral = m_marginal_cdf.back();
}

Vec2 BilinearSphereDistribution::sample(Vec2 u, float* pdf) const {
    // v: the marginal interval by binary search on its cdf, then (a + (b − a)t)·sin(φ0 + ct) inverted by Newton's
    // method, kept inside a bracket that bisection shrinks when a step leaves it.
    const double target_v = double(u.y) * m_integral;
    size_t k =
        size_t(std::upper_bound(m_marginal_cdf.begin(), m_marginal_cdf.end(), target_v) - m_marginal_cdf.begin());
    k = std::min(std::max(k, size_t(1)), m_nv + 1) - 1;
    while (k > 0 && !(m_marginal_cdf[k + 1] > m_marginal_cdf[k])) --k;  // off empty intervals (u.y = 1 − ε)
    const double v0 = knot_v(k, m_nv), width = knot_v(k + 1, m_nv) - v0, phi0 = k_pi * v0, c = k_pi * width;
    const double a = m_row_mean[k], b = m_row_mean[k + 1];
    const double mass = (m_marginal_cdf[k + 1] - m_marginal_cdf[k]) / width;  // ∫₀¹ (a + (b − a)t) sin dt
    const double target = std::min(std::max(target_v - m_marginal_cdf[k], 0.0) / width, mass);
    // Start: the linear density through the end values of the integrand.
    double t = invert_linear(a * std::sin(phi0), b * std::sin(phi0 + c), mass > 0.0 ? target / mass : 0.0);
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 12; ++it) {
        const SinMoments m = sin_moments(phi0, c, t);
        const double F = a * (m.i0 - m.i1) + b * m.i1 - target;
        if (F > 0.0)
            hi = t;
        else
            lo = t;
        const double f = (a + (b - a) * t) * std::sin(phi0 + c * t);
        double next = f > 0.0 ? t - F / f : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::fabs(next - t) < 1e-9) {
            t = next;
            break;
        }
        t = next;
    }
    t = std::min(std::max(t, 0.0), 1.0);
    const float v = std::min(float(v0 + t * width), k_one_minus_epsilon);

    // u: the conditional of the blended row (1 − t)·g_k + t·g_{k+1}; its cdf is the same blend of the rows' cdfs.
    const float tf = float(t);
    const float* c0 = &m_row_cdf[k * (m_nu + 1)];
    const float* c1 = &m_row_cdf[(k + 1) * (m_nu + 1)];
    const float* g0 = &m_knots[k * m_nu];
    const float* g1 = &m_knots[(k + 1) * m_nu];
    auto cdf = [&](size_t i) { return (1.f - tf) * c0[i] + tf * c1[i]; };
    const float target_u = u.x * cdf(m_nu);
    size_t lo_i = 0, hi_i = m_nu;  // largest i < nu with cdf(i) <= target_u
    while (hi_i - lo_i > 1) {
        const size_t mid = (lo_i + hi_i) / 2;
        if (cdf(mid) <= target_u)
            lo_i = mid;
        else
            hi_i = mid;
    }
    size_t i = lo_i;
    while (i > 0 && !(cdf(i + 1) > cdf(i))) --i;  // off empty intervals
    auto value = [&](size_t j) { return (1.f - tf) * g0[j % m_nu] + tf * g1[j % m_nu]; };
    const float mass_u = cdf(i + 1) - cdf(i);
    const float xi_u = mass_u > 0.f ? clamp((target_u - cdf(i)) / mass_u, 0.f, 1.f) : 0.f;
    float s =
        (float(i) + float(invert_linear(value(i), value(i + 1), xi_u)) + 0.5f) / float(m_nu);  // knot i: (i + ½)/nu
    if (s >= 1.f) s -= 1.f;
    const Vec2 p{std::min(s, k_one_minus_epsilon), v};
    *pdf = this->pdf(p);
    return p;
}

float BilinearSphereDistribution::pdf_over_sin(Vec2 p) const {
    if (!(m_integral > 0.0) || !(p.x >= 0.f && p.x < 1.f && p.y >= 0.f && p.y < 1.f)) return 0.f;
    const float y = p.y * float(m_nv) + 0.5f;  // knot row k sits at y = k for 1 ≤ k ≤ nv
    const size_t k = y < 1.f ? 0 : std::min(size_t(y), m_nv);
    const float v0 = float(knot_v(k, m_nv)), v1 = float(knot_v(k + 1, m_nv));
    const float t = clamp((p.y - v0) / (v1 - v0), 0.f, 1.f);
    float x = p.x * float(m_nu) - 0.5f;  // knot i at x = i, periodic
    if (x < 0.f) x += float(m_nu);
    const size_t i = std::min(size_t(x), m_nu - 1), i1 = (i + 1) % m_nu;
    const float s = clamp(x - float(i), 0.f, 1.f);
    const float* g0 = &m_knots[k * m_nu];
    const float* g1 = &m_knots[(k + 1) * m_nu];
    const float g = (1.f - t) * ((1.f - s) * g0[i] + s * g0[i1]) + t * ((1.f - s) * g1[i] + s * g1[i1]);
    return float(double(g) / m_integral);
}

float BilinearSphereDistribution::pdf(Vec2 p) const { return pdf_over_sin(p) * std::sin(k_pi * p.y); }

}  // namespace candela
