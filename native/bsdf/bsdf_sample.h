// The result of sampling a BSDF, the lobe flags and the transport direction.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

/// Which quantity a path carries. Only refraction is non-symmetric: with η = η(wi side)/η(wo side),
/// a transmission lobe's f in Radiance mode carries the factor 1/η² (radiance is compressed into the
/// denser medium: L/η² is invariant along a ray), while Importance mode (light tracing, photons — the
/// adjoint BSDF) omits it. So f_importance = η²·f_radiance for every transmission; reflection is equal.
enum class TransportMode : uint8_t { Radiance, Importance };

/// Lobe classification (pbrt-style bit set).
enum BsdfFlags : uint32_t {
    k_bsdf_none = 0,
    k_bsdf_reflection = 1u << 0,
    k_bsdf_transmission = 1u << 1,
    k_bsdf_diffuse = 1u << 2,
    k_bsdf_glossy = 1u << 3,
    k_bsdf_specular = 1u << 4,     // delta distribution: f and pdf are only meaningful for the sampled wi
    k_bsdf_transparent = 1u << 5,  // a Transparent BSDF's pass-through (Cycles' LABEL_TRANSPARENT): not a bounce
};

struct BsdfSample {
    Color f;          // BSDF value for (wo, wi), without the cosine (for delta samples: weight/|cos θi|)
    Vec3 wi;          // sampled incident direction, local frame (z < 0 for transmission)
    float pdf = 0.f;  // solid-angle density of wi (for delta samples: the discrete probability); 0 = no sample
    float eta = 1.f;  // η(wi side)/η(wo side) for transmission, 1 otherwise
    uint32_t flags = k_bsdf_none;

    bool valid() const { return pdf > 0.f; }
    bool is_delta() const { return (flags & k_bsdf_specular) != 0; }
    bool is_transmission() const { return (flags & k_bsdf_transmission) != 0; }
    bool is_reflection() const { return (flags & k_bsdf_reflection) != 0; }
    bool is_transparent() const { return (flags & k_bsdf_transparent) != 0; }
};

}  // namespace candela
