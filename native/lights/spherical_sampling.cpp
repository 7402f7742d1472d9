#include "lights/spherical_sampling.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "core/math.h"
#include "sampling/warp.h"

namespace candela {
namespace {

constexpr double k_pi_d = 3.14159265358979323846;

struct D3 {
    double x = 0, y = 0, z = 0;
};
D3 d3(const Vec3& v) { return {v.x, v.y, v.z}; }
Vec3 f3(const D3& v) { return Vec3(float(v.x), float(v.y), float(v.z)); }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dotd(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 crossd(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double lend(const D3& a) { return std::sqrt(dotd(a, a)); }
/// Normalises in place; false if the vector is zero or not finite.
bool normalize_d(D3* a) {
    const double l = lend(*a);
    if (!(l > 0.0) || !std::isfinite(l)) return false;
    *a = *a * (1.0 / l);
    return true;
}
double safe_sqrt_d(double v) { return std::sqrt(std::max(v, 0.0)); }
double clamp_d(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
/// Angle between unit vectors without acos's loss of precision near ±1.
double angle_between(const D3& a, const D3& b) {
    if (dotd(a, b) < 0.0) return k_pi_d - 2.0 * std::asin(clamp_d(lend(a + b) * 0.5, 0.0, 1.0));
    return 2.0 * std::asin(clamp_d(lend(a - b) * 0.5, 0.0, 1.0));
}
/// atan z for |z| ≤ tan(π/8): the alternating Taylor series Σ_{k≤8} (−1)^k z^{2k+1}/(2k+1) errs by less than its
/// first omitted term |z|¹⁹/19 ≤ tan(π/8)¹⁹/19 = 2.8e-9, which is ≤ 7e-9 relative to atan z ≥ z(1 − z²/3).
double atan_series(double t) {
    const double z = t * t;
    const double series =
        1.0 +
        z * (-1.0 / 3.0 +
             z * (1.0 / 5.0 +
                  z * (-1.0 / 7.0 +
                       z * (1.0 / 9.0 + z * (-1.0 / 11.0 + z * (1.0 / 13.0 + z * (-1.0 / 15.0 + z * (1.0 / 17.0))))))));
    return t * series;
}

/// atan(n/d) for 0 ≤ n ≤ d, d > 0, with one division. Above tan(π/8) the identity atan t = π/4 + atan((t − 1)/(t + 1))
/// moves the argument into [−tan(π/8), 0], and (t − 1)/(t + 1) = (n − d)/(n + d) is formed from n and d directly
/// (each rounded once, ~1e-16): the series' 2.8e-9 is then ≤ 7.2e-9 relative to a result ≥ π/8.
double atan_ratio(double n, double d) {
    constexpr double k_tan_pi_8 = 0.41421356237309503;  // √2 − 1
    if (n > k_tan_pi_8 * d) return k_pi_d / 4.0 + atan_series((n - d) / (n + d));
    return atan_series(n / d);
}

/// atan2(y, x) ∈ [0, π] for y ≥ 0, with atan_ratio's relative accuracy (π/2 − atan and π − atan of arguments in
/// [0, 1] lose nothing: the subtracted term is at most half the result).
double atan2_upper(double y, double x) {
    const double ax = std::fabs(x);
    double r;
    if (y <= ax)
        r = ax > 0.0 ? atan_ratio(y, ax) : 0.0;
    else
        r = k_pi_d / 2.0 - atan_ratio(ax, y);
    return x < 0.0 ? k_pi_d - r : r;
}

/// sin x and 1 − cos x for x ∈ [0, 2π): Taylor series at g = x/8 (|g| < π/4), then three double-angle steps
/// sin 2g = 2 sin g (1 − (1 − cos g)), 1 − cos 2g = 2 sin²g (1 − cos is never formed by cancellation).
/// Truncation at g ≤ π/4: sin's first omitted term g¹³/13! is 9e-12 of g, 1 − cos's g¹⁴/14! is 1.3e-12 of
/// g²/2; each doubling at most adds the relative errors of its two factors, and the one amplification by
/// cancellation, 1 − (1 − cos g) near 0 for x near 2π (Ω ≤ 6.22), is bounded by 1/cos(6.22/4) < 70: the results
/// stay within ~1e-9 relative — far below the float resolution of the sampled direction.
void sin_one_minus_cos(double x, double* sin_x, double* one_minus_cos_x) {
    const double g = 0.125 * x, g2 = g * g;
    double s =
        g * (1.0 + g2 * (-1.0 / 6.0 +
                         g2 * (1.0 / 120.0 + g2 * (-1.0 / 5040.0 + g2 * (1.0 / 362880.0 + g2 * (-1.0 / 39916800.0))))));
    double m =
        g2 *
        (0.5 + g2 * (-1.0 / 24.0 +
                     g2 * (1.0 / 720.0 + g2 * (-1.0 / 40320.0 + g2 * (1.0 / 3628800.0 + g2 * (-1.0 / 479001600.0))))));
    for (int i = 0; i < 3; ++i) {
        const double s2 = 2.0 * s * (1.0 - m);
        m = 2.0 * s * s;
        s = s2;
    }
    *sin_x = s;
    *one_minus_cos_x = m;
}

}  // namespace

SphericalTriangle SphericalTriangle::make(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    SphericalTriangle st;
    D3 a = d3(v0) - d3(p), b = d3(v1) - d3(p), c = d3(v2) - d3(p);
    if (!normalize_d(&a) || !normalize_d(&b) || !normalize_d(&c)) return st;
    const double triple = dotd(a, crossd(b, c));
    const double den = 1.0 + dotd(a, b) + dotd(a, c) + dotd(b, c);
    const double omega = 2.0 * atan2_upper(std::fabs(triple), den);
    st.a[0] = a.x;
    st.a[1] = a.y;
    st.a[2] = a.z;
    st.b[0] = b.x;
    st.b[1] = b.y;
    st.b[2] = b.z;
    st.c[0] = c.x;
    st.c[1] = c.y;
    st.c[2] = c.z;
    st.triple = triple;
    st.omega = std::isfinite(omega) && omega > 0.0 ? omega : 0.0;
    return st;
}

double spherical_triangle_solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    return SphericalTriangle::make(p, a, b, c).omega;
}

SphericalSample SphericalTriangle::sample(Vec2 u) const {
    SphericalSample out;
    if (!(omega > 0.0)) return out;
    const D3 a{this->a[0], this->a[1], this->a[2]}, b{this->b[0], this->b[1], this->b[2]},
        c{this->c[0], this->c[1], this->c[2]};
    // Normals of the great circles through the edges at a; a zero cross product is a degenerate triangle.
    // (b × c cannot be zero here: it would make the triple product, hence Ω, exactly 0.)
    const D3 n_ab = crossd(a, b), n_ca = crossd(c, a);
    const double l_ab = lend(n_ab), l_ca = lend(n_ca);
    if (!(l_ab > 0.0) || !(l_ca > 0.0) || !std::isfinite(l_ab * l_ca)) return out;
    // The vertex angle α at a is the dihedral angle between its edge planes, α ∈ [0, π]: cos α = n̂_ab·(−n̂_ca),
    // and since (a×b)×(a×c) = a·(a·(b×c)) for unit a, sin α = |a·(b×c)| / (|a×b||c×a|) ≥ 0 — no trigonometry.
    const double inv_l = 1.0 / (l_ab * l_ca);
    const double cos_alpha = clamp_d(-dotd(n_ab, n_ca) * inv_l, -1.0, 1.0);
    const double sin_alpha = std::min(std::fabs(triple) * inv_l, 1.0);

    // Arvo: choose the sub-triangle (a, b, c′) of area Â = u₀·Ω, then a point on the arc b–c′. Ω is the
    // Van Oosterom–Strackee solid angle (what the pdf uses), equal to Girard's excess α + β + γ − π and more
    // accurate than it for small triangles.
    double sin_a_hat, omc_a_hat;
    sin_one_minus_cos(double(u.x) * omega, &sin_a_hat, &omc_a_hat);
    const double cos_a_hat = 1.0 - omc_a_hat;
    const double s = sin_a_hat * cos_alpha - cos_a_hat * sin_alpha;   // sin(Â − α)
    const double t = cos_a_hat * cos_alpha + sin_a_hat * sin_alpha;   // cos(Â − α)
    const double uu = sin_a_hat * sin_alpha - omc_a_hat * cos_alpha;  // t − cos α without the cancellation
    const double vv = s + sin_alpha * dotd(a, b);                     // cos c = a·b (the arc opposite c)
    const double den = (vv * s + uu * t) * sin_alpha;
    double q = den != 0.0 ? ((vv * t - uu * s) * cos_alpha - vv) / den : 1.0;  // cos of the arc a–c′
    if (!std::isfinite(q)) q = 1.0;
    q = clamp_d(q, -1.0, 1.0);
    // Unit tangent at a toward c: |c − (c·a)a| = |c × a|.
    const D3 c_perp = (c - a * dotd(c, a)) * (1.0 / l_ca);
    const D3 c_hat = a * q + c_perp * safe_sqrt_d((1.0 - q) * (1.0 + q));
    // cos θ = z = 1 − u₁(1 − c′·b): uniform in the cosine along the arc b–c′; w = z·b + √(1 − z²)·t̂ with t̂ the
    // unit tangent at b toward c′, t̂ = (c′ − (c′·b)b)/√(1 − (c′·b)²). With k = c′·b, 1 − z² = u₁(1 − k)(1 + z) and
    // 1 − k² = (1 − k)(1 + k), so w = z·b + (c′ − k·b)·√(u₁(1 + z)/(1 + k)): one division and one square root, no
    // cancellation when c′ ≈ b (then w → b), and |w|² = z² + (1 − k)(1 + z)u₁ = z² + (1 − z)(1 + z) = 1 exactly
    // in real arithmetic, so w needs no renormalisation. 1 + k > 0: c′ = −b would need Ω ≥ 2π.
    const double k = dotd(c_hat, b);
    const double one_minus_z = double(u.y) * (1.0 - k);
    const double z = 1.0 - one_minus_z;
    const double scale = safe_sqrt_d(double(u.y) * (1.0 + z) / (1.0 + k));
    const D3 w = b * z + (c_hat - b * k) * scale;
    const float pdf = float(1.0 / omega);
    if (!(pdf > 0.f) || !std::isfinite(pdf) || !std::isfinite(w.x + w.y + w.z)) return out;
    out.w = f3(w);
    out.pdf = pdf;
    return out;
}

SphericalSample sample_spherical_triangle(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, Vec2 u) {
    return SphericalTriangle::make(p, v0, v1, v2).sample(u);
}

SphericalRectangle SphericalRectangle::make(const Vec3& o, const Vec3& s, const Vec3& ex, const Vec3& ey) {
    SphericalRectangle r;
    const D3 od = d3(o);
    D3 x = d3(ex), y = d3(ey);
    const double exl = lend(x), eyl = lend(y);
    if (!normalize_d(&x) || !normalize_d(&y)) return r;
    D3 z = crossd(x, y);
    if (!normalize_d(&z)) return r;
    const D3 d = d3(s) - od;
    double z0 = dotd(d, z);
    if (z0 > 0.0) {
        z = z * -1.0;
        z0 = -z0;
    }
    r.o[0] = od.x;
    r.o[1] = od.y;
    r.o[2] = od.z;
    r.x[0] = x.x;
    r.x[1] = x.y;
    r.x[2] = x.z;
    r.y[0] = y.x;
    r.y[1] = y.y;
    r.y[2] = y.z;
    r.z[0] = z.x;
    r.z[1] = z.y;
    r.z[2] = z.z;
    r.z0 = z0;
    r.x0 = dotd(d, x);
    r.y0 = dotd(d, y);
    r.x1 = r.x0 + exl;
    r.y1 = r.y0 + eyl;
    if (!(z0 < 0.0)) return r;  // the reference point lies in the rectangle's plane
    const D3 v00{r.x0, r.y0, z0}, v01{r.x0, r.y1, z0}, v10{r.x1, r.y0, z0}, v11{r.x1, r.y1, z0};
    D3 n0 = crossd(v00, v10), n1 = crossd(v10, v11), n2 = crossd(v11, v01), n3 = crossd(v01, v00);
    if (!normalize_d(&n0) || !normalize_d(&n1) || !normalize_d(&n2) || !normalize_d(&n3)) return r;
    const double g0 = angle_between(n0 * -1.0, n1), g1 = angle_between(n1 * -1.0, n2);
    const double g2 = angle_between(n2 * -1.0, n3), g3 = angle_between(n3 * -1.0, n0);
    r.b0 = n0.z;
    r.b1 = n2.z;
    r.k = 2.0 * k_pi_d - g2 - g3;
    r.S = g0 + g1 - r.k;
    r.valid = std::isfinite(r.S) && r.S > 0.0;
    const double min_nz2 = std::min(std::min(n0.z * n0.z, n1.z * n1.z), std::min(n2.z * n2.z, n3.z * n3.z));
    r.grazing = min_nz2 > k_spherical_rectangle_grazing_nz2;
    return r;
}

Vec3 SphericalRectangle::sample_point(Vec2 u) const {
    const double au = double(u.x) * S + k;
    const double sin_au = std::sin(au);
    double cu;
    if (sin_au == 0.0) {
        cu = 0.0;
    } else {
        const double fu = (std::cos(au) * b0 - b1) / sin_au;
        cu = (fu > 0.0 ? 1.0 : -1.0) / std::sqrt(fu * fu + b0 * b0);
        if (!std::isfinite(cu)) cu = 0.0;
    }
    cu = clamp_d(cu, -1.0, 1.0);
    double xu = -(cu * z0) / safe_sqrt_d(1.0 - cu * cu);
    if (std::isnan(xu)) xu = x0;
    xu = clamp_d(xu, x0, x1);
    const double dd = std::sqrt(xu * xu + z0 * z0);
    const double h0 = y0 / std::sqrt(dd * dd + y0 * y0), h1 = y1 / std::sqrt(dd * dd + y1 * y1);
    const double hv = h0 + double(u.y) * (h1 - h0), hv2 = hv * hv;
    double yv = hv2 < 1.0 - 1e-12 ? (hv * dd) / std::sqrt(1.0 - hv2) : y1;
    yv = clamp_d(yv, y0, y1);
    return Vec3(float(o[0] + xu * x[0] + yv * y[0] + z0 * z[0]), float(o[1] + xu * x[1] + yv * y[1] + z0 * z[1]),
                float(o[2] + xu * x[2] + yv * y[2] + z0 * z[2]));
}

namespace {

/// sin²θ_max and 1 − cosθ_max of the cone subtended by a sphere seen from outside (Taylor for tiny cones).
struct SphereCone {
    double sin2_max = 0, one_minus_cos_max = 0, dc = 0;
    D3 axis;  // unit, ref → centre
    bool outside = false;
};
SphereCone sphere_cone(const Vec3& ref, const Vec3& center, float radius) {
    SphereCone c;
    c.axis = d3(center) - d3(ref);
    const double dc2 = dotd(c.axis, c.axis), r2 = double(radius) * double(radius);
    if (dc2 <= r2 || !normalize_d(&c.axis)) return c;
    c.outside = true;
    c.dc = std::sqrt(dc2);
    c.sin2_max = r2 / dc2;
    c.one_minus_cos_max = c.sin2_max < k_sphere_taylor_sin2 ? 0.5 * c.sin2_max * (1.0 + 0.25 * c.sin2_max)
                                                            : 1.0 - safe_sqrt_d(1.0 - c.sin2_max);
    return c;
}

}  // namespace

double sphere_solid_angle(const Vec3& ref, const Vec3& center, float radius) {
    const SphereCone c = sphere_cone(ref, center, radius);
    return c.outside ? 2.0 * k_pi_d * c.one_minus_cos_max : 4.0 * k_pi_d;
}

SphereSample sample_sphere(const Vec3& ref, const Vec3& center, float radius, Vec2 u) {
    SphereSample out;
    if (!(radius > 0.f)) return out;
    const SphereCone c = sphere_cone(ref, center, radius);
    if (!c.outside) {
        // Inside or on the sphere: uniform area sampling, p_ω = p_A·d²/|cosθ_l|.
        const Vec3 n = sample_uniform_sphere(u);
        const Vec3 p = center + n * radius;
        Vec3 w = p - ref;
        const float d2 = length_squared(w);
        if (!(d2 > 0.f)) return out;
        const float d = std::sqrt(d2);
        w = w / d;
        const float pdf = d2 / (4.f * k_pi * radius * radius * std::fabs(dot(w, n)));
        if (!(pdf > 0.f) || !std::isfinite(pdf)) return out;
        out.w = w;
        out.p = p;
        out.n = n;
        out.dist = d;
        out.pdf = pdf;
        return out;
    }
    if (!(c.one_minus_cos_max > 0.0)) return out;
    double sin2, cos_t;
    if (c.sin2_max < k_sphere_taylor_sin2) {
        sin2 = c.sin2_max * double(u.x);
        cos_t = std::sqrt(1.0 - sin2);
    } else {
        cos_t = 1.0 - double(u.x) * c.one_minus_cos_max;
        sin2 = std::max(0.0, (1.0 - cos_t) * (1.0 + cos_t));
    }
    // Angle α at the centre between −axis and the surface point hit by the direction (no intersection).
    const double sin_max = std::sqrt(c.sin2_max);
    const double cos_alpha = clamp_d(sin2 / sin_max + cos_t * safe_sqrt_d(1.0 - sin2 / c.sin2_max), -1.0, 1.0);
    const double sin_alpha = safe_sqrt_d(1.0 - cos_alpha * cos_alpha);
    const double phi = 2.0 * k_pi_d * double(u.y);
    const Frame frame(f3(c.axis));
    const D3 e1 = d3(frame.s), e2 = d3(frame.t);
    const D3 tangent = e1 * std::cos(phi) + e2 * std::sin(phi);
    D3 w = c.axis * cos_t + tangent * std::sqrt(sin2);
    if (!normalize_d(&w)) return out;
    D3 n = c.axis * -cos_alpha + tangent * sin_alpha;
    if (!normalize_d(&n)) return out;
    const D3 p = d3(center) + n * double(radius);
    const double dist = lend(p - d3(ref));
    const float pdf = float(1.0 / (2.0 * k_pi_d * c.one_minus_cos_max));
    if (!(pdf > 0.f) || !std::isfinite(pdf) || !(dist > 0.0)) return out;
    out.w = f3(w);
    out.p = f3(p);
    out.n = f3(n);
    out.dist = float(dist);
    out.pdf = pdf;
    return out;
}

float sphere_pdf(const Vec3& ref, const Vec3& center, float radius, const Vec3& wf) {
    if (!(radius > 0.f)) return 0.f;
    const SphereCone c = sphere_cone(ref, center, radius);
    D3 w = d3(wf);
    if (!normalize_d(&w)) return 0.f;
    if (c.outside) {
        const double one_minus_cos = 1.0 - dotd(w, c.axis);
        if (one_minus_cos > c.one_minus_cos_max * (1.0 + 1e-5) + 1e-9) return 0.f;
        const float pdf = float(1.0 / (2.0 * k_pi_d * c.one_minus_cos_max));
        return std::isfinite(pdf) ? pdf : 0.f;
    }
    // Inside: the exit point of the ray, p_ω = t²/(A·|cos|).
    const D3 oc = d3(ref) - d3(center);
    const double b = dotd(oc, w), cc = dotd(oc, oc) - double(radius) * radius;
    const double t = -b + safe_sqrt_d(b * b - cc);
    if (!(t > 0.0)) return 0.f;
    D3 n = oc + w * t;
    if (!normalize_d(&n)) return 0.f;
    const double cos_l = std::fabs(dotd(w, n));
    if (!(cos_l > 1e-9)) return 0.f;
    const float pdf = float(t * t / (4.0 * k_pi_d * double(radius) * radius * cos_l));
    return std::isfinite(pdf) ? pdf : 0.f;
}

}  // namespace candela
