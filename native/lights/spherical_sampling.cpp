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
/// Unit component of v orthogonal to unit w; false if v ∥ w.
bool orthogonal_unit(const D3& v, const D3& w, D3* out) {
    *out = v - w * dotd(v, w);
    return normalize_d(out);
}

}  // namespace

double spherical_triangle_solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    D3 va = d3(a) - d3(p), vb = d3(b) - d3(p), vc = d3(c) - d3(p);
    if (!normalize_d(&va) || !normalize_d(&vb) || !normalize_d(&vc)) return 0.0;
    const double num = std::fabs(dotd(va, crossd(vb, vc)));
    const double den = 1.0 + dotd(va, vb) + dotd(va, vc) + dotd(vb, vc);
    const double omega = 2.0 * std::atan2(num, den);
    return std::isfinite(omega) && omega > 0.0 ? omega : 0.0;
}

SphericalSample sample_spherical_triangle(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, Vec2 u,
                                         double omega) {
    SphericalSample out;
    if (!(omega > 0.0)) omega = spherical_triangle_solid_angle(p, v0, v1, v2);
    if (!(omega > 0.0)) return out;
    D3 a = d3(v0) - d3(p), b = d3(v1) - d3(p), c = d3(v2) - d3(p);
    if (!normalize_d(&a) || !normalize_d(&b) || !normalize_d(&c)) return out;
    // Normals of the great circles through the edges; a zero cross product is a degenerate triangle.
    D3 n_ab = crossd(a, b), n_bc = crossd(b, c), n_ca = crossd(c, a);
    if (!normalize_d(&n_ab) || !normalize_d(&n_bc) || !normalize_d(&n_ca)) return out;
    // The vertex angle α at a is the dihedral angle between its edge planes: its cosine and sine come from the
    // planes' unit normals directly (sin α = |n_ab × −n_ca| ≥ 0 as α ∈ [0, π]); no trigonometric call is needed.
    const D3 m_ca = n_ca * -1.0;
    const double cos_alpha = clamp_d(dotd(n_ab, m_ca), -1.0, 1.0);
    const double sin_alpha = lend(crossd(n_ab, m_ca));

    // Arvo: choose the sub-triangle (a, b, c′) of area u₀·Ω, then a point on the arc b–c′. Ω is the
    // Van Oosterom–Strackee solid angle (what the pdf uses), equal to Girard's excess α + β + γ − π and more
    // accurate than it for small triangles.
    const double a_hat = double(u.x) * omega;
    const double sin_a_hat = std::sin(a_hat), cos_a_hat = std::cos(a_hat);
    const double s = sin_a_hat * cos_alpha - cos_a_hat * sin_alpha;  // sin(Â − α)
    const double t = cos_a_hat * cos_alpha + sin_a_hat * sin_alpha;  // cos(Â − α)
    const double uu = t - cos_alpha;
    const double vv = s + sin_alpha * dotd(a, b);  // cos c = a·b (the arc opposite c)
    const double den = (vv * s + uu * t) * sin_alpha;
    double q = den != 0.0 ? ((vv * t - uu * s) * cos_alpha - vv) / den : 1.0;
    if (!std::isfinite(q)) q = 1.0;
    q = clamp_d(q, -1.0, 1.0);
    D3 c_perp;
    if (!orthogonal_unit(c, a, &c_perp)) return out;
    D3 c_hat = a * q + c_perp * safe_sqrt_d(1.0 - q * q);
    const double z = 1.0 - double(u.y) * (1.0 - dotd(c_hat, b));
    D3 w = b;
    D3 cb_perp;
    if (orthogonal_unit(c_hat, b, &cb_perp)) w = b * z + cb_perp * safe_sqrt_d(1.0 - z * z);
    if (!normalize_d(&w)) return out;
    const float pdf = float(1.0 / omega);
    if (!(pdf > 0.f) || !std::isfinite(pdf)) return out;
    out.w = f3(w);
    out.pdf = pdf;
    return out;
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
    r.o[0] = od.x; r.o[1] = od.y; r.o[2] = od.z;
    r.x[0] = x.x; r.x[1] = x.y; r.x[2] = x.z;
    r.y[0] = y.x; r.y[1] = y.y; r.y[2] = y.z;
    r.z[0] = z.x; r.z[1] = z.y; r.z[2] = z.z;
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
