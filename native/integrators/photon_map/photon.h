// A stored photon in 18 bytes (docs/photon-mapping.md, "Memory"): its position (3 floats: the kd-tree searches
// them, and a search radius of 10⁻⁴ of the scene must still resolve), its flux as shared-exponent RGB (9-bit
// mantissas and a 5-bit exponent, relative to the map's flux scale) and the direction it arrived from
// (octahedral, 8 + 8 bits). Jensen stores 20 bytes (position, RGBE power, two direction angles, a split flag); the
// split flag lives in the kd-tree here.
//
// The flux is rounded stochastically: with u uniform in [0, 1) each mantissa is ⌊x + u⌋, whose expectation is x,
// so a density estimate over many photons keeps no rounding bias (all photons of a point light carry one flux,
// and a deterministic rounding would shift every estimate by the same up to 0.2 %). The exponent is chosen from
// the flux alone, so the rounding stays unbiased, also below 2⁻²¹ of the scale (there the mantissas are small and
// the rounding coarse, still unbiased); values beyond 2¹¹ times the scale are clamped (never reached by photons that
// Russian roulette keeps near their parents' power).
// The direction is rounded to the nearest of the 2¹⁶ octahedral directions (at most 0.6° off): it only feeds
// the BSDF, which the estimated lobes keep wider than a few degrees (common/lobe_classes.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

struct __attribute__((packed)) Photon {
    float x, y, z;
    uint32_t flux;  // shared-exponent RGB relative to the map's scale (encode_flux)
    uint16_t dir;   // octahedral unit direction toward where the photon came from (encode_direction)

    Vec3 position() const { return {x, y, z}; }
};
static_assert(sizeof(Photon) == 18, "a photon is 18 bytes");

inline constexpr int k_flux_exponent_bias = 20;

/// 2^k for a normal result (k in [−126, 127]), exactly std::ldexp(1.f, k) there, built from the bits.
inline float pow2(int k) {
    const uint32_t bits = uint32_t(k + 127) << 23;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

/// std::round (halves away from zero) for |x| < 2²³ or NaN, inline: x − floor(x) is exact there.
inline float round_half_away(float x) {
    const float a = std::fabs(x), r = std::floor(a);
    return std::copysign(a - r >= 0.5f ? r + 1.f : r, x);
}  // value = m·2^(e − bias − 9), e in [0, 31], m in [0, 511]

/// Shared-exponent encoding of the non-negative colour c (already divided by the map's scale), rounded
/// stochastically with u in [0, 1).
inline uint32_t encode_flux(const Color& c, float u) {
    const float m = max_component(c);
    if (!(m > 0.f) || !std::isfinite(m)) return 0u;
    int e2 = 0;  // m = f·2^e2, f in [0.5, 1) (frexp; read off the bits for a normal m)
    uint32_t bits;
    std::memcpy(&bits, &m, sizeof bits);
    if (bits >= 0x00800000u)
        e2 = int(bits >> 23) - 126;
    else
        std::frexp(m, &e2);
    int e = std::max(e2 + k_flux_exponent_bias, 0);  // below 2⁻²¹ of the scale: the smallest exponent
    float scale = pow2(9 - (e - k_flux_exponent_bias));
    if (m * scale > 511.f && e < 31) {  // the largest mantissa must stay below 512 after rounding up
        ++e;
        scale *= 0.5f;
    }
    if (e > 31) {  // beyond 2¹¹ of the scale: clamp
        e = 31;
        scale = pow2(9 - (31 - k_flux_exponent_bias));
    }
    // min(x, 511) as fmin (a NaN x gives 511) without the library call.
    auto min511 = [](float x) { return x < 511.f ? x : 511.f; };
    auto mant = [&](float v) { return uint32_t(min511(std::floor(min511(v * scale) + u))); };
    return mant(c.x) | (mant(c.y) << 9) | (mant(c.z) << 18) | (uint32_t(e) << 27);
}

inline Color decode_flux(uint32_t v) {
    const int e = int(v >> 27);
    const float scale = std::ldexp(1.f, e - k_flux_exponent_bias - 9);
    return Color(float(v & 511u), float((v >> 9) & 511u), float((v >> 18) & 511u)) * scale;
}

/// Octahedral encoding of a unit vector (Meyer et al. 2010), 8 bits per axis, rounded to nearest.
inline uint16_t encode_direction(const Vec3& d) {
    const float l1 = std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z);
    float u = d.x / l1, v = d.y / l1;
    if (d.z < 0.f) {
        const float uu = (1.f - std::fabs(v)) * (u >= 0.f ? 1.f : -1.f);
        const float vv = (1.f - std::fabs(u)) * (v >= 0.f ? 1.f : -1.f);
        u = uu;
        v = vv;
    }
    auto q = [](float t) { return uint32_t(clamp(round_half_away((t * 0.5f + 0.5f) * 255.f), 0.f, 255.f)); };
    return uint16_t(q(u) | (q(v) << 8));
}

inline Vec3 decode_direction(uint16_t e) {
    const float u = float(e & 255u) / 255.f * 2.f - 1.f, v = float(e >> 8) / 255.f * 2.f - 1.f;
    Vec3 d(u, v, 1.f - std::fabs(u) - std::fabs(v));
    if (d.z < 0.f) {
        const float x = (1.f - std::fabs(v)) * (u >= 0.f ? 1.f : -1.f);
        const float y = (1.f - std::fabs(u)) * (v >= 0.f ? 1.f : -1.f);
        d.x = x;
        d.y = y;
    }
    return normalize(d);
}

}  // namespace candela
