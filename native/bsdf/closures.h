// The closure lobes (Cycles 3.4's BSDF closures) as value types in the local shading frame: z = shading
// normal on the side the path arrives from (wo.z ≥ 0; the caller flips the frame), wi.z < 0 means
// transmission. Every lobe is colourless where Cycles' closure is (the colour is the closure weight held
// by Bsdf) and provides
//   Color f(wo, wi, mode)            BSDF value without the cosine (0 for delta lobes)
//   float pdf(wo, wi, mode)          solid-angle density of sample() (0 for delta lobes)
//   BsdfSample sample(wo, u, uc, mode)
//   float albedo(wo)                 rough reflectance estimate, only used to choose lobes
//   uint32_t flags()                 the BsdfFlags the lobe can produce
// For non-delta lobes sample() returns exactly f(wo, wi) and pdf(wo, wi) (it evaluates them), so MIS
// always sees the density sample() used.
#pragma once

#include <cmath>

#include "bsdf/bsdf_sample.h"
#include "bsdf/lambert.h"
#include "bsdf/microfacet.h"
#include "core/math.h"
#include "sampling/warp.h"

namespace candela {

namespace detail {

/// Cosine-weighted sampling of the upper hemisphere for a reflection lobe L (f and pdf evaluated by L).
template <typename L>
BsdfSample sample_cosine_reflection(const L& lobe, const Vec3& wo, Vec2 u, TransportMode mode, uint32_t flags) {
    BsdfSample s;
    if (wo.z <= 0.f) return s;
    s.wi = sample_cosine_hemisphere(u);
    if (s.wi.z <= 1e-7f) return s;
    s.f = lobe.f(wo, s.wi, mode);
    s.pdf = cosine_hemisphere_pdf(s.wi.z);
    s.flags = flags;
    return s;
}

}  // namespace detail

/// Oren–Nayar as Cycles parametrises it (bsdf_oren_nayar.h, after Fujii's "qualitative" form):
/// σ = clamp(roughness, 0, 1), A = 1/(π + (3π − 4)/6·σ), B = σ·A,
/// f = A + B·s/t with s = wi·wo − cosθi cosθo and t = max(cosθi, cosθo) when s > 0 (t = 1 otherwise).
/// σ = 0 gives Lambert exactly. Sampled by the cosine hemisphere (Cycles samples uniformly; any pdf works).
struct OrenNayarBsdf {
    float roughness = 0.f;

    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f) return Color(0.f);
        const float sigma = clamp(roughness, 0.f, 1.f);
        const float a = 1.f / (k_pi + ((3.f * k_pi - 4.f) / 6.f) * sigma), b = sigma * a;
        float s = dot(wi, wo) - wi.z * wo.z;
        if (s > 0.f) s /= max_num(wi.z, wo.z);
        return Color(a + b * s);
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z > 0.f) ? cosine_hemisphere_pdf(wi.z) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode mode = TransportMode::Radiance) const {
        return detail::sample_cosine_reflection(*this, wo, u, mode, flags());
    }
    float albedo(const Vec3&) const { return 1.f; }
    uint32_t flags() const { return k_bsdf_reflection | k_bsdf_diffuse; }
};

/// Diffuse transmission (Cycles' Translucent BSDF): f = 1/π on the far side, cosine-sampled there.
struct TranslucentBsdf {
    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z < 0.f) ? Color(k_inv_pi) : Color(0.f);
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z < 0.f) ? cosine_hemisphere_pdf(-wi.z) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode = TransportMode::Radiance) const {
        BsdfSample s;
        if (wo.z <= 0.f) return s;
        const Vec3 w = sample_cosine_hemisphere(u);
        if (w.z <= 1e-7f) return s;
        s.wi = Vec3(w.x, w.y, -w.z);
        s.f = Color(k_inv_pi);
        s.pdf = cosine_hemisphere_pdf(w.z);
        s.flags = flags();
        return s;
    }
    float albedo(const Vec3&) const { return 1.f; }
    uint32_t flags() const { return k_bsdf_transmission | k_bsdf_diffuse; }
};

/// Delta pass-through (Cycles' Transparent BSDF): wi = −wo with weight 1 (no η: the medium is unchanged).
struct TransparentBsdf {
    Color f(const Vec3&, const Vec3&, TransportMode = TransportMode::Radiance) const { return Color(0.f); }
    float pdf(const Vec3&, const Vec3&, TransportMode = TransportMode::Radiance) const { return 0.f; }
    BsdfSample sample(const Vec3& wo, Vec2, float = 0.f, TransportMode = TransportMode::Radiance) const {
        BsdfSample s;
        if (wo.z <= 1e-7f) return s;
        s.wi = -wo;
        s.f = Color(1.f / wo.z);
        s.pdf = 1.f;
        s.flags = flags();
        return s;
    }
    float albedo(const Vec3&) const { return 1.f; }
    uint32_t flags() const { return k_bsdf_transmission | k_bsdf_specular | k_bsdf_transparent; }
};

/// Fresnel factor of a microfacet reflection lobe. None: Cycles' Glossy/Anisotropic node (colour tint
/// only, via the weight). Principled: Cycles' interpolate_fresnel_color — the dielectric Fresnel at
/// `ior`, renormalised to [0, 1] from its normal-incidence value, blends cspec0 towards white.
struct SpecularFresnel {
    enum Kind : uint8_t { None, Principled } kind = None;
    Color cspec0{1.f};
    float ior = 1.5f;

    Color eval(float cos_h) const {
        if (kind == None) return Color(1.f);
        const float f0 = fresnel_dielectric(1.f, ior);
        const float fh = f0 < 1.f ? (fresnel_dielectric(cos_h, ior) - f0) / (1.f - f0) : 1.f;
        return cspec0 * (1.f - fh) + Color(fh);
    }
};

/// Microfacet reflection (GGX or Beckmann, anisotropic, α = roughness² set by the caller), sampled by
/// visible normals; α < 1e-3 is a delta mirror. f = F·D·G/(4 cosθo cosθi) with separable Smith G.
struct MicrofacetReflection {
    Microfacet distribution;
    SpecularFresnel fresnel;

    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f || distribution.effectively_smooth()) return Color(0.f);
        Vec3 h = wo + wi;
        if (length_squared(h) <= 1e-14f) return Color(0.f);
        h = normalize(h);
        const float d = distribution.D(h);
        if (d == 0.f) return Color(0.f);
        return fresnel.eval(dot(wo, h)) * (d * distribution.G(wo, wi) / (4.f * wo.z * wi.z));
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f || distribution.effectively_smooth()) return 0.f;
        Vec3 h = wo + wi;
        if (length_squared(h) <= 1e-14f) return 0.f;
        h = normalize(h);
        const float wh = dot(wo, h);
        return wh > 0.f ? distribution.D_visible(wo, h) / (4.f * wh) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode mode = TransportMode::Radiance) const {
        BsdfSample s;
        if (wo.z <= 1e-7f) return s;
        if (distribution.effectively_smooth()) {
            s.wi = Vec3(-wo.x, -wo.y, wo.z);
            s.f = fresnel.eval(wo.z) / wo.z;
            s.pdf = 1.f;
            s.flags = k_bsdf_reflection | k_bsdf_specular;
            return s;
        }
        const Vec3 h = distribution.sample_visible(wo, u);
        s.wi = reflect(wo, h);
        if (s.wi.z <= 1e-7f) return BsdfSample{};  // reflected below the horizon: no sample
        s.pdf = pdf(wo, s.wi, mode);
        if (!(s.pdf > 0.f)) return BsdfSample{};
        s.f = f(wo, s.wi, mode);
        s.flags = k_bsdf_reflection | k_bsdf_glossy;
        return s;
    }
    float albedo(const Vec3& wo) const { return luminance(fresnel.eval(wo.z)); }
    uint32_t flags() const {
        return k_bsdf_reflection | (distribution.effectively_smooth() ? k_bsdf_specular : k_bsdf_glossy);
    }
};

/// Dielectric interface (Cycles' Glass and Refraction nodes; the Principled glass). eta = η(far side)/
/// η(side of wo): the caller passes ior when the path arrives on the front face and 1/ior on the back.
/// α < 1e-3: delta reflection and refraction, chosen with probability F (Fresnel at the macro normal).
/// Rough: Walter et al. 2007 with visible-normal sampling; reflection vs refraction chosen with the
/// Fresnel of the sampled microfacet. refraction_only (Refraction node): no reflection and no Fresnel
/// factor on the transmission, as Cycles' refraction closures. Radiance mode carries 1/η² on
/// transmission (see TransportMode). Reflection is tinted tint_r, transmission tint_t.
/// Note: Cycles 3.4 builds its Glass node from two separate closures weighted by the Fresnel of the macro
/// normal; this lobe uses the per-microfacet Fresnel (energy-consistent; equal for smooth glass).
struct MicrofacetDielectric {
    Microfacet distribution;
    float eta = 1.5f;
    Color tint_r{1.f}, tint_t{1.f};
    bool refraction_only = false;

    Color f(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z == 0.f || distribution.effectively_smooth()) return Color(0.f);
        if (wi.z > 0.f) {
            if (refraction_only) return Color(0.f);
            Vec3 h = wo + wi;
            if (length_squared(h) <= 1e-14f) return Color(0.f);
            h = normalize(h);
            const float F = fresnel_dielectric(dot(wo, h), eta);
            return tint_r * (F * distribution.D(h) * distribution.G(wo, wi) / (4.f * wo.z * wi.z));
        }
        Vec3 h;
        float wo_h, wi_h;
        if (!transmission_half_vector(wo, wi, &h, &wo_h, &wi_h)) return Color(0.f);
        const float T = refraction_only ? 1.f : 1.f - fresnel_dielectric(wo_h, eta);
        const float denom = sqr(wo_h + eta * wi_h);
        float v =
            T * distribution.D(h) * distribution.G(wo, wi) * std::fabs(wi_h) * wo_h / (wo.z * std::fabs(wi.z) * denom);
        if (mode == TransportMode::Importance) v *= eta * eta;
        return tint_t * v;
    }

    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z == 0.f || distribution.effectively_smooth()) return 0.f;
        if (wi.z > 0.f) {
            if (refraction_only) return 0.f;
            Vec3 h = wo + wi;
            if (length_squared(h) <= 1e-14f) return 0.f;
            h = normalize(h);
            const float wo_h = dot(wo, h);
            if (wo_h <= 0.f) return 0.f;
            return distribution.D_visible(wo, h) / (4.f * wo_h) * fresnel_dielectric(wo_h, eta);
        }
        Vec3 h;
        float wo_h, wi_h;
        if (!transmission_half_vector(wo, wi, &h, &wo_h, &wi_h)) return 0.f;
        const float p_t = refraction_only ? 1.f : 1.f - fresnel_dielectric(wo_h, eta);
        return distribution.D_visible(wo, h) * eta * eta * std::fabs(wi_h) / sqr(wo_h + eta * wi_h) * p_t;
    }

    BsdfSample sample(const Vec3& wo, Vec2 u, float uc, TransportMode mode = TransportMode::Radiance) const {
        BsdfSample s;
        if (wo.z <= 1e-7f) return s;
        if (distribution.effectively_smooth()) {
            const float F = refraction_only ? 0.f : fresnel_dielectric(wo.z, eta);
            if (uc < F) {
                s.wi = Vec3(-wo.x, -wo.y, wo.z);
                s.f = tint_r * (F / wo.z);
                s.pdf = F;
                s.flags = k_bsdf_reflection | k_bsdf_specular;
                return s;
            }
            Vec3 wt;
            if (!refract(wo, Vec3(0.f, 0.f, 1.f), eta, &wt) || wt.z >= -1e-7f) return s;
            const float T = 1.f - F;  // = 1 for refraction_only
            float v = T / std::fabs(wt.z);
            if (mode == TransportMode::Radiance) v /= eta * eta;
            s.wi = wt;
            s.f = tint_t * v;
            s.pdf = T;
            s.eta = eta;
            s.flags = k_bsdf_transmission | k_bsdf_specular;
            return s;
        }
        const Vec3 h = distribution.sample_visible(wo, u);
        const float wo_h = dot(wo, h);
        if (wo_h <= 0.f) return s;
        const float F = refraction_only ? 0.f : fresnel_dielectric(wo_h, eta);
        if (uc < F) {
            s.wi = reflect(wo, h);
            if (s.wi.z <= 1e-7f) return BsdfSample{};
            s.flags = k_bsdf_reflection | k_bsdf_glossy;
        } else {
            if (!refract(wo, h, eta, &s.wi) || s.wi.z >= -1e-7f) return BsdfSample{};
            s.eta = eta;
            s.flags = k_bsdf_transmission | k_bsdf_glossy;
        }
        s.pdf = pdf(wo, s.wi, mode);
        if (!(s.pdf > 0.f)) return BsdfSample{};
        s.f = f(wo, s.wi, mode);
        return s;
    }
    float albedo(const Vec3&) const { return 1.f; }
    uint32_t flags() const {
        const uint32_t kind = distribution.effectively_smooth() ? k_bsdf_specular : k_bsdf_glossy;
        return kind | k_bsdf_transmission | (refraction_only ? 0u : k_bsdf_reflection);
    }

private:
    // Generalised half vector for wo.z > 0 > wi.z, facing +z; false for back-facing microfacets.
    bool transmission_half_vector(const Vec3& wo, const Vec3& wi, Vec3* h, float* wo_h, float* wi_h) const {
        Vec3 m = wo + wi * eta;
        if (length_squared(m) <= 1e-14f) return false;
        m = normalize(m);
        if (m.z < 0.f) m = -m;
        *wo_h = dot(wo, m);
        *wi_h = dot(wi, m);
        if (*wo_h <= 0.f || *wi_h >= 0.f) return false;
        *h = m;
        return true;
    }
};

/// Principled v1 diffuse (Cycles bsdf_principled_diffuse.h, PRINCIPLED_DIFFUSE_FULL): Disney's diffuse
/// with retro-reflection, f = (1/π)·[(1 − F_L/2)(1 − F_V/2) + R_R·(F_L + F_V + F_L F_V (R_R − 1))],
/// F = (1 − cos)^5, R_R = roughness·(1 + wi·wo) (= 2 roughness cos²θ_d). Not energy conserving (the
/// albedo exceeds 1 for rough surfaces), exactly as Cycles.
struct PrincipledDiffuseBsdf {
    float roughness = 0.5f;

    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f) return Color(0.f);
        const float fv = schlick_weight(wo.z), fl = schlick_weight(wi.z);
        const float rr = roughness * (dot(wi, wo) + 1.f);
        const float v = (1.f - 0.5f * fv) * (1.f - 0.5f * fl) + rr * (fl + fv + fl * fv * (rr - 1.f));
        return Color(k_inv_pi * v);
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z > 0.f) ? cosine_hemisphere_pdf(wi.z) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode mode = TransportMode::Radiance) const {
        return detail::sample_cosine_reflection(*this, wo, u, mode, flags());
    }
    float albedo(const Vec3&) const { return 1.f; }
    uint32_t flags() const { return k_bsdf_reflection | k_bsdf_diffuse; }
};

/// Principled v1 sheen (Cycles bsdf_principled_sheen.h): f = (1 − wi·h)^5 (no 1/π, as Cycles), cosine
/// sampled; the selection estimate is Cycles' avg_value (1 − cosθo)^5·cosθo.
struct PrincipledSheenBsdf {
    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f) return Color(0.f);
        Vec3 h = wo + wi;
        if (length_squared(h) <= 1e-14f) return Color(1.f);
        h = normalize(h);
        return Color(schlick_weight(dot(wi, h)));
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z > 0.f) ? cosine_hemisphere_pdf(wi.z) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode mode = TransportMode::Radiance) const {
        return detail::sample_cosine_reflection(*this, wo, u, mode, flags());
    }
    float albedo(const Vec3& wo) const { return max_num(schlick_weight(wo.z) * wo.z, 0.01f); }
    uint32_t flags() const { return k_bsdf_reflection | k_bsdf_diffuse; }
};

/// Principled v1 clearcoat (Cycles' MICROFACET_GGX_CLEARCOAT): GTR1 normal distribution with
/// α = clearcoat_roughness², Smith-GGX masking with the fixed α = 0.25, Fresnel of IOR 1.5 through
/// interpolate_fresnel_color with cspec0 = 0.04. The 0.25·clearcoat factor lives in the closure weight.
/// Sampled by D(m)·cosθm (Cycles samples GGX visible normals but reports the GTR1 pdf; we stay consistent).
struct ClearcoatBsdf {
    float alpha = 0.03f * 0.03f;

    float D(const Vec3& m) const {
        if (m.z <= 0.f) return 0.f;
        const float a = clamped_alpha();
        if (a >= 1.f) return k_inv_pi;
        const float a2 = a * a;
        return (a2 - 1.f) / (k_pi * std::log(a2) * (1.f + (a2 - 1.f) * m.z * m.z));
    }
    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f) return Color(0.f);
        Vec3 h = wo + wi;
        if (length_squared(h) <= 1e-14f) return Color(0.f);
        h = normalize(h);
        const Microfacet g{MicrofacetDistribution::GGX, 0.25f, 0.25f};
        const SpecularFresnel fr{SpecularFresnel::Principled, Color(0.04f), 1.5f};
        return fr.eval(dot(wo, h)) * (D(h) * g.G(wo, wi) / (4.f * wo.z * wi.z));
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        if (wo.z <= 0.f || wi.z <= 0.f) return 0.f;
        Vec3 h = wo + wi;
        if (length_squared(h) <= 1e-14f) return 0.f;
        h = normalize(h);
        return D(h) * h.z / (4.f * dot(wo, h));
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode mode = TransportMode::Radiance) const {
        BsdfSample s;
        if (wo.z <= 1e-7f) return s;
        const float a = clamped_alpha();
        float cos2;
        if (a >= 1.f) {
            cos2 = 1.f - u.x;
        } else {
            const float a2 = a * a;
            cos2 = (1.f - std::pow(a2, 1.f - u.x)) / (1.f - a2);
        }
        const float cos_t = safe_sqrt(cos2), sin_t = safe_sqrt(1.f - cos2), phi = 2.f * k_pi * u.y;
        const Vec3 h(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
        if (dot(wo, h) <= 0.f) return s;
        s.wi = reflect(wo, h);
        if (s.wi.z <= 1e-7f) return BsdfSample{};
        s.pdf = pdf(wo, s.wi, mode);
        if (!(s.pdf > 0.f)) return BsdfSample{};
        s.f = f(wo, s.wi, mode);
        s.flags = flags();
        return s;
    }
    float albedo(const Vec3& wo) const {
        return SpecularFresnel{SpecularFresnel::Principled, Color(0.04f), 1.5f}.eval(wo.z).x;
    }
    uint32_t flags() const { return k_bsdf_reflection | k_bsdf_glossy; }

private:
    float clamped_alpha() const { return clamp(alpha, 1e-3f, 1.f); }
};

}  // namespace candela
