// Eight shuffled, Owen-scrambled Sobol values at once (Burley 2020, "Practical Hash-based Owen Scrambling",
// JCGT 9(4)): lane k is coordinate x (Sobol dimension 0) or y (dimension 1) of the 2-D request at dimension
// dims[k] of one pixel sample. Every lane runs the same integer steps as SobolSampler's one-at-a-time draws —
//   seeds        s = hash32(pixel_seed + (4·dim + purpose)·φ)          (purpose 1: shuffle, 2: x, 3: y)
//   shuffle      i = reverse(burley_lsb_hash(reverse(index), s_shuffle))
//   value input  x lanes: i;  y lanes: sobol_dim1_reversed(i)   (both in the bit-reversed domain)
//   value        reverse(burley_lsb_hash(input, s_value)) as a 24-bit float
// — so the results are bit-identical; with AVX2 the eight lanes share each instruction, which makes a path
// vertex's five requests (light selection, light point, BSDF direction, roulette, lobe) one batch instead of
// ~20 scalar hashes and bit reversals.
#pragma once

#include <cstdint>

#include "core/rng.h"
#include "sampling/low_discrepancy.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace candela {

inline constexpr uint32_t k_sobol_seed_step = 0x9e3779b9u;  // φ·2³²: seeds of successive (dim, purpose) pairs

/// Seed of one scramble (purpose 1: index shuffle, 2: first coordinate, 3: second) of request `dim`.
inline uint32_t sobol_seed(uint32_t pixel_seed, uint32_t dim, uint32_t purpose) {
    return hash32(pixel_seed + (4u * dim + purpose) * k_sobol_seed_step);
}

/// Lane k of the batch, one at a time: the definition the SIMD path must reproduce.
inline float sobol_lane(uint32_t pixel_seed, uint32_t reversed_index, uint32_t dim, bool y) {
    const uint32_t i = reverse_bits32(burley_lsb_hash(reversed_index, sobol_seed(pixel_seed, dim, 1)));
    const uint32_t input = y ? sobol_dim1_reversed(i) : i;
    return fixed_to_float(reverse_bits32(burley_lsb_hash(input, sobol_seed(pixel_seed, dim, y ? 3u : 2u))));
}

/// out[k] = sobol_lane(pixel_seed, reversed_index, dims[k], bit k of y_lanes).
inline void sobol_x8_scalar(uint32_t pixel_seed, uint32_t reversed_index, const uint32_t (&dims)[8], uint32_t y_lanes,
                            float (&out)[8]) {
    for (int k = 0; k < 8; ++k) out[k] = sobol_lane(pixel_seed, reversed_index, dims[k], ((y_lanes >> k) & 1u) != 0);
}

/// The batch split in two, so that the part that does not depend on the sample index can be computed once per
/// pixel and reused by all of its samples (SobolSampler caches it per bounce).
///
/// burley_lsb_hash(x, s) = h(x ^ x·c₁ + s) with h(y) = z ^ z·c₃ where z = y·m ^ y·m₂, m = (s >> 16) | 1 and
/// m₂ = m·c₂: (y·m)·c₂ = y·(m·c₂) mod 2³², so the two multiplies of the middle step run side by side, one less
/// on the dependency chain. The seed part of a lane is (s, m₂) for the shuffle and for the value scramble.
struct SobolSeedsX8 {
    alignas(32) uint32_t shuffle[8];     // s_shuffle per lane
    alignas(32) uint32_t shuffle_m2[8];  // ((s_shuffle >> 16) | 1)·c₂
    alignas(32) uint32_t value[8];       // s_value (purpose 2 for x lanes, 3 for y lanes)
    alignas(32) uint32_t value_m2[8];    // ((s_value >> 16) | 1)·c₂
};
inline constexpr uint32_t k_burley_c1 = 0x3d20adeau, k_burley_c2 = 0x05526c56u, k_burley_c3 = 0x53a22864u;

/// The first step of burley_lsb_hash, which for the shuffle depends only on the (reversed) sample index.
inline uint32_t sobol_premix(uint32_t reversed_index) { return reversed_index ^ reversed_index * k_burley_c1; }
inline uint32_t burley_m2(uint32_t seed) { return ((seed >> 16) | 1u) * k_burley_c2; }
/// burley_lsb_hash after its first step, with the seed's m₂ precomputed.
inline uint32_t burley_lsb_hash_tail(uint32_t x, uint32_t seed, uint32_t m2) {
    x += seed;
    x = (x * ((seed >> 16) | 1u)) ^ (x * m2);
    return x ^ x * k_burley_c3;
}

#if defined(__AVX2__)
namespace simd {

inline __m256i mul(__m256i a, uint32_t c) { return _mm256_mullo_epi32(a, _mm256_set1_epi32(int(c))); }

inline __m256i hash32(__m256i x) {
    x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
    x = mul(x, 0x7feb352du);
    x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 15));
    x = mul(x, 0x846ca68bu);
    return _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
}

inline __m256i seed_multiplier(__m256i seed) {
    return _mm256_or_si256(_mm256_srli_epi32(seed, 16), _mm256_set1_epi32(1));
}

/// burley_lsb_hash_tail: x is the input after burley_lsb_hash's first step.
inline __m256i burley_lsb_hash_tail(__m256i x, __m256i seed, __m256i m2) {
    x = _mm256_add_epi32(x, seed);
    x = _mm256_xor_si256(_mm256_mullo_epi32(x, seed_multiplier(seed)), _mm256_mullo_epi32(x, m2));
    return _mm256_xor_si256(x, mul(x, k_burley_c3));
}

/// Bit reversal of each 32-bit lane: bytes swapped by a shuffle, then each byte's nibbles mirrored by two
/// 16-entry lookups.
inline __m256i reverse_bits(__m256i v) {
    const __m256i bswap = _mm256_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12,  //
                                           3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
    // rev4[n] = n with its 4 bits mirrored; the high-nibble table holds rev4[n] << 4.
    const __m256i rev_lo = _mm256_setr_epi8(0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15,  //
                                            0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15);
    const __m256i rev_hi = _mm256_slli_epi16(rev_lo, 4);
    const __m256i nibble = _mm256_set1_epi8(0x0f);
    v = _mm256_shuffle_epi8(v, bswap);
    const __m256i lo = _mm256_and_si256(v, nibble), hi = _mm256_and_si256(_mm256_srli_epi16(v, 4), nibble);
    return _mm256_or_si256(_mm256_shuffle_epi8(rev_hi, lo), _mm256_shuffle_epi8(rev_lo, hi));
}

inline __m256i sobol_dim1_reversed(__m256i i) {
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 1), _mm256_set1_epi32(0x55555555)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 2), _mm256_set1_epi32(0x33333333)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 4), _mm256_set1_epi32(0x0f0f0f0f)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 8), _mm256_set1_epi32(0x00ff00ff)));
    return _mm256_xor_si256(i, _mm256_srli_epi32(i, 16));
}

inline __m256i lane_mask(uint32_t lanes) {
    const __m256i lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(lanes)), lane_bits), lane_bits);
}

inline __m256i load(const uint32_t (&a)[8]) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(a)); }
inline void store(uint32_t (&a)[8], __m256i v) { _mm256_store_si256(reinterpret_cast<__m256i*>(a), v); }

}  // namespace simd
#endif

/// The seed part of the batch from the seeds' hash inputs: lane k's shuffle seed is hash32(base + shuffle_words[k])
/// and its value seed hash32(base + value_words[k]); sobol_seed(pixel_seed, dim, purpose) is base = pixel_seed,
/// word = (4·dim + purpose)·φ. (A caller whose dimensions move together splits the words differently: words mod 2³²
/// add, so any split of the sum gives the same seeds.)
inline void sobol_seeds_x8_words(uint32_t base, const uint32_t (&shuffle_words)[8], const uint32_t (&value_words)[8],
                                 SobolSeedsX8& out) {
#if defined(__AVX2__)
    using namespace simd;
    const __m256i b = _mm256_set1_epi32(int(base));
    const __m256i s_shuffle =
        hash32(_mm256_add_epi32(b, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(shuffle_words))));
    const __m256i s_value =
        hash32(_mm256_add_epi32(b, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(value_words))));
    store(out.shuffle, s_shuffle);
    store(out.shuffle_m2, mul(seed_multiplier(s_shuffle), k_burley_c2));
    store(out.value, s_value);
    store(out.value_m2, mul(seed_multiplier(s_value), k_burley_c2));
#else
    for (int k = 0; k < 8; ++k) {
        out.shuffle[k] = hash32(base + shuffle_words[k]);
        out.shuffle_m2[k] = burley_m2(out.shuffle[k]);
        out.value[k] = hash32(base + value_words[k]);
        out.value_m2[k] = burley_m2(out.value[k]);
    }
#endif
}

/// The seed part of the batch for lanes at dimensions dims with y lanes y_lanes (bit k: lane k is a y lane).
inline void sobol_seeds_x8(uint32_t pixel_seed, const uint32_t (&dims)[8], uint32_t y_lanes, SobolSeedsX8& out) {
    uint32_t shuffle_words[8], value_words[8];
    for (int k = 0; k < 8; ++k) {
        shuffle_words[k] = (4u * dims[k] + 1u) * k_sobol_seed_step;
        value_words[k] = (4u * dims[k] + (((y_lanes >> k) & 1u) != 0 ? 3u : 2u)) * k_sobol_seed_step;
    }
    sobol_seeds_x8_words(pixel_seed, shuffle_words, value_words, out);
}

/// The batch from its seed part: out[k] = sobol_lane(pixel_seed, reversed_index, dims[k], bit k of y_lanes) for the
/// pixel_seed and dims `seeds` were made from, with premixed = sobol_premix(reversed_index).
inline void sobol_x8_seeded(const SobolSeedsX8& seeds, uint32_t premixed, uint32_t y_lanes, float (&out)[8]) {
#if defined(__AVX2__)
    using namespace simd;
    const __m256i s_value = load(seeds.value);
    const __m256i i = reverse_bits(
        burley_lsb_hash_tail(_mm256_set1_epi32(int(premixed)), load(seeds.shuffle), load(seeds.shuffle_m2)));
    const __m256i input = _mm256_blendv_epi8(i, sobol_dim1_reversed(i), lane_mask(y_lanes));
    const __m256i v = reverse_bits(
        burley_lsb_hash_tail(_mm256_xor_si256(input, mul(input, k_burley_c1)), s_value, load(seeds.value_m2)));
    // fixed_to_float: the top 24 bits, exactly representable, times 2⁻²⁴.
    const __m256 f = _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_srli_epi32(v, 8)), _mm256_set1_ps(0x1p-24f));
    _mm256_storeu_ps(out, f);
#else
    for (int k = 0; k < 8; ++k) {
        const uint32_t i = reverse_bits32(burley_lsb_hash_tail(premixed, seeds.shuffle[k], seeds.shuffle_m2[k]));
        const uint32_t input = ((y_lanes >> k) & 1u) != 0 ? sobol_dim1_reversed(i) : i;
        out[k] = fixed_to_float(
            reverse_bits32(burley_lsb_hash_tail(sobol_premix(input), seeds.value[k], seeds.value_m2[k])));
    }
#endif
}

/// out[k] = sobol_lane(pixel_seed, reversed_index, dims[k], bit k of y_lanes), seeds computed on the spot.
inline void sobol_x8(uint32_t pixel_seed, uint32_t reversed_index, const uint32_t (&dims)[8], uint32_t y_lanes,
                     float (&out)[8]) {
    SobolSeedsX8 seeds;
    sobol_seeds_x8(pixel_seed, dims, y_lanes, seeds);
    sobol_x8_seeded(seeds, sobol_premix(reversed_index), y_lanes, out);
}

}  // namespace candela
