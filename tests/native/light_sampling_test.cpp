// light_pdf = AREA / SOLID_ANGLE: spherical triangles (Arvo 1995), spherical rectangles (Ureña et al. 2013)
// and the sphere cone sampler, checked against area sampling on pbrt-v4's configurations
// (docs/verification.md §5), Lambert's polygon formula and other closed forms (§2.2–§2.5), χ² of every
// light-sampling routine seen from a fixed point, sample pdf == evaluated pdf, and degenerate inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "chi2.h"
#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "lights/light.h"
#include "lights/spherical_sampling.h"
#include "sampling/low_discrepancy.h"

namespace candela {
namespace {

using test::chi2_test;
using test::Chi2Config;
using test::Chi2Result;

// ---- helpers ---------------------------------------------------------------------------------------------

/// Lambert's formula: E/L of a convex polygon above the horizon of (x, n) (docs/verification.md §2.4).
double lambert_polygon(const std::vector<Vec3>& poly, const Vec3& x, const Vec3& n) {
    double sum = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3 a = poly[i] - x, b = poly[(i + 1) % poly.size()] - x;
        double va[3] = {a.x, a.y, a.z}, vb[3] = {b.x, b.y, b.z};
        const double la = std::sqrt(va[0] * va[0] + va[1] * va[1] + va[2] * va[2]);
        const double lb = std::sqrt(vb[0] * vb[0] + vb[1] * vb[1] + vb[2] * vb[2]);
        for (int k = 0; k < 3; ++k) va[k] /= la, vb[k] /= lb;
        const double c = va[0] * vb[0] + va[1] * vb[1] + va[2] * vb[2];
        double u[3] = {va[1] * vb[2] - va[2] * vb[1], va[2] * vb[0] - va[0] * vb[2], va[0] * vb[1] - va[1] * vb[0]};
        const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        sum += std::acos(std::max(-1.0, std::min(1.0, c))) * (u[0] * n.x + u[1] * n.y + u[2] * n.z) / lu;
    }
    return 0.5 * std::fabs(sum);
}

/// Ray–triangle intersection (Möller–Trumbore, double): distance or −1.
double intersect_triangle(const Vec3& o, const Vec3& d, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    const double e1[3] = {double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z};
    const double e2[3] = {double(p2.x) - p0.x, double(p2.y) - p0.y, double(p2.z) - p0.z};
    const double dd[3] = {d.x, d.y, d.z};
    const double pv[3] = {dd[1] * e2[2] - dd[2] * e2[1], dd[2] * e2[0] - dd[0] * e2[2], dd[0] * e2[1] - dd[1] * e2[0]};
    const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (std::fabs(det) < 1e-300) return -1;
    const double tv[3] = {double(o.x) - p0.x, double(o.y) - p0.y, double(o.z) - p0.z};
    const double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    if (u < 0 || u > 1) return -1;
    const double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]};
    const double v = (dd[0] * qv[0] + dd[1] * qv[1] + dd[2] * qv[2]) / det;
    if (v < 0 || u + v > 1) return -1;
    const double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    return t > 0 ? t : -1;
}

TriangleLight make_triangle(Vec3 a, Vec3 b, Vec3 c, float L = 1.f) {
    TriangleLight t;
    t.p0 = a;
    t.p1 = b;
    t.p2 = c;
    const Vec3 n = cross(b - a, c - a);
    t.area = 0.5f * length(n);
    t.normal = normalize(n);
    t.radiance = Color(L);
    return t;
}

AreaLight make_rect(Vec3 center, Vec3 u, Vec3 v, Vec3 normal, float L = 1.f, bool ellipse = false) {
    AreaLight a;
    a.center = center;
    a.u = u;
    a.v = v;
    a.normal = normal;
    a.ellipse = ellipse;
    a.area = length(u) * length(v) * (ellipse ? k_pi / 4.f : 1.f);
    a.radiance = Color(L);
    return a;
}

struct Estimate {
    double mean, se;
};

/// Irradiance (luminance) at ctx from light sampling with `mode`.
Estimate irradiance(const Light& light, const LightSampleContext& ctx, LightPdfMode mode, int n, uint64_t seed = 7) {
    Pcg32 rng(seed, 3);
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const LightSample ls = light_sample_li(light, ctx, {rng.next_float(), rng.next_float()}, mode);
        double v = 0;
        if (ls.valid()) v = luminance(ls.Li) * std::max(0.f, dot(ls.wi, ctx.n)) / ls.pdf;
        s += v;
        s2 += v * v;
    }
    const double m = s / n;
    return {m, std::sqrt(std::max(0.0, s2 / n - m * m) / n)};
}

// ---- spherical triangle / rectangle vs area sampling (pbrt-v4 sampling_test.cpp configurations) ------------

TEST(SphericalTriangle, MatchesAreaSamplingOnPbrtConfiguration) {
    const Vec3 v[3] = {Vec3(4, 1, 1), Vec3(-10, 3, 3), Vec3(-2, -8, 10)};
    const Vec3 p(0.5f, -0.4f, 0.7f);
    auto f = [](double x, double y, double z) { return x * y * z; };
    const Vec3 N = normalize(cross(v[1] - v[0], v[2] - v[0]));
    const double area = 0.5 * length(cross(v[1] - v[0], v[2] - v[0]));
    const uint64_t n = 1024 * 1024;
    double sph = 0, ar = 0;
    for (uint64_t i = 0; i < n; ++i) {
        const Vec2 u{to_unit_float(halton(0, i)), to_unit_float(halton(1, i))};
        const SphericalSample s = sample_spherical_triangle(p, v[0], v[1], v[2], u);
        ASSERT_GT(s.pdf, 0.f);
        const double t = intersect_triangle(p, s.w, v[0], v[1], v[2]);
        // Samples may land a rounding error outside an edge: use the plane intersection.
        const double tp = t > 0 ? t : dot(v[0] - p, N) / dot(s.w, N);
        sph += f(p.x + tp * s.w.x, p.y + tp * s.w.y, p.z + tp * s.w.z) / s.pdf;
        const Vec2 b = sample_uniform_triangle(u);
        const double b0 = b.x, b1 = b.y, b2 = 1.0 - b0 - b1;
        const double q[3] = {b0 * v[0].x + b1 * v[1].x + b2 * v[2].x, b0 * v[0].y + b1 * v[1].y + b2 * v[2].y,
                             b0 * v[0].z + b1 * v[1].z + b2 * v[2].z};
        const double w[3] = {q[0] - p.x, q[1] - p.y, q[2] - p.z};
        const double d2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        const double cosl = std::fabs(w[0] * N.x + w[1] * N.y + w[2] * N.z) / std::sqrt(d2);
        ar += f(q[0], q[1], q[2]) * cosl * area / d2;
    }
    sph /= double(n);
    ar /= double(n);
    std::printf("spherical triangle: %.6f, area: %.6f, |diff| %.2e\n", sph, ar, std::fabs(sph - ar));
    EXPECT_LT(std::fabs(sph - ar), 1e-3);
}

TEST(SphericalRectangle, MatchesAreaSamplingOnPbrtConfiguration) {
    const Vec3 v00(4, 1, 1), v10(6, 1, -2), v01(4, 4, 1);
    const Vec3 p(0.5f, -0.4f, 0.7f);
    const Vec3 ex = v10 - v00, ey = v01 - v00;
    const Vec3 N = normalize(cross(ex, ey));
    const double area = length(ex) * length(ey);
    auto f = [](double x, double y, double z) { return x * y * z; };
    const SphericalRectangle rect = SphericalRectangle::make(p, v00, ex, ey);
    ASSERT_TRUE(rect.usable());
    const uint64_t n = 1024 * 1024;
    double sph = 0, ar = 0;
    for (uint64_t i = 0; i < n; ++i) {
        const Vec2 u{to_unit_float(hammersley(0, i, n)), to_unit_float(hammersley(1, i, n))};
        const Vec3 q = rect.sample_point(u);
        sph += f(q.x, q.y, q.z) / (1.0 / rect.S);
        const double a[3] = {v00.x + u.x * double(ex.x) + u.y * double(ey.x),
                             v00.y + u.x * double(ex.y) + u.y * double(ey.y),
                             v00.z + u.x * double(ex.z) + u.y * double(ey.z)};
        const double w[3] = {a[0] - p.x, a[1] - p.y, a[2] - p.z};
        const double d2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        const double cosl = std::fabs(w[0] * N.x + w[1] * N.y + w[2] * N.z) / std::sqrt(d2);
        ar += f(a[0], a[1], a[2]) * cosl * area / d2;
    }
    sph /= double(n);
    ar /= double(n);
    std::printf("spherical rectangle: %.6f, area: %.6f, |diff| %.2e\n", sph, ar, std::fabs(sph - ar));
    EXPECT_LT(std::fabs(sph - ar), 1e-3);
    // The solid angle agrees with two Van Oosterom–Strackee triangles.
    const double omega =
        spherical_triangle_solid_angle(p, v00, v10, v10 + ey) + spherical_triangle_solid_angle(p, v00, v10 + ey, v01);
    EXPECT_NEAR(rect.S, omega, 1e-6 * omega);
}

TEST(SphericalTriangle, SolidAngleMatchesHitFraction) {
    // Σ 1/pdf over Halton uniform-sphere directions that hit vs the closed form (pbrt-v3 Triangle.SolidAngle).
    Pcg32 rng(5, 9);
    for (int k = 0; k < 20; ++k) {
        Vec3 v[3];
        for (auto& x : v) x = Vec3(rng.next_float() * 20 - 10, rng.next_float() * 20 - 10, rng.next_float() * 20 - 10);
        const Vec3 p(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
        const double omega = spherical_triangle_solid_angle(p, v[0], v[1], v[2]);
        if (omega < 1e-2) continue;
        const int n = 200000;
        int hits = 0;
        for (int i = 0; i < n; ++i) {
            const Vec3 w = sample_uniform_sphere({to_unit_float(halton(0, i)), to_unit_float(halton(1, i))});
            hits += intersect_triangle(p, w, v[0], v[1], v[2]) > 0;
        }
        const double mc = 4 * M_PI * hits / n;
        EXPECT_NEAR(mc, omega, 5 * std::sqrt(4 * M_PI * omega / n) + 1e-3) << k;
    }
}

// ---- closed forms -------------------------------------------------------------------------------------

TEST(SphericalTriangle, LambertUnitRightTriangle) {
    const Light tri = make_triangle(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1));
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    const double exact = lambert_polygon({Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)}, ctx.p, ctx.n);
    EXPECT_NEAR(exact, 0.302300, 1e-6);
    for (LightPdfMode mode : {LightPdfMode::Area, LightPdfMode::SolidAngle}) {
        const Estimate e = irradiance(tri, ctx, mode, 400000);
        std::printf("triangle %s: E/L = %.6f ± %.6f (exact %.6f)\n", light_pdf_mode_name(mode), e.mean, e.se, exact);
        EXPECT_NEAR(e.mean, exact, 5 * e.se + 1e-6);
    }
}

TEST(SphericalRectangle, LambertTwoByTwoSquare) {
    const Light rect = make_rect(Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, -1));
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    const double exact =
        lambert_polygon({Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(-1, 1, 1)}, ctx.p, ctx.n);
    EXPECT_NEAR(exact, 1.740840, 1e-6);
    for (LightPdfMode mode : {LightPdfMode::Area, LightPdfMode::SolidAngle}) {
        const Estimate e = irradiance(rect, ctx, mode, 400000);
        std::printf("2x2 square %s: E/L = %.6f ± %.6f (exact %.6f)\n", light_pdf_mode_name(mode), e.mean, e.se, exact);
        EXPECT_NEAR(e.mean, exact, 5 * e.se + 1e-6);
    }
    // Under a corner (docs/verification.md §2.3): F = 0.138532 → E/L = πF.
    const Light corner = make_rect(Vec3(0.5f, 0.5f, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1));
    const Estimate e = irradiance(corner, ctx, LightPdfMode::SolidAngle, 400000);
    EXPECT_NEAR(e.mean, M_PI * 0.138532, 5 * e.se + 1e-5);
}

TEST(SphericalTriangle, SolidAngleIsNoWorseThanArea) {
    // A large triangle close to the receiver: the case solid-angle sampling exists for. Reports both
    // standard errors; SOLID_ANGLE must not be worse (it is the default).
    const Light tri = make_triangle(Vec3(-3, -2, 0.3f), Vec3(3, -2, 0.3f), Vec3(0, 3, 0.3f));
    const LightSampleContext ctx{Vec3(0.2f, 0.1f, 0.f), Vec3(0, 0, 1)};
    const Estimate a = irradiance(tri, ctx, LightPdfMode::Area, 200000);
    const Estimate s = irradiance(tri, ctx, LightPdfMode::SolidAngle, 200000);
    std::printf("near triangle: AREA %.5f ± %.5f, SOLID_ANGLE %.5f ± %.5f (σ ratio %.2f)\n", a.mean, a.se, s.mean, s.se,
                a.se / s.se);
    EXPECT_LT(s.se, a.se);
    EXPECT_NEAR(a.mean, s.mean, 5 * std::hypot(a.se, s.se));
    const Light rect = make_rect(Vec3(0, 0, 0.25f), Vec3(4, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, -1));
    const Estimate ra = irradiance(rect, ctx, LightPdfMode::Area, 200000);
    const Estimate rs = irradiance(rect, ctx, LightPdfMode::SolidAngle, 200000);
    std::printf("near rectangle: AREA %.5f ± %.5f, SOLID_ANGLE %.5f ± %.5f (σ ratio %.2f)\n", ra.mean, ra.se, rs.mean,
                rs.se, ra.se / rs.se);
    EXPECT_LT(rs.se, ra.se);
    EXPECT_NEAR(ra.mean, rs.mean, 5 * std::hypot(ra.se, rs.se));
}

TEST(SphericalSphere, ConeMatchesClosedForms) {
    // docs/verification.md §2.5: r = 1, d = 2, θ = 0 ⇒ E/L = π/4.
    const Vec3 c(0, 0, 2);
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    auto est = [&](const Vec3& center, float r, const Vec3& p, const Vec3& n, int count) {
        Pcg32 rng(17, 1);
        double s = 0, s2 = 0;
        for (int i = 0; i < count; ++i) {
            const SphereSample ss = sample_sphere(p, center, r, {rng.next_float(), rng.next_float()});
            double v = 0;
            if (ss.pdf > 0.f) {
                EXPECT_TRUE(std::isfinite(ss.pdf) && std::isfinite(ss.dist));
                v = std::max(0.f, dot(ss.w, n)) / ss.pdf;
            }
            s += v;
            s2 += v * v;
        }
        const double m = s / count;
        return Estimate{m, std::sqrt(std::max(0.0, s2 / count - m * m) / count)};
    };
    const Estimate e = est(c, 1.f, ctx.p, ctx.n, 200000);
    EXPECT_NEAR(e.mean, M_PI / 4, 5 * e.se + 1e-6);
    // Tilted receiver, sphere above the horizon: E = π(r/d)²cosθ.
    const Vec3 nt = normalize(Vec3(0.5f, 0, 1));
    const Estimate et = est(c, 1.f, ctx.p, nt, 200000);
    EXPECT_NEAR(et.mean, M_PI / 4 * dot(nt, Vec3(0, 0, 1)), 5 * et.se + 1e-6);
    // Inside the sphere (area fallback): ∫ cos over the hemisphere = π.
    const Estimate ei = est(c, 1.f, Vec3(0.2f, -0.3f, 2.1f), Vec3(0, 0, 1), 400000);
    EXPECT_NEAR(ei.mean, M_PI, 5 * ei.se + 1e-4);
    // Taylor branch: r = 1e-3 at d = 1 (sin²θ_max = 1e-6): E = π·1e-6 relative to 1e-4.
    const Estimate es = est(Vec3(0, 0, 1), 1e-3f, Vec3(0.f), Vec3(0, 0, 1), 10000);
    EXPECT_NEAR(es.mean / (M_PI * 1e-6), 1.0, 1e-4);
    // Solid angle: 1/pdf is the cone's solid angle, exactly, and matches a hit-fraction estimate.
    for (float r : {1.f, 0.5f, 1e-2f, 1e-3f}) {
        const double sin2 = double(r) * r / 4.0;
        const double omega = 2 * M_PI * (1 - std::sqrt(1 - sin2));
        const SphereSample ss = sample_sphere(ctx.p, c, r, {0.3f, 0.7f});
        EXPECT_NEAR(1.0 / ss.pdf, omega, 2e-6 * omega) << r;
        EXPECT_NEAR(sphere_solid_angle(ctx.p, c, r), omega, 1e-9 * omega) << r;
        EXPECT_FLOAT_EQ(sphere_pdf(ctx.p, c, r, ss.w), ss.pdf) << r;
    }
    const int n = 1 << 20;
    int hits = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 w = sample_uniform_sphere({to_unit_float(halton(0, i)), to_unit_float(halton(1, i))});
        hits += sphere_pdf(ctx.p, c, 1.f, w) > 0.f;
    }
    EXPECT_NEAR(4 * M_PI * hits / n, sphere_solid_angle(ctx.p, c, 1.f), 2e-3);
}

// ---- χ²: every light-sampling routine from a fixed point ------------------------------------------------

struct Chi2Case {
    std::string name;
    test::DirectionSampler sample;
    test::DirectionPdf pdf;
};

std::vector<Chi2Case> chi2_cases() {
    std::vector<Chi2Case> out;
    const LightSampleContext ctx{Vec3(0.1f, -0.2f, 0.f), Vec3(0, 0, 1)};
    auto from_light = [ctx](Light light, LightPdfMode mode) {
        return [ctx, light, mode](Vec2 u, float, Vec3* w) {
            const LightSample s = light_sample_li(light, ctx, u, mode);
            if (!s.valid()) return false;
            *w = s.wi;
            return true;
        };
    };
    const TriangleLight tri = make_triangle(Vec3(-1, -0.5f, 0.8f), Vec3(1.5f, -0.3f, 1.2f), Vec3(0.2f, 1.4f, 0.6f));
    for (LightPdfMode mode : {LightPdfMode::Area, LightPdfMode::SolidAngle}) {
        out.push_back({std::string("triangle_") + light_pdf_mode_name(mode), from_light(tri, mode),
                       [ctx, tri, mode](const Vec3& w) {
                           const double t = intersect_triangle(ctx.p, w, tri.p0, tri.p1, tri.p2);
                           return t > 0 ? double(tri.pdf_li(ctx, w, float(t), mode)) : 0.0;
                       }});
    }
    const AreaLight rect = make_rect(Vec3(0.3f, 0.2f, 1.f), Vec3(2.f, 0.f, 0.5f), Vec3(0.f, 1.5f, 0.f),
                                     normalize(cross(Vec3(0.f, 1.5f, 0.f), Vec3(2.f, 0.f, 0.5f))));
    const AreaLight ell =
        make_rect(Vec3(0.3f, 0.2f, 1.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 1.5f, 0.f), Vec3(0, 0, -1), 1.f, true);
    for (const AreaLight& a : {rect, ell})
        for (LightPdfMode mode : {LightPdfMode::Area, LightPdfMode::SolidAngle}) {
            out.push_back({std::string(a.ellipse ? "ellipse_" : "rectangle_") + light_pdf_mode_name(mode),
                           from_light(a, mode), [ctx, a, mode](const Vec3& w) {
                               float t;
                               return a.intersect(ctx.p, w, 0.f, 1e30f, &t) ? double(a.pdf_li(ctx, w, t, mode)) : 0.0;
                           }});
        }
    // Sphere cone (outside, large and small), and inside (area sampling).
    for (auto [center, r] : {std::pair<Vec3, float>{Vec3(0.5f, 0.3f, 1.5f), 1.f},
                             {Vec3(2.5f, 0.3f, 1.5f), 0.6f},
                             {Vec3(0.3f, -0.1f, 0.2f), 1.f}}) {
        out.push_back(
            {"sphere_r" + std::to_string(r) + "_z" + std::to_string(center.z),
             [ctx, center = center, r = r](Vec2 u, float, Vec3* w) {
                 const SphereSample s = sample_sphere(ctx.p, center, r, u);
                 *w = s.w;
                 return s.pdf > 0.f;
             },
             [ctx, center = center, r = r](const Vec3& w) { return double(sphere_pdf(ctx.p, center, r, w)); }});
    }
    // Point light with a radius (a disk facing the point), a soft sun, the world.
    PointLight pl;
    pl.position = Vec3(0.4f, 0.2f, 1.f);
    pl.intensity = Color(1.f);
    pl.radius = 0.6f;
    out.push_back({"point_radius", from_light(pl, LightPdfMode::Area), [ctx, pl](const Vec3& w) {
                       const Vec3 to = pl.position - ctx.p;
                       const Vec3 axis = normalize(to);
                       const float cw = dot(w, axis);
                       if (cw <= 0.f) return 0.0;
                       const float t = dot(to, axis) / cw;
                       const Vec3 q = ctx.p + w * t - pl.position;
                       if (length_squared(q) > pl.radius * pl.radius) return 0.0;
                       return double(area_to_solid_angle(1.f / (k_pi * pl.radius * pl.radius), t * t, cw));
                   }});
    SunLight sun;
    sun.to_sun = normalize(Vec3(0.3f, 0.2f, 1.f));
    sun.irradiance = Color(1.f);
    sun.tan_half_angle = std::tan(0.5f);
    out.push_back({"sun_angle", from_light(sun, LightPdfMode::Area), [sun](const Vec3& w) {
                       const float c = dot(w, sun.to_sun);
                       if (c <= 0.f) return 0.0;
                       const float tan2 = (1.f - c * c) / (c * c);
                       if (tan2 > sun.tan_half_angle * sun.tan_half_angle) return 0.0;
                       return 1.0 / (M_PI * sun.tan_half_angle * sun.tan_half_angle) / (double(c) * c * c);
                   }});
    WorldLight world;
    world.radiance = Color(1.f);
    out.push_back({"world", from_light(world, LightPdfMode::Area), [](const Vec3&) { return double(k_inv_four_pi); }});
    return out;
}

TEST(LightSamplingChi2, EveryRoutineMatchesItsPdf) {
    const auto cases = chi2_cases();
    const double alpha = test::sidak_alpha(0.01, int(cases.size()));
    for (size_t i = 0; i < cases.size(); ++i) {
        Chi2Config cfg;
        cfg.samples = 500000;
        cfg.seed = 40 + i;
        cfg.integration_pieces = 8;
        const Chi2Result r = chi2_test(cases[i].sample, cases[i].pdf, cfg);
        std::printf("chi2 %-24s p = %.4f  dof %d  ∫pdf = %.5f\n", cases[i].name.c_str(), r.p_value, r.dof,
                    r.pdf_integral);
        EXPECT_GT(r.p_value, alpha) << cases[i].name << ": " << r.summary();
        EXPECT_NEAR(r.pdf_integral, 1.0, 2e-3) << cases[i].name;
    }
}

// ---- pdf consistency and degenerate inputs -----------------------------------------------------------------

void check_sample(const Light& light, const LightSampleContext& ctx, Vec2 u, LightPdfMode mode,
                  const std::string& what) {
    const LightSample s = light_sample_li(light, ctx, u, mode);
    ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.f) << what;
    if (!s.valid()) return;
    ASSERT_TRUE(is_finite(s.Li) && is_finite(s.wi) && std::isfinite(s.dist) && s.dist > 0.f) << what;
    ASSERT_NEAR(length(s.wi), 1.f, 1e-4f) << what;
    const float pdf = light_pdf_li(light, ctx, s.wi, s.dist, mode);
    ASSERT_TRUE(std::isfinite(pdf)) << what;
    ASSERT_NEAR(pdf, s.pdf, 1e-4f * s.pdf) << what;
}

TEST(LightSamplingPdf, SampledPdfEqualsEvaluatedPdf) {
    Pcg32 rng(23, 4);
    auto rnd = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    int spherical = 0;
    for (int k = 0; k < 200; ++k) {
        const Vec3 a(rnd(-3, 3), rnd(-3, 3), rnd(-3, 3)), b(rnd(-3, 3), rnd(-3, 3), rnd(-3, 3)),
            c(rnd(-3, 3), rnd(-3, 3), rnd(-3, 3));
        const TriangleLight tri = make_triangle(a, b, c);
        const Vec3 e1 = normalize(Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)));
        const Vec3 e2 = normalize(cross(e1, Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1))));
        const AreaLight rect = make_rect(a, e1 * rnd(0.1f, 3), e2 * rnd(0.1f, 3), normalize(cross(e2, e1)));
        const LightSampleContext ctx{Vec3(rnd(-2, 2), rnd(-2, 2), rnd(-2, 2)),
                                     normalize(Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)))};
        spherical += tri.uses_spherical_sampling(ctx.p);
        for (int i = 0; i < 50; ++i) {
            const Vec2 u{rng.next_float(), rng.next_float()};
            for (LightPdfMode mode : {LightPdfMode::Area, LightPdfMode::SolidAngle}) {
                check_sample(tri, ctx, u, mode, "triangle " + std::to_string(k));
                check_sample(rect, ctx, u, mode, "rect " + std::to_string(k));
                if (mode == LightPdfMode::SolidAngle) {  // exact equality in the spherical branches
                    const LightSample s = tri.sample_li(ctx, u, mode);
                    if (s.valid() && tri.uses_spherical_sampling(ctx.p)) {
                        EXPECT_EQ(tri.pdf_li(ctx, s.wi, s.dist, mode), s.pdf);
                    }
                    const LightSample r = rect.sample_li(ctx, u, mode);
                    if (r.valid()) {
                        EXPECT_EQ(rect.pdf_li(ctx, r.wi, r.dist, mode), r.pdf);
                    }
                }
            }
        }
    }
    EXPECT_GT(spherical, 100);
}

TEST(LightSamplingPdf, DegenerateConfigurationsStayFinite) {
    const float one_minus = k_one_minus_epsilon;
    const std::vector<Vec2> us = {{0, 0},       {0, one_minus}, {one_minus, 0}, {one_minus, one_minus},
                                  {0.5f, 0.5f}, {1e-7f, 0.5f},  {0.5f, 1e-7f},  {0.25f, 0.75f}};
    std::vector<std::pair<std::string, Light>> lights;
    // Tiny (1e-6) triangle, near-hemisphere triangles either side of 6.22 sr, a sliver.
    lights.push_back({"tiny", make_triangle(Vec3(0, 0, 1), Vec3(1e-6f, 0, 1), Vec3(0, 1e-6f, 1))});
    lights.push_back({"huge", make_triangle(Vec3(-1e4f, -1e4f, 1), Vec3(1e4f, -1e4f, 1), Vec3(0, 1e4f, 1))});
    lights.push_back({"large", make_triangle(Vec3(-60, -60, 1), Vec3(60, -60, 1), Vec3(0, 60, 1))});
    lights.push_back({"sliver", make_triangle(Vec3(-1, 0, 1), Vec3(1, 0, 1), Vec3(0, 1e-5f, 1))});
    lights.push_back({"rect_tiny", make_rect(Vec3(0, 0, 1), Vec3(1e-5f, 0, 0), Vec3(0, 1e-5f, 0), Vec3(0, 0, -1))});
    lights.push_back({"rect_huge", make_rect(Vec3(0, 0, 1), Vec3(1e4f, 0, 0), Vec3(0, 1e4f, 0), Vec3(0, 0, -1))});
    lights.push_back({"rect_thin", make_rect(Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(0, 1e-6f, 0), Vec3(0, 0, -1))});
    const std::vector<std::pair<std::string, LightSampleContext>> points = {
        {"below", {Vec3(0.1f, 0.1f, 0), Vec3(0, 0, 1)}},
        {"on_plane_inside", {Vec3(1e-7f, 1e-7f, 1), Vec3(0, 0, 1)}},
        {"on_plane_outside", {Vec3(5, 5, 1), Vec3(0, 0, 1)}},
        {"grazing", {Vec3(30, 0.2f, 1 - 1e-4f), Vec3(0, 0, 1)}},
        {"grazing_far", {Vec3(1e3f, 0, 1 - 1e-3f), Vec3(0, 0, 1)}},
        {"above", {Vec3(0.1f, 0.2f, 2), Vec3(0, 0, -1)}},
        {"at_vertex", {Vec3(0, 0, 1), Vec3(0, 0, 1)}},
        {"medium", {Vec3(0.3f, 0.1f, 0.5f), Vec3(0.f)}},
    };
    for (const auto& [ln, light] : lights)
        for (const auto& [pn, ctx] : points)
            for (Vec2 u : us)
                for (LightPdfMode mode : {LightPdfMode::Area, LightPdfMode::SolidAngle})
                    check_sample(light, ctx, u, mode, ln + "/" + pn + "/" + light_pdf_mode_name(mode));
    // Branch thresholds: the huge triangle (Ω > 6.22) falls back to area, the "large" one samples spherically.
    float omega;
    EXPECT_FALSE(std::get<TriangleLight>(lights[1].second).uses_spherical_sampling(Vec3(0.f), &omega));
    EXPECT_GT(omega, 6.22f);
    EXPECT_TRUE(std::get<TriangleLight>(lights[2].second).uses_spherical_sampling(Vec3(0.f), &omega));
    EXPECT_FALSE(std::get<TriangleLight>(lights[0].second).uses_spherical_sampling(Vec3(0.f)));
    // Grazing rectangles fall back to area sampling; the point in the plane gets no sample and no NaN.
    const AreaLight& r = std::get<AreaLight>(lights[5].second);
    EXPECT_FALSE(r.spherical_rectangle(Vec3(2e4f, 0, 1 - 1e-3f)).usable());
    // Sphere: tiny, huge, on the surface, at the centre.
    for (auto [center, radius, p] : {std::tuple<Vec3, float, Vec3>{Vec3(0, 0, 1), 1e-6f, Vec3(0.f)},
                                     {Vec3(0, 0, 1e4f), 1e-3f, Vec3(0.f)},
                                     {Vec3(0, 0, 2), 1.f, Vec3(0, 0, 1)},
                                     {Vec3(0, 0, 2), 1.f, Vec3(0, 0, 2)},
                                     {Vec3(0, 0, 1.0001f), 1.f, Vec3(0.f)}})
        for (Vec2 u : us) {
            const SphereSample s = sample_sphere(p, center, radius, u);
            ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.f);
            if (s.pdf > 0.f) {
                ASSERT_TRUE(is_finite(s.w) && is_finite(s.p) && std::isfinite(s.dist));
            }
            ASSERT_TRUE(std::isfinite(sphere_pdf(p, center, radius, s.w)));
        }
}

TEST(LightSamplingPdf, LightSetUsesItsMode) {
    LightSet set;
    set.add(make_triangle(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)));
    set.finalize(10.f);
    EXPECT_EQ(set.pdf_mode(), LightPdfMode::SolidAngle);
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    const LightSample s = set.sample_li(0, ctx, {0.3f, 0.6f});
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(set.pdf_li(0, ctx, s.wi, s.dist), s.pdf);
    EXPECT_FLOAT_EQ(s.pdf,
                    float(1.0 / spherical_triangle_solid_angle(ctx.p, Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1))));
    set.set_pdf_mode(parse_light_pdf_mode("AREA"));
    const LightSample a = set.sample_li(0, ctx, {0.3f, 0.6f});
    EXPECT_NEAR(set.pdf_li(0, ctx, a.wi, a.dist), a.pdf, 1e-5f * a.pdf);
    EXPECT_THROW(parse_light_pdf_mode("BOGUS"), InvalidScene);
}

}  // namespace
}  // namespace candela
