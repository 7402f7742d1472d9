// A BSDF is Cycles' weighted closure list: up to k_max_lobes {lobe, colour weight} pairs. Mix Shader
// scales weights (mix), Add Shader concatenates (add). All directions are in the local shading frame
// (z = shading normal flipped to the side of wo), so a BSDF never sees world space.
//   f(wo, wi)   = Σ_i weight_i·f_i(wo, wi)                     (cosine excluded)
//   pdf(wo, wi) = Σ_i p_i·pdf_i(wo, wi),  p_i ∝ luminance(weight_i)·albedo_i(wo)
//   sample: one dimension (uc) picks lobe i with probability p_i and is rescaled for the lobe's own
//   choice; a non-delta result is re-evaluated as the full mixture (f, pdf) — exactly pdf() — so MIS
//   sees the density sample() used; a delta result keeps weight_i·f_i and the discrete p_i·P_i.
//
// Bump shadowing (Chiang, Li and Burley 2019, "Taming the Shadow Terminator", eq. 4; what Cycles 3.4 applies to
// its diffuse closures whose normal a Bump or Normal Map node bent): with N_s the smooth (interpolated) normal and
// N_b the bent one, the diffuse lobes' f is multiplied by G(g), g = (N_s·ω_i)/((N_b·ω_i)(N_s·N_b)),
// G = 1 for g ≥ 1, 0 for g < 0 and −g³ + g² + g in between (C¹ at g = 1). It darkens light arriving at a bent
// normal from where the smooth surface would not see it, which removes the terminator's bright band. The pdf is
// unchanged (the term only scales f), so sample() keeps its density. Inactive unless set (set_bump_shadowing).
#pragma once

#include <array>
#include <cstdint>
#include <variant>

#include "bsdf/closures.h"

namespace candela {

using BsdfLobe = std::variant<LambertBsdf, OrenNayarBsdf, TranslucentBsdf, TransparentBsdf, MicrofacetReflection,
                              MicrofacetDielectric, PrincipledDiffuseBsdf, PrincipledSheenBsdf, ClearcoatBsdf>;

struct WeightedLobe {
    BsdfLobe lobe;
    Color weight{1.f};
};

/// The smooth normal in the local frame of a BSDF whose z axis is a bent (bumped) normal (see above).
struct BumpShadowing {
    Vec3 smooth{0.f, 0.f, 1.f};
    bool active = false;

    /// G(g) for incident direction wi (local); 1 when inactive.
    float term(const Vec3& wi) const {
        if (!active) return 1.f;
        const float denom = wi.z * smooth.z;
        const float g = denom != 0.f ? dot(smooth, wi) / denom : 0.f;
        if (g >= 1.f) return 1.f;
        if (!(g >= 0.f)) return 0.f;
        const float g2 = g * g;
        return -g2 * g + g2 + g;
    }
};

class Bsdf {
public:
    static constexpr int k_max_lobes = 8;

    Bsdf() = default;
    /// A single lobe (implicit, so `Bsdf b = LambertBsdf{}` keeps working).
    template <typename L, typename = std::enable_if_t<std::is_constructible_v<BsdfLobe, L>>>
    Bsdf(const L& lobe, Color weight = Color(1.f)) {  // NOLINT(google-explicit-constructor)
        add(lobe, weight);
    }

    /// Appends a lobe; a black weight is skipped, and like Cycles' closure limit a lobe beyond capacity
    /// is dropped (returns false).
    bool add(const BsdfLobe& lobe, Color weight) {
        if (is_black(weight) || !(max_component(weight) > 0.f) || !is_finite(weight)) return true;
        if (m_count >= k_max_lobes) return false;
        m_lobes[size_t(m_count++)] = WeightedLobe{lobe, vmax(weight, Color(0.f))};
        // A lobe's flags are fixed by its parameters, which never change after add(): cache them.
        const uint32_t fl = std::visit([](const auto& l) { return l.flags(); }, lobe);
        m_flags |= fl;
        if (!(fl & k_bsdf_specular)) m_all_delta = false;
        return true;
    }
    void scale(Color s) {
        for (int i = 0; i < m_count; ++i) m_lobes[size_t(i)].weight *= s;
    }
    /// Turns bump shadowing on for the diffuse lobes (the smooth normal in this BSDF's local frame), or off.
    void set_bump_shadowing(const BumpShadowing& b) { m_shadowing = b; }
    const BumpShadowing& bump_shadowing() const { return m_shadowing; }

    int size() const { return m_count; }
    bool empty() const { return m_count == 0; }
    const WeightedLobe& operator[](int i) const { return m_lobes[size_t(i)]; }

    /// Union of the lobes' flags.
    uint32_t flags() const { return m_flags; }
    /// True if every lobe is a delta distribution (NEE is pointless); false for an empty BSDF.
    bool is_delta() const { return m_count > 0 && m_all_delta; }
    bool has_non_delta() const { return m_count > 0 && !is_delta(); }

    // f, pdf and sample: a lone Lambert lobe (the most common material) is evaluated inline here; everything
    // else goes through the lobe variant out of line (the *_general functions), which keeps these small enough
    // to inline into the integrators' vertex loops.
    Color f(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const {
        if (single_lambert() && !m_shadowing.active) return m_lobes[0].weight * LambertBsdf{}.f(wo, wi, mode);
        return f_general(wo, wi, mode);
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const {
        if (single_lambert()) return LambertBsdf{}.pdf(wo, wi, mode);
        return pdf_general(wo, wi, mode);
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float uc, TransportMode mode = TransportMode::Radiance) const {
        if (single_lambert() && !m_shadowing.active) {
            BsdfSample s = LambertBsdf{}.sample(wo, u, uc, mode);
            s.f *= m_lobes[0].weight;
            return s;
        }
        return sample_general(wo, u, uc, mode);
    }

    /// The colour of a lone Lambert lobe without bump shadowing (f = colour/π, sampled by the cosine), else null:
    /// callers with a fast path for the most common material test it.
    const Color* lone_lambert() const { return single_lambert() && !m_shadowing.active ? &m_lobes[0].weight : nullptr; }

    /// Directional albedo estimate Σ weight_i·albedo_i(wo) (the lobes' own estimates; for roulette and choices).
    Color albedo(const Vec3& wo) const {
        Color sum(0.f);
        for (int i = 0; i < m_count; ++i) {
            const WeightedLobe& wl = m_lobes[size_t(i)];
            sum += wl.weight * std::visit([&](const auto& l) { return l.albedo(wo); }, wl.lobe);
        }
        return sum;
    }

    /// Lobe selection probabilities p_i (false if no lobe can be chosen).
    bool selection(const Vec3& wo, std::array<float, k_max_lobes>& p) const {
        float total = 0.f;
        for (int i = 0; i < m_count; ++i) {
            const WeightedLobe& wl = m_lobes[size_t(i)];
            const float a = std::visit([&](const auto& l) { return l.albedo(wo); }, wl.lobe);
            const float w = luminance(wl.weight) * max_num(a, 0.f);
            p[size_t(i)] = std::isfinite(w) ? w : 0.f;
            total += p[size_t(i)];
        }
        if (!(total > 0.f)) return false;
        for (int i = 0; i < m_count; ++i) p[size_t(i)] /= total;
        return true;
    }

private:
    /// Exactly one lobe, Lambertian: f, pdf and sample take the inline path.
    bool single_lambert() const { return m_count == 1 && std::holds_alternative<LambertBsdf>(m_lobes[0].lobe); }
    /// Lobe i's weighted f, with the bump shadowing term for diffuse lobes.
    Color lobe_f(int i, const Vec3& wo, const Vec3& wi, TransportMode mode) const {
        const WeightedLobe& wl = m_lobes[size_t(i)];
        Color v = wl.weight * std::visit([&](const auto& l) { return l.f(wo, wi, mode); }, wl.lobe);
        if (m_shadowing.active && std::visit([](const auto& l) { return (l.flags() & k_bsdf_diffuse) != 0u; }, wl.lobe))
            v *= m_shadowing.term(wi);
        return v;
    }
    __attribute__((noinline)) Color f_general(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
        if (m_count == 1) return lobe_f(0, wo, wi, mode);  // one lobe: no mixture bookkeeping (the common case)
        Color sum(0.f);
        for (int i = 0; i < m_count; ++i) sum += lobe_f(i, wo, wi, mode);
        return sum;
    }

    __attribute__((noinline)) float pdf_general(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
        if (m_count == 1) return std::visit([&](const auto& l) { return l.pdf(wo, wi, mode); }, m_lobes[0].lobe);
        std::array<float, k_max_lobes> p;
        if (!selection(wo, p)) return 0.f;
        float sum = 0.f;
        for (int i = 0; i < m_count; ++i)
            if (p[size_t(i)] > 0.f)
                sum += p[size_t(i)] *
                       std::visit([&](const auto& l) { return l.pdf(wo, wi, mode); }, m_lobes[size_t(i)].lobe);
        return sum;
    }

    __attribute__((noinline)) BsdfSample sample_general(const Vec3& wo, Vec2 u, float uc, TransportMode mode) const {
        if (m_count == 1) {  // one lobe: its own sample is exactly the mixture's
            BsdfSample s = std::visit([&](const auto& l) { return l.sample(wo, u, uc, mode); }, m_lobes[0].lobe);
            s.f *= m_lobes[0].weight;
            if (m_shadowing.active && (s.flags & k_bsdf_diffuse)) s.f *= m_shadowing.term(s.wi);
            return s;
        }
        std::array<float, k_max_lobes> p;
        if (!selection(wo, p)) return {};
        // Pick lobe i by uc and rescale uc to [0, 1) for the lobe's own discrete choice.
        int chosen = -1;
        float cdf = 0.f;
        for (int i = 0; i < m_count; ++i) {
            if (p[size_t(i)] <= 0.f) continue;
            chosen = i;
            if (uc < cdf + p[size_t(i)]) break;
            cdf += p[size_t(i)];
        }
        if (chosen < 0) return {};
        const float p_chosen = p[size_t(chosen)];
        const float uc_lobe = min_num(max_num((uc - cdf) / p_chosen, 0.f), k_one_minus_epsilon);
        const WeightedLobe& wl = m_lobes[size_t(chosen)];
        BsdfSample s = std::visit([&](const auto& l) { return l.sample(wo, u, uc_lobe, mode); }, wl.lobe);
        if (!s.valid()) return {};
        if (s.is_delta()) {
            s.f *= wl.weight;
            s.pdf *= p_chosen;
            return s;
        }
        s.f = f(wo, s.wi, mode);
        float pdf_sum = 0.f;
        for (int i = 0; i < m_count; ++i)
            if (p[size_t(i)] > 0.f)
                pdf_sum +=
                    p[size_t(i)] * (i == chosen ? s.pdf
                                                : std::visit([&](const auto& l) { return l.pdf(wo, s.wi, mode); },
                                                             m_lobes[size_t(i)].lobe));
        s.pdf = pdf_sum;
        if (!(s.pdf > 0.f) || !std::isfinite(s.pdf) || !is_finite(s.f)) return {};
        return s;
    }

    std::array<WeightedLobe, k_max_lobes> m_lobes{};
    BumpShadowing m_shadowing;
    int m_count = 0;
    uint32_t m_flags = 0;     // union of the lobes' flags
    bool m_all_delta = true;  // every lobe specular (vacuous when empty; is_delta() checks m_count)
};

/// Mix Shader: (1 − fac)·a + fac·b (fac clamped to [0, 1]).
inline Bsdf mix(const Bsdf& a, const Bsdf& b, float fac) {
    fac = clamp(fac, 0.f, 1.f);
    Bsdf out;
    for (int i = 0; i < a.size(); ++i) out.add(a[i].lobe, a[i].weight * (1.f - fac));
    for (int i = 0; i < b.size(); ++i) out.add(b[i].lobe, b[i].weight * fac);
    return out;
}
/// Add Shader: the concatenation of both lists.
inline Bsdf add(const Bsdf& a, const Bsdf& b) {
    Bsdf out = a;
    for (int i = 0; i < b.size(); ++i) out.add(b[i].lobe, b[i].weight);
    return out;
}

/// Principled BSDF v1 inputs (Cycles 3.4 defaults). Subsurface is approximated by mixing the subsurface
/// colour into the diffuse colour (no BSSRDF); the distribution is GGX (multiscatter GGX is not implemented).
struct PrincipledParams {
    Color base_color{0.8f};
    float subsurface = 0.f;
    Color subsurface_color{0.8f, 0.8f, 0.8f};
    float metallic = 0.f;
    float specular = 0.5f;
    float specular_tint = 0.f;
    float roughness = 0.5f;
    float anisotropic = 0.f;
    float sheen = 0.f;
    float sheen_tint = 0.5f;
    float clearcoat = 0.f;
    float clearcoat_roughness = 0.03f;
    float ior = 1.45f;
    float transmission = 0.f;
    float transmission_roughness = 0.f;  // not yet used: the glass lobe has one roughness
    bool backfacing = false;             // the path arrives on the back face: the glass sees 1/ior
};

/// The closure list Cycles 3.4's svm/closure.h builds for Principled v1 (docs/conventions.md §5).
Bsdf principled_bsdf(const PrincipledParams& p);

/// Glass node (Cycles: GGX/Beckmann/Sharp glass; roughness² = α). Refraction node: refraction_only.
inline Bsdf glass_bsdf(Color color, float roughness, float ior, bool backfacing,
                       MicrofacetDistribution d = MicrofacetDistribution::GGX, bool refraction_only = false) {
    const float a = clamp(roughness, 0.f, 1.f) * clamp(roughness, 0.f, 1.f);
    const float i = std::fmax(ior, 1e-5f);
    MicrofacetDielectric g{Microfacet{d, a, a}, backfacing ? 1.f / i : i, Color(1.f), Color(1.f), refraction_only};
    return Bsdf(g, color);
}

// Free-function interface used by the integrators. `uc` picks the lobe; the default 0.5 is only for
// single-lobe callers (it would bias a multi-lobe BSDF).
inline Color bsdf_f(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) {
    return b.f(wo, wi, mode);
}
inline float bsdf_pdf(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) {
    return b.pdf(wo, wi, mode);
}
inline BsdfSample bsdf_sample(const Bsdf& b, const Vec3& wo, Vec2 u, float uc = 0.5f,
                              TransportMode mode = TransportMode::Radiance) {
    return b.sample(wo, u, uc, mode);
}

}  // namespace candela
