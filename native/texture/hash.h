// Integer and float hashes of the procedural textures (docs/textures.md, "Hashes").
//
// Cycles' procedural textures hash with Bob Jenkins' lookup3 (public domain, burtleburtle.net/bob/c/lookup3.c):
// the state a = b = c = 0xdeadbeef + 4·n + 13 for n 32-bit keys, the keys added to a, b, c (a fourth key after
// one mix() round), then final() and c is the hash. Floats are hashed by their bit patterns and mapped to [0, 1]
// by n / (2³² − 1). The textures' randomness (White Noise, Voronoi's feature points, the offsets of Noise's colour
// channels) is a function of these hashes, so they must be bit-exact for the same picture as Cycles.
#pragma once

#include <cstdint>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

struct Vec4 {
    float x = 0.f, y = 0.f, z = 0.f, w = 0.f;
};

namespace lookup3 {

inline uint32_t rot(uint32_t x, int k) { return (x << k) | (x >> (32 - k)); }

inline void mix(uint32_t& a, uint32_t& b, uint32_t& c) {
    a -= c;
    a ^= rot(c, 4);
    c += b;
    b -= a;
    b ^= rot(a, 6);
    a += c;
    c -= b;
    c ^= rot(b, 8);
    b += a;
    a -= c;
    a ^= rot(c, 16);
    c += b;
    b -= a;
    b ^= rot(a, 19);
    a += c;
    c -= b;
    c ^= rot(b, 4);
    b += a;
}

inline void final(uint32_t& a, uint32_t& b, uint32_t& c) {
    c ^= b;
    c -= rot(b, 14);
    a ^= c;
    a -= rot(c, 11);
    b ^= a;
    b -= rot(a, 25);
    c ^= b;
    c -= rot(b, 16);
    a ^= c;
    a -= rot(c, 4);
    b ^= a;
    b -= rot(a, 14);
    c ^= b;
    c -= rot(b, 24);
}

constexpr uint32_t seed(uint32_t keys) { return 0xdeadbeefu + (keys << 2) + 13u; }

}  // namespace lookup3

inline uint32_t hash_uint(uint32_t kx) {
    uint32_t a = lookup3::seed(1), b = a, c = a;
    a += kx;
    lookup3::final(a, b, c);
    return c;
}
inline uint32_t hash_uint2(uint32_t kx, uint32_t ky) {
    uint32_t a = lookup3::seed(2), b = a, c = a;
    b += ky;
    a += kx;
    lookup3::final(a, b, c);
    return c;
}
inline uint32_t hash_uint3(uint32_t kx, uint32_t ky, uint32_t kz) {
    uint32_t a = lookup3::seed(3), b = a, c = a;
    c += kz;
    b += ky;
    a += kx;
    lookup3::final(a, b, c);
    return c;
}
inline uint32_t hash_uint4(uint32_t kx, uint32_t ky, uint32_t kz, uint32_t kw) {
    uint32_t a = lookup3::seed(4), b = a, c = a;
    a += kx;
    b += ky;
    c += kz;
    lookup3::mix(a, b, c);
    a += kw;
    lookup3::final(a, b, c);
    return c;
}

/// n / (2³² − 1): [0, 1] with both ends included.
inline float uint_to_unit(uint32_t n) { return float(n) * (1.f / float(0xFFFFFFFFu)); }

inline float hash_to_float(float k) { return uint_to_unit(hash_uint(float_bits(k))); }
inline float hash_to_float(float x, float y) { return uint_to_unit(hash_uint2(float_bits(x), float_bits(y))); }
inline float hash_to_float(float x, float y, float z) {
    return uint_to_unit(hash_uint3(float_bits(x), float_bits(y), float_bits(z)));
}
inline float hash_to_float(float x, float y, float z, float w) {
    return uint_to_unit(hash_uint4(float_bits(x), float_bits(y), float_bits(z), float_bits(w)));
}
inline float hash_to_float(const Vec3& k) { return hash_to_float(k.x, k.y, k.z); }
inline float hash_to_float(const Vec4& k) { return hash_to_float(k.x, k.y, k.z, k.w); }

// Several independent values from one key: the key with extra components 1, 2 (1-D to 3-D keys), or permuted
// (4-D keys).
inline Vec3 hash_to_color(float k) { return {hash_to_float(k), hash_to_float(k, 1.f), hash_to_float(k, 2.f)}; }
inline Vec3 hash_to_color(float x, float y) {
    return {hash_to_float(x, y), hash_to_float(x, y, 1.f), hash_to_float(x, y, 2.f)};
}
inline Vec3 hash_to_color(const Vec3& k) {
    return {hash_to_float(k), hash_to_float(k.x, k.y, k.z, 1.f), hash_to_float(k.x, k.y, k.z, 2.f)};
}
inline Vec3 hash_to_color(const Vec4& k) {
    return {hash_to_float(k), hash_to_float(k.z, k.x, k.w, k.y), hash_to_float(k.w, k.z, k.y, k.x)};
}
inline Vec2 hash_to_vec2(float x, float y) { return {hash_to_float(x, y), hash_to_float(x, y, 1.f)}; }
inline Vec4 hash_to_vec4(const Vec4& k) {
    return {hash_to_float(k), hash_to_float(k.w, k.x, k.y, k.z), hash_to_float(k.z, k.w, k.x, k.y),
            hash_to_float(k.y, k.z, k.w, k.x)};
}

}  // namespace candela
