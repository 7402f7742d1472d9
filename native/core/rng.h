// Random numbers: PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
// algorithms for random number generation", pcg32 XSH-RR 64/32) plus integer hashing used to derive
// independent streams from (seed, pixel, sample index). Images therefore depend only on those numbers,
// never on thread count or tile order.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace candela {

/// 64-bit finaliser of MurmurHash3 (fmix64): a bijection with full avalanche.
inline uint64_t mix64(uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    k *= 0xc4ceb9fe1a85ec53ULL;
    k ^= k >> 33;
    return k;
}

/// 32-bit integer hash (Wellons' "lowbias32": xorshift-multiply, bias ~0.17): a bijection, cheap in SIMD lanes.
inline uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

inline uint64_t rotl64(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

/// Hash of several integers, order-sensitive.
inline uint64_t hash_combine(uint64_t a, uint64_t b) {
    return mix64(a ^ (mix64(b) + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}
inline uint64_t hash_values(uint64_t a, uint64_t b, uint64_t c) { return hash_combine(hash_combine(mix64(a), b), c); }

class Pcg32 {
public:
    Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
    Pcg32(uint64_t state_seed, uint64_t stream) { seed(state_seed, stream); }

    void seed(uint64_t state_seed, uint64_t stream) {
        m_state = 0u;
        m_inc = (stream << 1u) | 1u;
        next_u32();
        m_state += state_seed;
        next_u32();
    }

    uint32_t next_u32() {
        const uint64_t old = m_state;
        m_state = old * 0x5851f42d4c957f2dULL + m_inc;
        const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }

    /// Uniform float in [0, 1): the top 24 bits scaled by 2^-24, so it never reaches 1.
    float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

private:
    uint64_t m_state = 0, m_inc = 0;
};

}  // namespace candela
