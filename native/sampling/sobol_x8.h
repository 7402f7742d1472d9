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

inline __m256i burley_lsb_hash(__m256i x, __m256i seed) {
    x = _mm256_xor_si256(x, mul(x, 0x3d20adeau));
    x = _mm256_add_epi32(x, seed);
    x = _mm256_mullo_epi32(x, _mm256_or_si256(_mm256_srli_epi32(seed, 16), _mm256_set1_epi32(1)));
    x = _mm256_xor_si256(x, mul(x, 0x05526c56u));
    return _mm256_xor_si256(x, mul(x, 0x53a22864u));
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

}  // namespace simd
#endif

inline void sobol_x8(uint32_t pixel_seed, uint32_t reversed_index, const uint32_t (&dims)[8], uint32_t y_lanes,
                     float (&out)[8]) {
#if defined(__AVX2__)
    using namespace simd;
    const __m256i dim4 = _mm256_slli_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(dims)), 2);
    const __m256i lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i y = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(y_lanes)), lane_bits), lane_bits);
    // (4·dim + purpose)·φ + pixel_seed, purpose 1 for the shuffle, 2 or 3 (x or y lane) for the value.
    const __m256i base = _mm256_set1_epi32(int(pixel_seed));
    const __m256i purpose_value = _mm256_sub_epi32(_mm256_set1_epi32(2), y);  // y lanes are all ones (−1): 3
    const __m256i s_shuffle = hash32(_mm256_add_epi32(base, mul(_mm256_add_epi32(dim4, _mm256_set1_epi32(1)), k_sobol_seed_step)));
    const __m256i s_value = hash32(_mm256_add_epi32(base, mul(_mm256_add_epi32(dim4, purpose_value), k_sobol_seed_step)));
    const __m256i i = reverse_bits(burley_lsb_hash(_mm256_set1_epi32(int(reversed_index)), s_shuffle));
    const __m256i input = _mm256_blendv_epi8(i, sobol_dim1_reversed(i), y);
    const __m256i v = reverse_bits(burley_lsb_hash(input, s_value));
    // fixed_to_float: the top 24 bits, exactly representable, times 2⁻²⁴.
    const __m256 f = _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_srli_epi32(v, 8)), _mm256_set1_ps(0x1p-24f));
    _mm256_storeu_ps(out, f);
#else
    sobol_x8_scalar(pixel_seed, reversed_index, dims, y_lanes, out);
#endif
}

}  // namespace candela
