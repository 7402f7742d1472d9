// Microfacet building blocks in the local shading frame (z = macro normal): GGX (Trowbridge–Reitz) and
// Beckmann normal distributions with anisotropic roughness (α_x along the local x axis), Smith masking,
// visible-normal sampling, the dielectric Fresnel term, and reflect/refract helpers.
// References: Walter et al. 2007 ("Microfacet Models for Refraction through Rough Surfaces"); Heitz 2014
// ("Understanding the Masking-Shadowing Function"); Heitz 2018 ("Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4)); Jakob 2014 / Heitz & d'Eon 2014 (Beckmann visible-slope sampling).
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/vec.h"
#include "sampling/erfinv.h"

namespace candela {

enum class MicrofacetDistribution : uint8_t { GGX, Beckmann };

/// Roughness below which a microfacet lobe is treated as a perfectly smooth (delta) interface.
inline constexpr float k_smooth_alpha = 1e-3f;

/// Dielectric Fresnel reflectance for cos_i = cos of the angle to the (micro)normal on the incident side
/// (≥ 0) and eta = η_transmitted/η_incident. Returns 1 under total internal reflection.
inline float fresnel_dielectric(float cos_i, float eta) {
    cos_i = clamp(cos_i, 0.f, 1.f);
    const float sin2_t = (1.f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.f) return 1.f;
    const float cos_t = safe_sqrt(1.f - sin2_t);
    const float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

/// Schlick's weight (1 − u)^5 with u clamped to [0, 1].
inline float schlick_weight(float u) {
    const float m = clamp(1.f - u, 0.f, 1.f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return -wo + n * (2.f * dot(wo, n)); }

/// Refraction of wo (pointing away from the surface, dot(wo, n) > 0) through the microfacet n with
/// eta = η_t/η_i. Returns false on total internal reflection.
inline bool refract(const Vec3& wo, const Vec3& n, float eta, Vec3* wt) {
    const float cos_i = dot(wo, n);
    const float sin2_t = (1.f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.f) return false;
    const float cos_t = safe_sqrt(1.f - sin2_t);
    *wt = -wo / eta + n * (cos_i / eta - cos_t);
    return true;
}

/// Inverse error function: Giles 2010 single-precision approximation (relative error ~1e-6 inside (−1, 1)),
/// polished by one Newton step in float. The visible-slope sampler's pdf is analytic (D_visible), so the sampled
/// density must follow it closely: the χ² tests of the Beckmann lobes (bsdf_test) check it. The former two
/// double-precision Newton steps (two libm erf + two exp calls per inverse) were ~10 % of a Veach-MIS render.
inline float erfinv(float x) {
    x = clamp(x, -0.99999994f, 0.99999994f);
    const float y = erfinv_giles_factor(x) * x;
    const float err = std::erf(y) - x;  // Newton on erf(y) = x: erf'(y) = 2/√π·exp(−y²)
    return y - err / (1.12837917f * std::exp(-y * y));
}

/// An anisotropic microfacet distribution. D, Λ and G1 take unit vectors in the local frame.
struct Microfacet {
    MicrofacetDistribution type = MicrofacetDistribution::GGX;
    float alpha_x = 0.f, alpha_y = 0.f;

    bool effectively_smooth() const { return std::fmax(alpha_x, alpha_y) < k_smooth_alpha; }

    /// Normal distribution D(m), normalised so that ∫ D(m) cos θm dωm = 1.
    float D(const Vec3& m) const {
        if (m.z <= 0.f) return 0.f;
        const float z2 = m.z * m.z;
        const float e = (sqr(m.x / alpha_x) + sqr(m.y / alpha_y)) / z2;  // tan²θ·(cos²φ/αx² + sin²φ/αy²)
        if (type == MicrofacetDistribution::GGX) {
            const float d = z2 * (1.f + e);
            return 1.f / (k_pi * alpha_x * alpha_y * d * d);
        }
        if (e > 80.f) return 0.f;
        return std::exp(-e) / (k_pi * alpha_x * alpha_y * z2 * z2);
    }

    /// Smith Λ(w) (symmetric in w.z's sign).
    float Lambda(const Vec3& w) const {
        const float z2 = w.z * w.z;
        if (z2 <= 0.f) return 1e30f;
        const float a2t2 = (sqr(w.x * alpha_x) + sqr(w.y * alpha_y)) / z2;  // α(w)²·tan²θ
        if (type == MicrofacetDistribution::GGX) return 0.5f * (std::sqrt(1.f + a2t2) - 1.f);
        if (a2t2 <= 0.f) return 0.f;
        // Λ = (exp(−a²)/(a√π) − erfc(a))/2, a = 1/(α tanθ), in float: the two terms agree to a relative 1/(2a²),
        // so at most ~6 of float's 24 bits cancel below a = 6, and G1 = 1/(1 + Λ) needs Λ's absolute error only.
        const float a = 1.f / std::sqrt(a2t2);
        if (a > 6.f) return 0.f;  // erfc(6) ≈ 2e-17: Λ underflows
        return 0.5f * (std::exp(-a * a) / (a * 1.77245385f) - std::erfc(a));
    }
    float G1(const Vec3& w) const { return 1.f / (1.f + Lambda(w)); }
    /// Separable Smith shadowing-masking, as Cycles 3.4 uses (G1(wo)·G1(wi)).
    float G(const Vec3& wo, const Vec3& wi) const { return G1(wo) * G1(wi); }

    /// Density of visible normals seen from wo (wo.z > 0): G1(wo)·max(0, wo·m)·D(m)/wo.z.
    float D_visible(const Vec3& wo, const Vec3& m) const {
        const float wm = dot(wo, m);
        if (wo.z <= 0.f || wm <= 0.f) return 0.f;
        return G1(wo) * wm * D(m) / wo.z;
    }

    /// Samples a visible normal for wo (wo.z > 0).
    Vec3 sample_visible(const Vec3& wo, Vec2 u) const {
        return type == MicrofacetDistribution::GGX ? sample_visible_ggx(wo, u) : sample_visible_beckmann(wo, u);
    }

private:
    // Heitz 2018: stretch, sample the projected hemisphere of the stretched view, unstretch.
    Vec3 sample_visible_ggx(const Vec3& wo, Vec2 u) const {
        const Vec3 vh = normalize(Vec3(alpha_x * wo.x, alpha_y * wo.y, wo.z));
        const float lensq = vh.x * vh.x + vh.y * vh.y;
        const Vec3 t1 = lensq > 1e-14f ? Vec3(-vh.y, vh.x, 0.f) / std::sqrt(lensq) : Vec3(1.f, 0.f, 0.f);
        const Vec3 t2 = cross(vh, t1);
        const float r = std::sqrt(u.x), phi = 2.f * k_pi * u.y;
        const float p1 = r * std::cos(phi);
        float p2 = r * std::sin(phi);
        const float s = 0.5f * (1.f + vh.z);
        p2 = (1.f - s) * safe_sqrt(1.f - p1 * p1) + s * p2;
        const Vec3 nh = t1 * p1 + t2 * p2 + vh * safe_sqrt(1.f - p1 * p1 - p2 * p2);
        return normalize(Vec3(alpha_x * nh.x, alpha_y * nh.y, std::fmax(1e-6f, nh.z)));
    }

    // Visible slopes of the standard (α = 1) Beckmann distribution for an incident direction at cos θ:
    // x by inverting the visible-slope CDF (Newton–bisection in the erf domain), y by the Gaussian.
    static Vec2 sample_visible_slopes_beckmann(float cos_t, Vec2 u) {
        const float ux = clamp(u.x, 1e-6f, 1.f - 1e-6f), uy = clamp(u.y, 1e-6f, 1.f - 1e-6f);
        if (cos_t > 0.99999f) {
            const float r = std::sqrt(-std::log(1.f - ux)), phi = 2.f * k_pi * uy;
            return {r * std::cos(phi), r * std::sin(phi)};
        }
        const double sin_t = std::sqrt(std::max(0.0, 1.0 - double(cos_t) * cos_t));
        const double tan_t = sin_t / cos_t, cot_t = 1.0 / tan_t;
        const double inv_sqrt_pi = 0.56418958354775628;
        // CDF of the x slope, parameterised by b = erf(x): C(b) = norm·(1 + b + tanθ/√π·exp(−x²)).
        double lo = -1.0, hi = std::erf(cot_t);
        const double norm = 1.0 / (1.0 + hi + inv_sqrt_pi * tan_t * std::exp(-cot_t * cot_t));
        const double theta = std::acos(double(cos_t));
        const double fit = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
        double b = hi - (1.0 + hi) * std::pow(1.0 - double(ux), fit);
        for (int it = 0; it < 100; ++it) {
            if (!(b >= lo && b <= hi)) b = 0.5 * (lo + hi);
            // Unpolished inverse (relative error ~1e-6): x enters only through exp(−x²), and the result is polished.
            const float bf = clamp(float(b), -0.99999994f, 0.99999994f);
            const double x = erfinv_giles_factor(bf) * bf;
            const double value = norm * (1.0 + b + inv_sqrt_pi * tan_t * std::exp(-x * x)) - ux;
            const double deriv = norm * (1.0 - x * tan_t);
            if (std::fabs(value) < 1e-7) break;
            if (value > 0.0)
                hi = b;
            else
                lo = b;
            b -= value / deriv;
        }
        return {erfinv(float(b)), erfinv(2.f * uy - 1.f)};
    }

    Vec3 sample_visible_beckmann(const Vec3& wo, Vec2 u) const {
        const Vec3 ws = normalize(Vec3(alpha_x * wo.x, alpha_y * wo.y, wo.z));  // stretched view
        const float sin_t = safe_sqrt(1.f - ws.z * ws.z);
        float cos_phi = 1.f, sin_phi = 0.f;
        if (sin_t > 1e-7f) {
            cos_phi = clamp(ws.x / sin_t, -1.f, 1.f);
            sin_phi = clamp(ws.y / sin_t, -1.f, 1.f);
        }
        Vec2 s = sample_visible_slopes_beckmann(ws.z, u);
        const float sx = cos_phi * s.x - sin_phi * s.y, sy = sin_phi * s.x + cos_phi * s.y;
        return normalize(Vec3(-sx * alpha_x, -sy * alpha_y, 1.f));
    }
};

}  // namespace candela
