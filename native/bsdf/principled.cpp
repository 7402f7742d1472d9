// Principled BSDF v1 as Cycles 3.4's svm/closure.h (NODE_CLOSURE_BSDF, CLOSURE_BSDF_PRINCIPLED_ID)
// assembles it from closures: diffuse, sheen, specular, glass, clearcoat.
#include "bsdf/bsdf.h"

namespace candela {

namespace {
constexpr float k_weight_cutoff = 1e-5f;  // Cycles' CLOSURE_WEIGHT_CUTOFF
}

Bsdf principled_bsdf(const PrincipledParams& p) {
    const float metallic = clamp(p.metallic, 0.f, 1.f);
    const float transmission = clamp(p.transmission, 0.f, 1.f);
    const float specular_tint = clamp(p.specular_tint, 0.f, 1.f);
    const float roughness = clamp(p.roughness, 0.f, 1.f);
    const Color base = p.base_color;

    const float diffuse_weight = (1.f - metallic) * (1.f - transmission);
    const float final_transmission = transmission * (1.f - metallic);
    const float specular_weight = 1.f - final_transmission;

    // Cycles normalises the base colour by an approximate luminance (0.3, 0.6, 0.1) to isolate hue.
    const float cd_lum = 0.3f * base.x + 0.6f * base.y + 0.1f * base.z;
    const Color c_tint = cd_lum > 0.f ? base / cd_lum : Color(1.f);

    Bsdf b;
    if (diffuse_weight > k_weight_cutoff) {
        const float ss = clamp(p.subsurface, 0.f, 1.f);
        const Color diffuse_color = base * (1.f - ss) + p.subsurface_color * ss;  // no BSSRDF yet
        b.add(PrincipledDiffuseBsdf{roughness}, diffuse_color * diffuse_weight);
        if (p.sheen > k_weight_cutoff) {
            const float st = clamp(p.sheen_tint, 0.f, 1.f);
            const Color sheen_color = Color(1.f - st) + c_tint * st;
            b.add(PrincipledSheenBsdf{}, sheen_color * (p.sheen * diffuse_weight));
        }
    }
    if (specular_weight > k_weight_cutoff && (p.specular > k_weight_cutoff || metallic > k_weight_cutoff)) {
        const float aspect = safe_sqrt(1.f - clamp(p.anisotropic, 0.f, 1.f) * 0.9f);
        const float r2 = roughness * roughness;
        MicrofacetReflection spec;
        spec.distribution = Microfacet{MicrofacetDistribution::GGX, r2 / aspect, r2 * aspect};
        const Color tmp_col = Color(1.f - specular_tint) + c_tint * specular_tint;
        spec.fresnel.kind = SpecularFresnel::Principled;
        spec.fresnel.cspec0 = tmp_col * (std::fmax(p.specular, 0.f) * 0.08f) * (1.f - metallic) + base * metallic;
        spec.fresnel.ior = 2.f / (1.f - safe_sqrt(std::fmin(0.08f * std::fmax(p.specular, 0.f), 0.99f))) - 1.f;
        b.add(spec, Color(specular_weight));
    }
    if (final_transmission > k_weight_cutoff) {
        const float ior = std::fmax(p.ior, 1e-5f);
        MicrofacetDielectric glass;
        glass.distribution = Microfacet{MicrofacetDistribution::GGX, roughness * roughness, roughness * roughness};
        glass.eta = p.backfacing ? 1.f / ior : ior;
        glass.tint_r = base * specular_tint + Color(1.f - specular_tint);
        glass.tint_t = base;
        b.add(glass, Color(final_transmission));
    }
    if (p.clearcoat > k_weight_cutoff) {
        const float cr = clamp(p.clearcoat_roughness, 0.f, 1.f);
        b.add(ClearcoatBsdf{cr * cr}, Color(0.25f * p.clearcoat));
    }
    return b;
}

}  // namespace candela
