// The fast paths of next-event estimation against the straightforward implementations they replaced
// (the project's previous code, kept here as references): they must compute the same maps and densities.
//   - Distribution1D: linear count for small tables, tabulated pmf and zero-bin remap ≡ std::upper_bound plus
//     the zero-bin loops and the per-call division — bit for bit;
//   - the concentric disk's polynomial sin/cos ≡ std::cos/std::sin to float rounding;
//   - the spherical triangle's series atan2 and sin/(1 − cos) ≡ libm's double functions to their derived bounds;
//   - TriangleLight::prepare()'s cached longest edge ≡ the per-call one, to rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "lights/light.h"
#include "lights/spherical_sampling.h"
#include "sampling/distribution_1d.h"
#include "sampling/warp.h"

namespace candela {
namespace {

// ---- Distribution1D --------------------------------------------------------------------------------------

/// The previous Distribution1D search: cdf as the constructor builds it, std::upper_bound, zero-bin loops.
struct ReferenceDistribution {
    std::vector<float> func, cdf;
    float integral = 0.f;
    explicit ReferenceDistribution(const std::vector<float>& w) : func(w) {
        const size_t n = w.size();
        cdf.assign(n + 1, 0.f);
        std::vector<double> c(n + 1, 0.0);
        double running = 0.0;
        for (size_t i = 0; i < n; ++i) c[i + 1] = running += w[i];
        integral = float(running / n);
        for (size_t i = 1; i <= n; ++i) cdf[i] = float(c[i] / running);
        cdf[n] = 1.f;
    }
    size_t find(float u) const {
        const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
        size_t i = size_t(std::max<std::ptrdiff_t>(0, (it - cdf.begin()) - 1));
        i = std::min(i, func.size() - 1);
        while (i > 0 && func[i] == 0.f) --i;
        while (i + 1 < func.size() && func[i] == 0.f) ++i;
        return i;
    }
    float pmf(size_t i) const { return func[i] / (integral * func.size()); }
};

TEST(FastDistribution1D, SearchAndPmfMatchTheReferenceBitForBit) {
    // Table sizes on both sides of the linear-search limit, with zero runs at the start, middle and end, and
    // u at every cdf value, one ulp either side of it, 0, 1 − ε and 1, plus random u.
    Pcg32 rng(11, 3);
    int checked = 0;
    for (size_t n : {size_t(1), size_t(2), size_t(3), size_t(7), size_t(8), size_t(9), size_t(17), size_t(100)}) {
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<float> w(n);
            for (float& x : w) x = rng.next_float() < 0.3f ? 0.f : rng.next_float() * 10.f;
            if (trial % 4 == 0) w[0] = 0.f;
            if (trial % 4 == 1) w[n - 1] = 0.f;
            if (trial % 5 == 2) w[n / 2] = 1e-12f;  // a bin too thin for the float cdf
            bool any = false;
            for (float x : w) any |= x > 0.f;
            if (!any) w[n / 2] = 1.f;
            const Distribution1D d(w);
            const ReferenceDistribution ref(w);
            std::vector<float> us = {0.f, k_one_minus_epsilon, 1.f};
            for (float c : ref.cdf) {
                us.push_back(c);
                us.push_back(std::nextafter(c, 0.f));
                us.push_back(std::nextafter(c, 1.f));
            }
            for (int k = 0; k < 200; ++k) us.push_back(rng.next_float());
            for (float u : us) {
                if (u < 0.f) continue;
                float pmf = -1.f;
                const size_t i = d.sample_discrete(u, &pmf);
                ASSERT_EQ(i, ref.find(u)) << "n " << n << " u " << u;
                ASSERT_EQ(pmf, ref.pmf(i)) << "n " << n << " u " << u;
                ASSERT_GT(w[i], 0.f);
                ++checked;
            }
            for (size_t i = 0; i < n; ++i) ASSERT_EQ(d.pmf(i), ref.pmf(i));
        }
    }
    EXPECT_GT(checked, 10000);
}

// ---- concentric disk ---------------------------------------------------------------------------------------

Vec2 reference_concentric(Vec2 u) {
    const float ox = 2.f * u.x - 1.f, oy = 2.f * u.y - 1.f;
    if (ox == 0.f && oy == 0.f) return {0.f, 0.f};
    float r, theta;
    if (std::fabs(ox) > std::fabs(oy)) {
        r = ox;
        theta = (k_pi / 4.f) * (oy / ox);
    } else {
        r = oy;
        theta = (k_pi / 2.f) - (k_pi / 4.f) * (ox / oy);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}

TEST(FastWarp, ConcentricDiskMatchesLibmSinCos) {
    // Both compute r·(cos θ, sin θ) with |r| ≤ 1. The reference rounds θ = π/2 − φ (up to 3π/4, half an ulp
    // = 1.2e-7, moving its result by as much) and calls libm (≤ 1 ulp = 6e-8); the fast path uses cos θ = sin φ
    // etc. with a series whose truncation is < 2e-9 (warp.h) and Horner rounding ≤ 2 ulps (1.2e-7); each side
    // then rounds r·(…) (3e-8). Bound: 1.2e-7 + 6e-8 + 1.2e-7 + 6e-8 = 3.6e-7 per component; a wrong sign or
    // coefficient moves points by ≫ 1e-6.
    Pcg32 rng(7, 1);
    float worst = 0.f;
    for (int i = 0; i < 200000; ++i) {
        const Vec2 u{rng.next_float(), rng.next_float()};
        const Vec2 a = sample_uniform_disk_concentric(u), b = reference_concentric(u);
        worst = std::max({worst, std::fabs(a.x - b.x), std::fabs(a.y - b.y)});
    }
    for (Vec2 u : {Vec2{0.5f, 0.5f}, Vec2{0.f, 0.f}, Vec2{k_one_minus_epsilon, k_one_minus_epsilon}, Vec2{0.f, 0.5f},
                   Vec2{0.5f, k_one_minus_epsilon}, Vec2{0.75f, 0.75f}}) {
        const Vec2 a = sample_uniform_disk_concentric(u), b = reference_concentric(u);
        worst = std::max({worst, std::fabs(a.x - b.x), std::fabs(a.y - b.y)});
        EXPECT_LE(a.x * a.x + a.y * a.y, 1.f + 3e-7f);
    }
    std::printf("concentric disk: max |fast − libm| = %.3g\n", worst);
    EXPECT_LE(worst, 3.6e-7f);
}

// ---- spherical triangle ------------------------------------------------------------------------------------

struct D3 {
    double x, y, z;
};
D3 sub(const Vec3& a, const Vec3& b) { return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot3(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross3(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return a * (1.0 / std::sqrt(dot3(a, a))); }

/// Van Oosterom–Strackee with libm's atan2.
double reference_solid_angle(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    const D3 a = unit(sub(v0, p)), b = unit(sub(v1, p)), c = unit(sub(v2, p));
    return 2.0 * std::atan2(std::fabs(dot3(a, cross3(b, c))), 1.0 + dot3(a, b) + dot3(a, c) + dot3(b, c));
}

/// The previous Arvo sampler (libm sin/cos, the same Ω).
bool reference_arvo(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, Vec2 u, double omega, D3* w) {
    const D3 a = unit(sub(v0, p)), b = unit(sub(v1, p)), c = unit(sub(v2, p));
    const D3 n_ab = unit(cross3(a, b)), m_ca = unit(cross3(c, a)) * -1.0;
    const double cos_alpha = std::clamp(dot3(n_ab, m_ca), -1.0, 1.0);
    const D3 x = cross3(n_ab, m_ca);
    const double sin_alpha = std::sqrt(dot3(x, x));
    const double a_hat = double(u.x) * omega;
    const double s = std::sin(a_hat) * cos_alpha - std::cos(a_hat) * sin_alpha;
    const double t = std::cos(a_hat) * cos_alpha + std::sin(a_hat) * sin_alpha;
    const double uu = t - cos_alpha, vv = s + sin_alpha * dot3(a, b);
    const double den = (vv * s + uu * t) * sin_alpha;
    const double q = std::clamp(den != 0.0 ? ((vv * t - uu * s) * cos_alpha - vv) / den : 1.0, -1.0, 1.0);
    const D3 c_hat = a * q + unit(c - a * dot3(c, a)) * std::sqrt(std::max(0.0, 1.0 - q * q));
    const double z = 1.0 - double(u.y) * (1.0 - dot3(c_hat, b));
    *w = unit(b * z + unit(c_hat - b * dot3(c_hat, b)) * std::sqrt(std::max(0.0, 1.0 - z * z)));
    return std::isfinite(w->x) && std::isfinite(w->y) && std::isfinite(w->z);
}

TEST(FastSphericalTriangle, SolidAngleMatchesLibmAtan2) {
    // Series atan: relative truncation ≤ 7.2e-9 (spherical_sampling.cpp), plus a few double roundings; the
    // tolerance 2e-8 keeps float(1/Ω) within one float ulp of libm's. Triangles from 1e-5 sr (tiny, far) to
    // nearly 2π (huge, close: den < 0, the π − atan branch).
    Pcg32 rng(17, 5);
    double worst = 0.0, largest = 0.0, smallest = 10.0;
    for (int k = 0; k < 20000; ++k) {
        const float scale = std::pow(10.f, rng.next_float() * 6.f - 3.f);
        Vec3 v[3];
        for (auto& x : v) x = Vec3(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, 0.f) * scale + Vec3(0, 0, 1);
        const Vec3 p(rng.next_float() * 0.2f - 0.1f, rng.next_float() * 0.2f - 0.1f, rng.next_float() * 0.9f);
        const double ref = reference_solid_angle(p, v[0], v[1], v[2]);
        if (!(ref > 1e-5)) continue;
        const double fast = spherical_triangle_solid_angle(p, v[0], v[1], v[2]);
        worst = std::max(worst, std::fabs(fast - ref) / ref);
        largest = std::max(largest, ref);
        smallest = std::min(smallest, ref);
    }
    std::printf("solid angle: Ω ∈ [%.3g, %.4f], max relative |series − libm| = %.3g\n", smallest, largest, worst);
    EXPECT_GT(largest, 6.0);
    EXPECT_LT(smallest, 1e-3);
    EXPECT_LE(worst, 2e-8);
}

TEST(FastSphericalTriangle, SamplesMatchLibmArvo) {
    // The same Arvo map with libm's sin/cos: the fast one's Â = u₀Ω has the series' ~1e-9 relative error and the
    // reformulated t − cos α, (1 − q)(1 + q), (1 − z)(1 + z) round differently by ~1e-16 relative — both far
    // below the float rounding of the returned direction (3e-8 per component). 2e-7 leaves room for that
    // rounding on both sides; a map that differs (a wrong term) moves directions by ≫ 1e-6.
    Pcg32 rng(29, 8);
    double worst = 0.0;
    int compared = 0;
    for (int k = 0; k < 400; ++k) {
        const float scale = std::pow(10.f, rng.next_float() * 3.f - 1.5f);
        Vec3 v[3];
        for (auto& x : v) x = Vec3(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 0.2f) * scale;
        const Vec3 p(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 0.3f + rng.next_float() * scale);
        const double omega = spherical_triangle_solid_angle(p, v[0], v[1], v[2]);
        if (!(omega > k_min_spherical_triangle_sr && omega < k_max_spherical_triangle_sr)) continue;
        for (int i = 0; i < 100; ++i) {
            const Vec2 u{rng.next_float(), rng.next_float()};
            const SphericalSample s = sample_spherical_triangle(p, v[0], v[1], v[2], u);
            D3 w;
            ASSERT_GT(s.pdf, 0.f);
            ASSERT_EQ(s.pdf, float(1.0 / omega));
            if (!reference_arvo(p, v[0], v[1], v[2], u, omega, &w)) continue;
            worst = std::max({worst, std::fabs(s.w.x - w.x), std::fabs(s.w.y - w.y), std::fabs(s.w.z - w.z)});
            ++compared;
        }
    }
    std::printf("spherical triangle: %d samples, max |fast − libm| = %.3g\n", compared, worst);
    EXPECT_GT(compared, 10000);
    EXPECT_LE(worst, 2e-7);
}

TEST(FastTriangleLight, PreparedLightSamplesLikeUnprepared) {
    // prepare() caches the longest edge² that the near/far test otherwise recomputes per call. The same float
    // expression may round differently where the compiler contracts it into FMAs in another context, so the
    // cached and the per-call value agree to a few ulps (|Δ| ≤ 3 roundings of a 3-term sum ≤ 4e-7 relative),
    // not necessarily bit for bit; the samples then agree to float rounding (1e-5 relative leaves room for
    // contraction differences in the inlined sampling arithmetic), and a prepared light's pdf evaluation equals
    // its sample's pdf exactly in the spherical branch (both read the cache and the one out-of-line Ω).
    Pcg32 rng(31, 2);
    int spherical = 0, compared = 0;
    for (int k = 0; k < 100; ++k) {
        TriangleLight t;
        t.p0 = Vec3(rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, 1.f);
        t.p1 = Vec3(rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, 1.2f);
        t.p2 = Vec3(rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, 0.9f);
        const Vec3 c = cross(t.p1 - t.p0, t.p2 - t.p0);
        t.area = 0.5f * length(c);
        t.normal = normalize(c);
        t.radiance = Color(1.f);
        TriangleLight prepared = t;
        prepared.prepare();
        ASSERT_GE(prepared.longest_edge_sq, 0.f);
        ASSERT_NEAR(prepared.longest_edge_squared(), t.longest_edge_squared(), 4e-7f * t.longest_edge_squared());
        const LightSampleContext ctx{Vec3(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 3 - 1),
                                     Vec3(0, 0, 1)};
        const bool sph = prepared.uses_spherical_sampling(ctx.p);
        spherical += sph;
        if (sph != t.uses_spherical_sampling(ctx.p)) continue;  // a decision exactly at the rounding boundary
        for (int i = 0; i < 20; ++i) {
            const Vec2 u{rng.next_float(), rng.next_float()};
            const LightSample a = prepared.sample_li(ctx, u, LightPdfMode::SolidAngle);
            const LightSample b = t.sample_li(ctx, u, LightPdfMode::SolidAngle);
            ASSERT_EQ(a.valid(), b.valid());
            if (!a.valid()) continue;
            ASSERT_NEAR(a.pdf, b.pdf, 1e-5f * b.pdf);
            ASSERT_NEAR(a.dist, b.dist, 1e-5f * b.dist);
            ASSERT_LE(length(a.wi - b.wi), 1e-5f);
            if (sph) {
                ASSERT_EQ(prepared.pdf_li(ctx, a.wi, a.dist, LightPdfMode::SolidAngle), a.pdf);
            }
            ++compared;
        }
    }
    EXPECT_GT(spherical, 20);
    EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace candela
