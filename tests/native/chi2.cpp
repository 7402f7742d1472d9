#include "chi2.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>

#include "core/math.h"

namespace candela::test {

namespace {

// Series for P(a, x), valid for x < a + 1.
double gamma_p_series(double a, double x) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000; ++n) {
        term *= x / (a + n);
        sum += term;
        if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Continued fraction for Q(a, x) (modified Lentz), valid for x ≥ a + 1.
double gamma_q_fraction(double a, double x) {
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// Adaptive Simpson on [a, b] with the usual Richardson correction.
template <typename F>
double simpson_rec(const F& f, double a, double b, double fa, double fm, double fb, double whole, double eps,
                   int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double diff = left + right - whole;
    if (depth <= 0 || std::fabs(diff) <= 15.0 * eps) return left + right + diff / 15.0;
    return simpson_rec(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
           simpson_rec(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

// Starts from `pieces` equal sub-intervals so that narrow peaks are not missed by the first 3 points.
template <typename F>
double adaptive_simpson(const F& f, double a, double b, double eps, int pieces, int depth) {
    double sum = 0.0;
    const double h = (b - a) / pieces;
    for (int i = 0; i < pieces; ++i) {
        const double x0 = a + i * h, x1 = x0 + h, xm = 0.5 * (x0 + x1);
        const double f0 = f(x0), fm = f(xm), f1 = f(x1);
        const double whole = h / 6.0 * (f0 + 4.0 * fm + f1);
        sum += simpson_rec(f, x0, x1, f0, fm, f1, whole, eps / pieces, depth);
    }
    return sum;
}

Vec3 direction(double cos_t, double phi) {
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    return Vec3(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t));
}

}  // namespace

double regularized_gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
    return gamma_q_fraction(a, x);
}

double chi2_survival(double statistic, int dof) {
    if (dof <= 0) return 1.0;
    return regularized_gamma_q(0.5 * dof, 0.5 * statistic);
}

double sidak_alpha(double alpha, int n) { return 1.0 - std::pow(1.0 - alpha, 1.0 / n); }

std::vector<double> integrate_cells(const DirectionPdf& pdf, const Chi2Config& cfg) {
    std::vector<double> out(size_t(cfg.cos_bins) * cfg.phi_bins);
    const double dz = 2.0 / cfg.cos_bins, dphi = 2.0 * M_PI / cfg.phi_bins;
    const double cell_eps = cfg.integration_eps;
    for (int i = 0; i < cfg.cos_bins; ++i) {
        const double z0 = -1.0 + i * dz, z1 = (i + 1 == cfg.cos_bins) ? 1.0 : z0 + dz;
        for (int j = 0; j < cfg.phi_bins; ++j) {
            const double p0 = j * dphi, p1 = p0 + dphi;
            auto inner = [&](double z) {
                auto g = [&](double phi) { return pdf(direction(z, phi)); };
                return adaptive_simpson(g, p0, p1, cell_eps / dz, cfg.integration_pieces, 10);
            };
            out[size_t(i) * cfg.phi_bins + j] = adaptive_simpson(inner, z0, z1, cell_eps, cfg.integration_pieces, 10);
        }
    }
    return out;
}

Chi2Result chi2_test(const DirectionSampler& sample, const DirectionPdf& pdf, const Chi2Config& cfg) {
    Chi2Result r;
    const size_t cells = size_t(cfg.cos_bins) * cfg.phi_bins;
    r.observed.assign(cells, 0.0);
    std::mt19937_64 rng(cfg.seed);
    auto uniform = [&]() { return float(rng() >> 40) * 0x1p-24f; };  // [0, 1), never 1
    for (uint64_t n = 0; n < cfg.samples; ++n) {
        const Vec2 u{uniform(), uniform()};
        const float uc = uniform();
        Vec3 w;
        if (!sample(u, uc, &w)) continue;
        const float len = length(w);
        if (!(std::fabs(len - 1.f) < 1e-3f)) continue;  // counted as lost: shows up as a deficit
        w = w / len;
        ++r.valid_samples;
        const int ci = std::clamp(int((double(w.z) + 1.0) * 0.5 * cfg.cos_bins), 0, cfg.cos_bins - 1);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0.0) phi += 2.0 * M_PI;
        const int pj = std::clamp(int(phi / (2.0 * M_PI) * cfg.phi_bins), 0, cfg.phi_bins - 1);
        r.observed[size_t(ci) * cfg.phi_bins + pj] += 1.0;
    }
    r.expected = integrate_cells(pdf, cfg);
    for (double& e : r.expected) {
        r.pdf_integral += e;
        e *= double(cfg.samples);
    }

    std::vector<size_t> order(cells);
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return r.expected[a] < r.expected[b]; });
    double pooled_obs = 0.0, pooled_exp = 0.0, stat = 0.0;
    int dof = 0;
    for (size_t c : order) {
        const double o = r.observed[c], e = r.expected[c];
        if (e <= 0.0) {
            if (o > double(cfg.samples) * 1e-5) r.rejected_empty_cell = true;
        } else if (e < cfg.min_expected || (pooled_exp > 0.0 && pooled_exp < cfg.min_expected)) {
            pooled_obs += o;
            pooled_exp += e;
        } else {
            stat += (o - e) * (o - e) / e;
            ++dof;
        }
    }
    if (pooled_exp > 0.0) {
        stat += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++dof;
    }
    dof -= 1;
    r.statistic = stat;
    r.dof = dof;
    r.p_value = r.rejected_empty_cell ? 0.0 : chi2_survival(stat, dof);
    if (!std::isfinite(r.p_value)) r.p_value = 0.0;
    return r;
}

std::string Chi2Result::summary() const {
    std::ostringstream s;
    s << "chi2 = " << statistic << ", dof = " << dof << ", p = " << p_value << ", valid samples = " << valid_samples
      << ", pdf integral = " << pdf_integral << (rejected_empty_cell ? ", samples in a zero-pdf cell" : "");
    return s.str();
}

}  // namespace candela::test
