// Which lobes of a BSDF are ray traced and which are estimated from photons, for the integrators that estimate
// radiance by density estimation (PHOTON, SPPM; docs/photon-mapping.md, "Traced and estimated lobes"):
//
//   traced (T)     delta lobes (mirror, smooth glass, transparency) and glossy lobes narrower than a threshold
//                  (roughness r with α = r² below α_t in either direction): a density estimate would blur them,
//                  so camera paths follow them by sampling, and a photon path whose scatterings so far are all
//                  traced is a caustic path (L S+ …);
//   estimated (E)  every other lobe (diffuse, translucent, sheen, glossy at or above the threshold): photons are
//                  stored where a surface has one, and radiance leaving through them is a density estimate.
//
// A BSDF is split into its T and E lobes with their weights unchanged, so f = f_T + f_E exactly, and each part is
// sampled by its own lobe selection: an estimator that treats the parts separately (or picks one with a
// probability) stays unbiased for the whole BSDF.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <variant>

#include "bsdf/bsdf.h"

namespace candela {

/// The Blender roughness below which a glossy lobe is traced by default (α = 0.0625): a GGX lobe that narrow
/// spans a few degrees, about what one density estimate over ~50 photons resolves.
inline constexpr float k_default_traced_roughness = 0.25f;

/// The narrowest α of a lobe (∞ for lobes without one: diffuse, translucent, sheen).
inline float lobe_alpha(const BsdfLobe& lobe) {
    return std::visit(
        [](const auto& l) -> float {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, MicrofacetReflection> || std::is_same_v<T, MicrofacetDielectric>)
                return std::fmin(l.distribution.alpha_x, l.distribution.alpha_y);
            else if constexpr (std::is_same_v<T, ClearcoatBsdf>)
                return std::fmax(l.alpha, 1e-3f);
            else
                return std::numeric_limits<float>::infinity();
        },
        lobe);
}

/// Whether a lobe is traced: a delta lobe, or a glossy one with α below alpha_threshold.
inline bool lobe_traced(const BsdfLobe& lobe, float alpha_threshold) {
    const uint32_t flags = std::visit([](const auto& l) { return l.flags(); }, lobe);
    if (flags & k_bsdf_specular) return true;
    return (flags & k_bsdf_glossy) && lobe_alpha(lobe) < alpha_threshold;
}

/// Bit i set: lobe i of `bsdf` is traced.
inline uint32_t traced_lobe_mask(const Bsdf& bsdf, float alpha_threshold) {
    uint32_t mask = 0;
    for (int i = 0; i < bsdf.size(); ++i)
        if (lobe_traced(bsdf[i].lobe, alpha_threshold)) mask |= 1u << i;
    return mask;
}

/// The lobes of `bsdf` whose bit in `traced_mask` equals `traced`, with their weights.
inline Bsdf lobe_subset(const Bsdf& bsdf, uint32_t traced_mask, bool traced) {
    Bsdf out;
    for (int i = 0; i < bsdf.size(); ++i)
        if (((traced_mask >> i) & 1u) == (traced ? 1u : 0u)) out.add(bsdf[i].lobe, bsdf[i].weight);
    return out;
}

/// Which part of a BSDF a vertex uses: its traced or its estimated lobes (VertexBsdf's lobe filter).
struct LobeSubset {
    float alpha_threshold = k_default_traced_roughness * k_default_traced_roughness;
    bool traced = false;
    Bsdf apply(const Bsdf& bsdf) const { return lobe_subset(bsdf, traced_lobe_mask(bsdf, alpha_threshold), traced); }
};

}  // namespace candela
