#include "bsdf/bsdf_filters.h"

#include <type_traits>

namespace candela {

namespace {

Microfacet blurred(Microfacet m, float alpha) {
    m.alpha_x = std::fmax(m.alpha_x, alpha);
    m.alpha_y = std::fmax(m.alpha_y, alpha);
    return m;
}

}  // namespace

Bsdf blur_bsdf(const Bsdf& b, float alpha) {
    Bsdf out;
    for (int i = 0; i < b.size(); ++i) {
        BsdfLobe lobe = b[i].lobe;
        std::visit(
            [&](auto& l) {
                using T = std::decay_t<decltype(l)>;
                if constexpr (std::is_same_v<T, MicrofacetReflection> || std::is_same_v<T, MicrofacetDielectric>)
                    l.distribution = blurred(l.distribution, alpha);
                else if constexpr (std::is_same_v<T, ClearcoatBsdf>)
                    l.alpha = std::fmax(l.alpha, alpha);
            },
            lobe);
        out.add(lobe, b[i].weight);
    }
    out.set_bump_shadowing(b.bump_shadowing());
    return out;
}

bool has_microfacet_lobe(const Bsdf& b) {
    for (int i = 0; i < b.size(); ++i)
        if (std::holds_alternative<MicrofacetReflection>(b[i].lobe) ||
            std::holds_alternative<MicrofacetDielectric>(b[i].lobe) || std::holds_alternative<ClearcoatBsdf>(b[i].lobe))
            return true;
    return false;
}

Bsdf caustics_filter(const Bsdf& b, float cos_o, bool reflective, bool refractive) {
    Bsdf out;
    for (int i = 0; i < b.size(); ++i) {
        const WeightedLobe& wl = b[i];
        if (std::holds_alternative<MicrofacetReflection>(wl.lobe) || std::holds_alternative<ClearcoatBsdf>(wl.lobe)) {
            if (reflective) out.add(wl.lobe, wl.weight);
        } else if (const auto* g = std::get_if<MicrofacetDielectric>(&wl.lobe)) {
            if (g->refraction_only) {
                if (refractive) out.add(wl.lobe, wl.weight);
            } else if (reflective && refractive) {
                out.add(wl.lobe, wl.weight);
            } else if (reflective || refractive) {
                const float F = fresnel_dielectric(cos_o, g->eta);
                if (reflective) {
                    out.add(MicrofacetReflection{g->distribution, SpecularFresnel{}}, wl.weight * g->tint_r * F);
                } else {
                    MicrofacetDielectric t = *g;
                    t.refraction_only = true;
                    out.add(t, wl.weight * g->tint_t * std::fmax(1e-4f, 1.f - F));
                }
            }
        } else {
            out.add(wl.lobe, wl.weight);
        }
    }
    out.set_bump_shadowing(b.bump_shadowing());
    return out;
}

bool caustics_filter_changes(const Bsdf& b, bool reflective, bool refractive) {
    if (reflective && refractive) return false;
    for (int i = 0; i < b.size(); ++i) {
        const BsdfLobe& l = b[i].lobe;
        if (std::holds_alternative<MicrofacetReflection>(l) || std::holds_alternative<ClearcoatBsdf>(l)) {
            if (!reflective) return true;
        } else if (const auto* g = std::get_if<MicrofacetDielectric>(&l)) {
            if (!refractive || !g->refraction_only) return true;
        }
    }
    return false;
}

Color transparency(const Bsdf& b) {
    Color t(0.f);
    for (int i = 0; i < b.size(); ++i)
        if (std::holds_alternative<TransparentBsdf>(b[i].lobe)) t += b[i].weight;
    return t;
}

}  // namespace candela
