#include "texture/noise.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

inline float fade(float t) { return t * t * t * (t * (t * 6.f - 15.f) + 10.f); }
inline float negate_if(float v, uint32_t condition) { return condition ? -v : v; }
inline float floor_frac(float x, int* i) {
    const float f = std::floor(x);
    *i = int(f);
    return x - f;
}
inline float mix(float a, float b, float t) { return (1.f - t) * a + t * b; }
inline float bi_mix(float v0, float v1, float v2, float v3, float x, float y) {
    const float x1 = 1.f - x;
    return (1.f - y) * (v0 * x1 + v1 * x) + y * (v2 * x1 + v3 * x);
}
inline float tri_mix(const float v[8], float x, float y, float z) {
    const float x1 = 1.f - x, y1 = 1.f - y, z1 = 1.f - z;
    return z1 * (y1 * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x)) +
           z * (y1 * (v[4] * x1 + v[5] * x) + y * (v[6] * x1 + v[7] * x));
}

// Perlin's gradient sets, selected by the low bits of the corner hash.
inline float grad1(uint32_t h, float x) {
    h &= 15u;
    const float g = float(1u + (h & 7u));
    return negate_if(g, h & 8u) * x;
}
inline float grad2(uint32_t h, float x, float y) {
    h &= 7u;
    const float u = h < 4u ? x : y;
    const float v = 2.f * (h < 4u ? y : x);
    return negate_if(u, h & 1u) + negate_if(v, h & 2u);
}
inline float grad3(uint32_t h, float x, float y, float z) {
    h &= 15u;
    const float u = h < 8u ? x : y;
    const float vt = (h == 12u || h == 14u) ? x : z;
    const float v = h < 4u ? y : vt;
    return negate_if(u, h & 1u) + negate_if(v, h & 2u);
}
inline float grad4(uint32_t h, float x, float y, float z, float w) {
    h &= 31u;
    const float u = h < 24u ? x : y;
    const float v = h < 16u ? y : z;
    const float s = h < 8u ? z : w;
    return negate_if(u, h & 1u) + negate_if(v, h & 2u) + negate_if(s, h & 4u);
}

float perlin(float x) {
    int X;
    const float fx = floor_frac(x, &X);
    return mix(grad1(hash_uint(uint32_t(X)), fx), grad1(hash_uint(uint32_t(X + 1)), fx - 1.f), fade(fx));
}

float perlin(float x, float y) {
    int X, Y;
    const float fx = floor_frac(x, &X), fy = floor_frac(y, &Y);
    const uint32_t x0 = uint32_t(X), x1 = uint32_t(X + 1), y0 = uint32_t(Y), y1 = uint32_t(Y + 1);
    return bi_mix(grad2(hash_uint2(x0, y0), fx, fy), grad2(hash_uint2(x1, y0), fx - 1.f, fy),
                  grad2(hash_uint2(x0, y1), fx, fy - 1.f), grad2(hash_uint2(x1, y1), fx - 1.f, fy - 1.f), fade(fx),
                  fade(fy));
}

float perlin(float x, float y, float z) {
    int X, Y, Z;
    const float fx = floor_frac(x, &X), fy = floor_frac(y, &Y), fz = floor_frac(z, &Z);
    float v[8];
    for (int k = 0; k < 8; ++k) {
        const int i = k & 1, j = (k >> 1) & 1, l = k >> 2;
        v[k] = grad3(hash_uint3(uint32_t(X + i), uint32_t(Y + j), uint32_t(Z + l)), fx - float(i), fy - float(j),
                     fz - float(l));
    }
    return tri_mix(v, fade(fx), fade(fy), fade(fz));
}

float perlin(float x, float y, float z, float w) {
    int X, Y, Z, W;
    const float fx = floor_frac(x, &X), fy = floor_frac(y, &Y), fz = floor_frac(z, &Z), fw = floor_frac(w, &W);
    float v[16];
    for (int k = 0; k < 16; ++k) {
        const int i = k & 1, j = (k >> 1) & 1, l = (k >> 2) & 1, m = k >> 3;
        v[k] = grad4(hash_uint4(uint32_t(X + i), uint32_t(Y + j), uint32_t(Z + l), uint32_t(W + m)), fx - float(i),
                     fy - float(j), fz - float(l), fw - float(m));
    }
    const float u = fade(fx), s = fade(fy), t = fade(fz);
    return mix(tri_mix(v, u, s, t), tri_mix(v + 8, u, s, t), fade(fw));
}

/// Large coordinates lose the fraction the noise is made of: keep them below 10⁵ (the shift by ½ from 10⁶ on
/// avoids landing on lattice points, where the noise is 0).
inline float reduce(float p) {
    if (std::fabs(p) < 100000.f) return p;  // fmod would return p itself
    const float correction = std::fabs(p) >= 1000000.f ? 0.5f : 0.f;
    return std::fmod(p, 100000.f) + correction;
}

}  // namespace

float snoise(float p) { return 0.25f * perlin(reduce(p)); }
float snoise(Vec2 p) { return 0.6616f * perlin(reduce(p.x), reduce(p.y)); }
float snoise(const Vec3& p) { return 0.9820f * perlin(reduce(p.x), reduce(p.y), reduce(p.z)); }
float snoise(const Vec4& p) { return 0.8344f * perlin(reduce(p.x), reduce(p.y), reduce(p.z), reduce(p.w)); }

template <typename V>
float fractal_noise(const V& p, float detail, float roughness) {
    float fscale = 1.f, amp = 1.f, maxamp = 0.f, sum = 0.f;
    const float octaves = clamp(detail, 0.f, 15.f);
    const float r = clamp(roughness, 0.f, 1.f);
    const int n = int(octaves);
    for (int i = 0; i <= n; ++i) {
        sum += snoise(p * fscale) * amp;
        maxamp += amp;
        amp *= r;
        fscale *= 2.f;
    }
    const float rmd = octaves - std::floor(octaves);
    if (rmd == 0.f) return 0.5f * sum / maxamp + 0.5f;
    const float t = snoise(p * fscale);
    const float sum2 = (sum + t * amp) / (maxamp + amp);
    sum /= maxamp;
    return (1.f - rmd) * (0.5f * sum + 0.5f) + rmd * (0.5f * sum2 + 0.5f);
}

template <typename V>
float musgrave(const V& p0, const MusgraveParams& m) {
    V p = p0;
    const float H = std::fmax(m.dimension, 1e-5f);
    const float lac = std::fmax(m.lacunarity, 1e-5f);
    const float octaves = clamp(m.detail, 0.f, 15.f);
    const int n = int(octaves);
    const float rmd = octaves - std::floor(octaves);
    const float pw_hl = std::pow(lac, -H);
    switch (m.type) {
    case MusgraveType::Fbm: {
        float value = 0.f, pwr = 1.f;
        for (int i = 0; i < n; ++i) {
            value += snoise(p) * pwr;
            pwr *= pw_hl;
            p = p * lac;
        }
        if (rmd != 0.f) value += rmd * snoise(p) * pwr;
        return value;
    }
    case MusgraveType::Multifractal: {
        float value = 1.f, pwr = 1.f;
        for (int i = 0; i < n; ++i) {
            value *= pwr * snoise(p) + 1.f;
            pwr *= pw_hl;
            p = p * lac;
        }
        if (rmd != 0.f) value *= rmd * pwr * snoise(p) + 1.f;
        return value;
    }
    case MusgraveType::HeteroTerrain: {
        float pwr = pw_hl;
        float value = m.offset + snoise(p);  // the first octave unscaled
        p = p * lac;
        for (int i = 1; i < n; ++i) {
            value += (snoise(p) + m.offset) * pwr * value;
            pwr *= pw_hl;
            p = p * lac;
        }
        if (rmd != 0.f) value += rmd * (snoise(p) + m.offset) * pwr * value;
        return value;
    }
    case MusgraveType::HybridMultifractal: {
        float pwr = pw_hl;
        float value = snoise(p) + m.offset;
        float weight = m.gain * value;
        p = p * lac;
        for (int i = 1; weight > 0.001f && i < n; ++i) {
            weight = std::fmin(weight, 1.f);
            const float signal = (snoise(p) + m.offset) * pwr;
            pwr *= pw_hl;
            value += weight * signal;
            weight *= m.gain * signal;
            p = p * lac;
        }
        if (rmd != 0.f && weight > 0.001f) {
            weight = std::fmin(weight, 1.f);
            value += rmd * weight * (snoise(p) + m.offset) * pwr;
        }
        return value;
    }
    case MusgraveType::RidgedMultifractal: {
        float pwr = pw_hl;
        float signal = m.offset - std::fabs(snoise(p));
        signal *= signal;
        float value = signal;
        for (int i = 1; i < n; ++i) {
            p = p * lac;
            const float weight = clamp(signal * m.gain, 0.f, 1.f);
            signal = m.offset - std::fabs(snoise(p));
            signal *= signal * weight;
            value += signal * pwr;
            pwr *= pw_hl;
        }
        return value;
    }
    }
    return 0.f;
}

template float fractal_noise<float>(const float&, float, float);
template float fractal_noise<Vec2>(const Vec2&, float, float);
template float fractal_noise<Vec3>(const Vec3&, float, float);
template float fractal_noise<Vec4>(const Vec4&, float, float);
template float musgrave<float>(const float&, const MusgraveParams&);
template float musgrave<Vec2>(const Vec2&, const MusgraveParams&);
template float musgrave<Vec3>(const Vec3&, const MusgraveParams&);
template float musgrave<Vec4>(const Vec4&, const MusgraveParams&);

}  // namespace candela
