#include "integrators/irradiance_cache/ic_hemisphere.h"

#include <algorithm>
#include <limits>

#include "core/math.h"

namespace candela {

GatherStrata GatherStrata::for_rays(int rays) {
    GatherStrata s;
    s.M = std::max(1, int(std::lround(std::sqrt(double(std::max(rays, 1)) / double(k_pi)))));
    s.N = std::max(1, int(std::lround(double(std::max(rays, 1)) / double(s.M))));
    return s;
}

Vec3 gather_direction(const GatherStrata& s, int j, int k, float u1, float u2) {
    const float sin2 = (float(j) + u1) / float(s.M);
    const float phi = 2.f * k_pi * (float(k) + u2) / float(s.N);
    const float sin_t = std::sqrt(sin2), cos_t = std::sqrt(std::max(0.f, 1.f - sin2));
    return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

GatherEstimate estimate_gather(const HemisphereSamples& s) {
    const int M = s.strata.M, N = s.strata.N;
    GatherEstimate g;
    const double scale = double(k_pi) / double(M * N);
    double E[3] = {0, 0, 0}, inv_r = 0.0;
    double gr[3][2] = {};
    const double dphi = 2.0 * double(k_pi) / double(N);
    for (int j = 0; j < M; ++j) {
        // ∫ over row j of sin²θ dθ (the polar part of ∫ (n × ω) dω over a cell; θ/2 − sin 2θ/4 at the bounds).
        const double t_lo = std::asin(std::sqrt(double(j) / M)), t_hi = std::asin(std::sqrt(double(j + 1) / M));
        const double polar = 0.5 * (t_hi - t_lo) - 0.25 * (std::sin(2.0 * t_hi) - std::sin(2.0 * t_lo));
        for (int k = 0; k < N; ++k) {
            const size_t i = size_t(j * N + k);
            const Color& L = s.L[i];
            if (std::isfinite(s.r[i]) && s.r[i] > 0.f) inv_r += 1.0 / double(s.r[i]);
            // The azimuthal part: ∫ (−sin φ, cos φ) dφ over the column.
            const double p0 = dphi * k, p1 = dphi * (k + 1);
            const double ax = polar * (std::cos(p1) - std::cos(p0)), ay = polar * (std::sin(p1) - std::sin(p0));
            for (int c = 0; c < 3; ++c) {
                E[c] += double(L[c]);
                gr[c][0] += ax * double(L[c]);
                gr[c][1] += ay * double(L[c]);
            }
        }
    }
    for (int c = 0; c < 3; ++c) {
        g.E[c] = float(scale * E[c]);
        g.grad_r[c] = Vec3(float(gr[c][0]), float(gr[c][1]), 0.f);
    }
    if (inv_r > 0.0) g.R = float(double(M * N) / inv_r);

    // Translational gradient (Ward & Heckbert 1992).
    auto at = [&](int j, int k) { return size_t(j * N + ((k + N) % N)); };
    auto inv_min = [&](size_t a, size_t b) {
        const float r = std::min(s.r[a], s.r[b]);
        return std::isfinite(r) && r > 0.f ? 1.0 / double(r) : 0.0;
    };
    double gt[3][3] = {};
    for (int k = 0; k < N; ++k) {
        const double phi_c = dphi * (double(k) + 0.5), phi_b = dphi * double(k);
        const double ux = std::cos(phi_c), uy = std::sin(phi_c);   // u_k
        const double vx = -std::sin(phi_b), vy = std::cos(phi_b);  // v_k⁻
        for (int j = 0; j < M; ++j) {
            const double sin_lo = std::sqrt(double(j) / M), sin_hi = std::sqrt(double(j + 1) / M);
            const size_t here = at(j, k);
            if (j > 0) {  // boundary with the row above (smaller θ) in this column
                const double cos2_lo = 1.0 - double(j) / M;
                const double w = dphi * sin_lo * cos2_lo * inv_min(here, at(j - 1, k));
                if (w != 0.0)
                    for (int c = 0; c < 3; ++c) {
                        const double d = w * (double(s.L[here][c]) - double(s.L[at(j - 1, k)][c]));
                        gt[c][0] += ux * d;
                        gt[c][1] += uy * d;
                    }
            }
            if (N > 1) {  // boundary with the previous column in this row
                const double w = (sin_hi - sin_lo) * inv_min(here, at(j, k - 1));
                if (w != 0.0)
                    for (int c = 0; c < 3; ++c) {
                        const double d = w * (double(s.L[here][c]) - double(s.L[at(j, k - 1)][c]));
                        gt[c][0] += vx * d;
                        gt[c][1] += vy * d;
                    }
            }
        }
    }
    for (int c = 0; c < 3; ++c) g.grad_t[c] = Vec3(float(gt[c][0]), float(gt[c][1]), 0.f);
    return g;
}

IcRecord record_from_gather(GatherEstimate est, const Vec3& p, const Frame& frame, const RecordRules& rules) {
    gradients_to_world(frame, est);
    IcRecord rec;
    rec.p = p;
    rec.n = frame.n;
    rec.E = est.E;
    for (int c = 0; c < 3; ++c) {
        rec.grad_r[c] = est.grad_r[c];
        rec.grad_t[c] = est.grad_t[c];
    }
    float R = std::fmin(est.R, rules.max_R);
    // The gradient limit (Křivánek et al.): over the validity radius a·R the translational term may change E by at
    // most a·E. Near a concave edge a gather ray meets the other face at a tiny distance and Ward & Heckbert's
    // 1/min(r) makes the gradient large and noisy; extrapolated over a radius set by the other rays it would make
    // bright or dark blotches.
    const Vec3 g_lum = rec.grad_t[0] * 0.2126f + rec.grad_t[1] * 0.7152f + rec.grad_t[2] * 0.0722f;
    const float g = length(g_lum), e = luminance(rec.E);
    if (rules.gradients && g > 0.f) R = std::fmin(R, e / g);
    rec.R_min = 0.f;
    if (rules.footprint > 0.f && std::isfinite(rules.footprint)) {
        rec.R_min = rules.min_spacing * rules.footprint / rules.a;
        R = std::fmin(std::fmax(R, rec.R_min), rules.max_spacing * rules.footprint / rules.a);
    }
    // Where the minimum spacing keeps R above the limit, the gradient is scaled down to it instead.
    if (rules.gradients && g * R > e) {
        const float scale = g > 0.f && R > 0.f ? e / (g * R) : 0.f;
        for (int c = 0; c < 3; ++c) rec.grad_t[c] *= scale;
    }
    rec.R = R;
    return rec;
}

}  // namespace candela
