// Gradient noise in 1–4 dimensions and its fractal sums, as Cycles 3.4 defines them (docs/textures.md, "Noise").
//
// perlin(p): Perlin's improved noise (Perlin 2002, "Improving Noise"): at each lattice corner a pseudo-random
// gradient chosen by the lookup3 hash of the corner's integer coordinates (texture/hash.h), dotted with the offset
// to the corner, blended with the quintic fade 6t⁵ − 15t⁴ + 10t³. The gradient sets are Perlin's (1-D: ±1…±8;
// 2-D: (±1, ±2), (±2, ±1); 3-D: the 12 cube edges; 4-D: the 32 hypercube edges). snoise(p) = s_n · perlin(p)
// with Cycles' normalising factors s_1..4 = 0.25, 0.6616, 0.982, 0.8344 (about [−1, 1]); noise = ½·snoise + ½.
// Coordinates are reduced modulo 10⁵ first (shifted by ½ from 10⁶ on) to keep the fraction's precision.
//
// fractal_noise: the Noise Texture's fBm — octaves 0..⌊detail⌋ at frequencies 2^i, amplitude roughness^i,
// normalised by the amplitude sum, with a fractional last octave blended in by detail − ⌊detail⌋.
// musgrave_*: Musgrave's five fractal types (Ebert et al., "Texturing and Modeling", ch. 14), as the Musgrave
// Texture uses them.
#pragma once

#include "texture/hash.h"

namespace candela {

float snoise(float p);
float snoise(Vec2 p);
float snoise(const Vec3& p);
float snoise(const Vec4& p);

/// The Noise Texture's fractal sum in [0, 1] (detail clamped to [0, 15], roughness to [0, 1]).
template <typename V>
float fractal_noise(const V& p, float detail, float roughness);

enum class MusgraveType : uint32_t { Multifractal, Fbm, HybridMultifractal, RidgedMultifractal, HeteroTerrain };

struct MusgraveParams {
    MusgraveType type = MusgraveType::Fbm;
    float dimension = 2.f, lacunarity = 2.f, detail = 2.f, offset = 0.f, gain = 1.f;
};

/// One Musgrave fractal at p (already scaled).
template <typename V>
float musgrave(const V& p, const MusgraveParams& m);

// Small vector helpers shared by the textures.
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, float s) { return {a.x * s, a.y * s}; }
inline Vec4 operator+(const Vec4& a, const Vec4& b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
inline Vec4 operator-(const Vec4& a, const Vec4& b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
inline Vec4 operator*(const Vec4& a, float s) { return {a.x * s, a.y * s, a.z * s, a.w * s}; }

}  // namespace candela
