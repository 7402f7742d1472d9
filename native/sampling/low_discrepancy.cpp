#include "sampling/low_discrepancy.h"

#include <array>

namespace candela {

namespace {

std::array<uint32_t, k_num_primes> make_primes() {
    std::array<uint32_t, k_num_primes> primes{};
    int count = 0;
    for (uint32_t n = 2; count < k_num_primes; ++n) {
        bool is_prime = true;
        for (int k = 0; k < count && primes[k] * primes[k] <= n; ++k)
            if (n % primes[k] == 0) {
                is_prime = false;
                break;
            }
        if (is_prime) primes[count++] = n;
    }
    return primes;
}

const std::array<uint32_t, k_num_primes> g_primes = make_primes();

/// Bijection of [0, mask] (mask = 2^bits − 1): rounds of xor, odd multiply, xorshift and add, all mod 2^bits.
inline uint32_t hashed_bijection(uint32_t x, uint32_t mask, int bits, uint64_t seed) {
    const int shift = bits / 2 + 1;
    seed = mix64(seed);
    for (int round = 0; round < 3; ++round) {
        seed = seed * 0x5851f42d4c957f2dULL + 0x14057b7ef767814fULL;  // LCG step: fresh round constants
        x ^= uint32_t(seed >> 32) & mask;  // the high bits of an LCG state are the random ones
        x = (x * (uint32_t(seed >> 20) | 1u)) & mask;
        x ^= x >> shift;
        x = (x + uint32_t(seed >> 27)) & mask;
        x ^= (x * (uint32_t(seed >> 36) << 1)) & mask;
        x ^= x >> 1;
    }
    return x;
}

}  // namespace

uint32_t prime(int index) { return g_primes[size_t(index)]; }

double radical_inverse_base(uint32_t base, uint64_t a) {
    if (base == 2) {
        if (a <= 0xffffffffull) return double(reverse_bits32(uint32_t(a))) * 0x1p-32;
    }
    const double inv_base = 1.0 / base;
    uint64_t reversed = 0;
    double inv_base_n = 1.0;
    while (a) {
        const uint64_t next = a / base, digit = a - next * base;
        reversed = reversed * base + digit;
        inv_base_n *= inv_base;
        a = next;
    }
    return double(reversed) * inv_base_n;
}

double radical_inverse(int base_index, uint64_t a) { return radical_inverse_base(prime(base_index), a); }

double owen_radical_inverse(uint32_t base, uint64_t a, uint64_t seed, uint64_t max_index) {
    const double inv_base = 1.0 / base;
    double weight = 1.0, result = 0.0;
    uint64_t h = seed;
    // Digits are permuted while a or max_index has digits left; 2^-27 is below the float spacing of
    // every value in [0.5, 1).
    while ((a != 0 || max_index != 0) && weight > 0x1p-27) {
        const uint64_t next = a / base;
        const uint32_t digit = uint32_t(a - next * base);
        a = next;
        max_index /= base;
        weight *= inv_base;
        result += double(permute_index(digit, base, h)) * weight;
        h = mix64(h + (digit + 1) * 0x9e3779b97f4a7c15ULL);  // the prefix of digits seen so far seeds the next
    }
    // The remaining digits of a are zeros; Owen scrambling turns them into independent uniform digits (each
    // prefix here is unique among indices ≤ max_index), i.e. a uniform tail in [0, weight).
    result += double(mix64(h ^ 0x2545f4914f6cdd1dULL) >> 11) * 0x1p-53 * weight;
    return result;
}

uint32_t permute_index(uint32_t i, uint32_t n, uint64_t seed) {
    if (n <= 1) return 0;
    int bits = 1;
    while (bits < 32 && (n - 1) >> bits) ++bits;
    const uint32_t mask = bits == 32 ? 0xffffffffu : (1u << bits) - 1u;
    do {
        i = hashed_bijection(i, mask, bits, seed);
    } while (i >= n);  // cycle walking: i lies on a cycle of the bijection, which returns into range
    // A random rotation on top makes every element's image exactly uniform over {0..n−1} (up to 2^-64),
    // however far the hashed bijections are from uniform permutations: no estimator bias from them.
    const uint64_t r = uint64_t((unsigned __int128)(mix64(seed ^ 0xd1b54a32d192ed03ULL)) * n >> 64);
    const uint64_t rotated = uint64_t(i) + r;
    return uint32_t(rotated >= n ? rotated - n : rotated);
}

}  // namespace candela
