// Building blocks of the quasi-Monte Carlo samplers: the van der Corput radical inverse (base 2 by bit
// reversal, any base by a digit loop), the unscrambled Halton and Hammersley points, the first two
// dimensions of the Sobol sequence (closed-form generator matrices: the identity and the Pascal matrix
// mod 2), base-2 Owen scrambling by hashing (Burley 2020, "Practical Hash-based Owen Scrambling",
// JCGT 9(4): every bit is flipped by a hash of the more significant bits), Owen scrambling in any base
// (a hashed permutation of each digit, seeded by the digits before it), and hashed random permutations
// of {0, …, n−1} used to shuffle strata.
//
// References: Pharr, Jakob & Humphreys, PBRT 4th ed., §8.6–8.7 (radical inverse, Halton, Sobol,
// scrambling); Owen 1995, "Randomly permuted (t,m,s)-nets and (t,s)-sequences"; Kensler 2013,
// "Correlated Multi-Jittered Sampling" (cycle-walking hashed permutations).
#pragma once

#include <cstdint>

#include "core/math.h"
#include "core/rng.h"

namespace candela {

/// Number of primes in prime(): Halton uses one per dimension up to this many.
inline constexpr int k_num_primes = 1024;
/// The i-th prime (prime(0) = 2), i < k_num_primes.
uint32_t prime(int index);

inline uint32_t reverse_bits32(uint32_t v) {
    v = __builtin_bswap32(v);  // bytes, then nibbles, bit pairs and bits within each byte
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    return ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
}

/// Φ_b(a) for a base b ≥ 2: the digits of a mirrored about the radix point (exact for base 2 when a < 2^32).
double radical_inverse_base(uint32_t base, uint64_t a);
/// Φ_{prime(base_index)}(a); base_index 0 is base 2, computed by bit reversal: reverse_bits32(a)·2⁻³².
double radical_inverse(int base_index, uint64_t a);

/// Unscrambled Halton point i, coordinate `dim`: Φ_{prime(dim)}(i).
inline double halton(int dim, uint64_t i) { return radical_inverse(dim, i); }
/// Unscrambled Hammersley point i of n, coordinate `dim`: i/n for dim 0, then Φ_{prime(dim−1)}(i).
inline double hammersley(int dim, uint64_t i, uint64_t n) {
    return dim == 0 ? double(i) / double(n) : radical_inverse(dim - 1, i);
}

/// The first two Sobol dimensions as 32-bit fixed-point fractions (MSB = first binary digit).
/// Together they form a (0,2)-sequence in base 2: every aligned block of 2^m indices is a (0,m,2)-net.
inline uint32_t sobol_dim0(uint32_t i) { return reverse_bits32(i); }
/// Sobol dimension 1 by its generator matrix (direction number of bit j: v_0 = 2^31, v_{j+1} = v_j ^ v_j >> 1),
/// bit-by-bit: the reference the transform below is checked against.
constexpr uint32_t sobol_dim1_bitwise(uint32_t i) {
    uint32_t r = 0;
    for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1u) r ^= v;
    return r;
}
/// reverse_bits32(sobol_dim1(i)), without the reversal. Direction number v_k has bit 31 − j set iff C(k, j) is
/// odd, i.e. (Lucas) iff j ⊆ k as bit sets; so bit j of the reversed result is the XOR of the index bits i_k
/// over all k ⊇ j — a superset-XOR transform over the five bits of the position, one shift-mask-xor per bit.
/// Branch- and table-free (the same steps run in SIMD lanes, sampling/sobol_x8.h).
inline uint32_t sobol_dim1_reversed(uint32_t i) {
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0f0f0f0fu;
    i ^= (i >> 8) & 0x00ff00ffu;
    i ^= (i >> 16) & 0x0000ffffu;
    return i;
}
inline uint32_t sobol_dim1(uint32_t i) { return reverse_bits32(sobol_dim1_reversed(i)); }

/// The seed-dependent constants of owen_lsb_hash: one mix of the seed gives 64 random bits, and the constants
/// are that word and two odd-multiplied rotations of it (cheap, and as random as the word itself for
/// scrambling purposes). Separate so that a caller scrambling many values with one seed derives them once.
struct OwenKey {
    uint32_t add0, xmul0, mul1, add1, xmul2, mul2;
};
inline OwenKey owen_key(uint64_t seed) {
    const uint64_t h0 = mix64(seed ^ 0x6a09e667f3bcc909ULL);
    const uint64_t h1 = rotl64(h0 * 0xbb67ae8584caa73bULL, 29), h2 = rotl64(h0 * 0x3c6ef372fe94f82bULL, 43);
    return {uint32_t(h0),       uint32_t(h0 >> 32) << 1, uint32_t(h1) | 1u,
            uint32_t(h1 >> 32), uint32_t(h2) << 1,       uint32_t(h2 >> 32) | 1u};
}

/// A bijection of 32-bit words in which output bit k equals input bit k XOR a seeded hash of the input
/// bits below k (so it is an Owen scramble of the bit-reversed word).
inline uint32_t owen_lsb_hash(uint32_t x, const OwenKey& k) {
    // Every step is triangular: bit k changes only through bits < k (adding, multiplying by an odd
    // number, xoring in a multiple by an even number).
    x += k.add0;
    x ^= x * k.xmul0;
    x *= k.mul1;
    x += k.add1;
    x ^= x * k.xmul2;
    x *= k.mul2;
    x ^= x * (0x2c1b3c6du << 1);
    return x;
}
inline uint32_t owen_lsb_hash(uint32_t x, uint64_t seed) { return owen_lsb_hash(x, owen_key(seed)); }

/// Burley 2020's keyed hash (§3: the Laine–Karras construction with his improved constants), the scramble the
/// Sobol sampler applies on every draw: five triangular steps (multiplying by an even constant, adding the seed,
/// multiplying by an odd seed-derived number), so output bit k is input bit k XOR a function of the seed and the
/// input bits below k — an Owen scramble of the bit-reversed word, with no per-seed set-up.
inline uint32_t burley_lsb_hash(uint32_t x, uint32_t seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}
/// Base-2 Owen scrambling of a 32-bit word (most significant bit first) by burley_lsb_hash.
inline uint32_t owen_scramble_fast(uint32_t v, uint32_t seed) {
    return reverse_bits32(burley_lsb_hash(reverse_bits32(v), seed));
}

/// Base-2 Owen scrambling of a 32-bit word: bit k (from the most significant) is flipped by a hash of the
/// bits above it. Applied to a fixed-point fraction it is a nested uniform scramble (each scrambled value
/// is uniform, nets stay nets); applied to an index it maps every aligned block of 2^m indices onto an
/// aligned block of 2^m indices.
inline uint32_t owen_scramble_base2(uint32_t v, uint64_t seed) {
    return reverse_bits32(owen_lsb_hash(reverse_bits32(v), seed));
}

/// Owen-scrambled Φ_b(a): digit k is replaced by a random permutation of {0..b−1} seeded by the seed and
/// the digits before it. Digits are permuted as far as a or max_index have digits (pass the largest index
/// of the point set so all its points share the permutations); below that the scrambled zero digits are
/// independent uniform digits, drawn at once as a uniform tail.
double owen_radical_inverse(uint32_t base, uint64_t a, uint64_t seed, uint64_t max_index = 0);

/// Element i of a random permutation of {0, …, n−1} chosen by `seed` (hashed bijection on the next power of
/// two, cycle-walked into range). i < n.
uint32_t permute_index(uint32_t i, uint32_t n, uint64_t seed);

/// A 32-bit fixed-point fraction as a float in [0, 1): the top 24 bits, exactly.
inline float fixed_to_float(uint32_t v) { return float(v >> 8) * 0x1p-24f; }
/// A double in [0, 1] as a float in [0, 1).
inline float to_unit_float(double v) { return std::min(float(v), k_one_minus_epsilon); }

}  // namespace candela
