// Ward's error metric and weights (Ward, Rubinstein & Clear 1988; the course's "Irradiance Caching", docs/
// irradiance_cache.md): a record i predicts the irradiance at a point x with normal n with the error
//
//   ε_i(x, n) = ‖x − x_i‖ / R_i + √(1 − n·n_i),
//
// the first term the change to expect over a distance relative to the distance of the surfaces that make E_i, the
// second the change with a tilted normal. Record i is used at x when its weight w_i = 1/ε_i exceeds 1/a (ε_i < a,
// the user's error a), and the estimate is Σ w_i E_i(x, n) / Σ w_i over the records used. So a record is trusted
// within the sphere of radius a·R_i around x_i (its validity radius), for normals close to n_i.
//
// Ward's further test (Radiance's "in front" test): a record lying in front of x — above x's tangent plane by more
// than a tenth of the validity radius, d_i = (x − x_i)·(n + n_i)/2 < −0.1·a·R_i — is not used: it sits on another
// surface close above x (a shelf over a floor), whose hemisphere sees something else.
#pragma once

#include <cmath>
#include <limits>

#include "core/vec.h"
#include "integrators/irradiance_cache/ic_record.h"

namespace candela {

/// ε_i(x, n).
inline float ic_error(const IcRecord& r, const Vec3& x, const Vec3& n) {
    const float c = 1.f - dot(n, r.n);
    return length(x - r.p) / r.R + std::sqrt(c > 0.f ? c : 0.f);
}

/// w_i = 1/ε_i (infinite at the record itself).
inline float ic_weight(float error) { return error > 0.f ? 1.f / error : std::numeric_limits<float>::infinity(); }

/// Whether the record lies in front of x (see above): then it is not used.
inline bool ic_in_front(const IcRecord& r, const Vec3& x, const Vec3& n, float a) {
    return dot(x - r.p, (n + r.n) * 0.5f) < -0.1f * a * r.R;
}

/// Whether record r is used at (x, n) for error a: w_i > 1/a, i.e. ε_i < a, and not in front.
inline bool ic_usable(const IcRecord& r, const Vec3& x, const Vec3& n, float a, float* error) {
    *error = ic_error(r, x, n);
    return *error < a && !ic_in_front(r, x, n, a);
}

/// The record's irradiance extrapolated to (x, n) by its gradients (Ward & Heckbert 1992, eq. 4's terms):
/// E_c + (n_i × n)·∇_r E_c + (x − x_i)·∇_t E_c, each channel clamped at 0 (an extrapolation past a steep gradient
/// must not give negative light).
inline Color ic_extrapolate(const IcRecord& r, const Vec3& x, const Vec3& n, bool gradients) {
    if (!gradients) return r.E;
    const Vec3 rot = cross(r.n, n), dx = x - r.p;
    Color e;
    for (int c = 0; c < 3; ++c) {
        const float v = r.E[c] + dot(rot, r.grad_r[c]) + dot(dx, r.grad_t[c]);
        e[c] = v > 0.f ? v : 0.f;
    }
    return e;
}

}  // namespace candela
