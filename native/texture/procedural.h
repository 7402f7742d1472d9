// Cycles 3.4's procedural texture nodes (docs/textures.md): Noise, White Noise, Musgrave, Wave, Magic, Checker,
// Brick and Gradient, each as a function of its (already resolved) socket values. Voronoi is texture/voronoi.h.
// Coordinates arrive unscaled; the node's Scale is applied here, as in the node.
#pragma once

#include <cstdint>

#include "texture/noise.h"

namespace candela {

/// Noise Texture: Fac and Color. dims 1 uses w, 2 (x, y), 3 (x, y, z), 4 all.
struct NoiseParams {
    float scale = 5.f, detail = 2.f, roughness = 0.5f, distortion = 0.f;
};
void noise_texture(int dims, const Vec4& p, const NoiseParams& n, bool want_color, float* fac, Vec3* color);

/// White Noise Texture: Value and Color.
void white_noise_texture(int dims, const Vec4& p, float* value, Vec3* color);

/// Musgrave Texture: Fac.
float musgrave_texture(int dims, const Vec4& p, float scale, const MusgraveParams& m);

enum class WaveType : uint32_t { Bands, Rings };
enum class WaveDirection : uint32_t {
    X,
    Y,
    Z,
    DiagonalOrSpherical
};  // bands: X, Y, Z, DIAGONAL; rings: X, Y, Z, SPHERICAL
enum class WaveProfile : uint32_t { Sine, Saw, Triangle };
struct WaveParams {
    WaveType type = WaveType::Bands;
    WaveDirection direction = WaveDirection::X;
    WaveProfile profile = WaveProfile::Sine;
    float scale = 5.f, distortion = 0.f, detail = 2.f, detail_scale = 1.f, detail_roughness = 0.5f, phase = 0.f;
};
float wave_texture(const Vec3& p, const WaveParams& w);

/// Magic Texture: Color (Fac is its average).
Vec3 magic_texture(const Vec3& p, int depth, float scale, float distortion);

/// Checker Texture: 1 where Color1 shows, 0 for Color2.
float checker_texture(const Vec3& p, float scale);

enum class GradientType : uint32_t { Linear, Quadratic, Easing, Diagonal, Spherical, QuadraticSphere, Radial };
float gradient_texture(const Vec3& p, GradientType type);

struct BrickParams {
    float scale = 5.f, mortar_size = 0.02f, mortar_smooth = 0.1f, bias = 0.f, brick_width = 0.5f, row_height = 0.25f;
    float offset = 0.5f, squash = 1.f;
    int offset_frequency = 2, squash_frequency = 2;
};
/// Brick Texture: Fac (1 in the mortar) and the colour from the three colour inputs.
float brick_texture(const Vec3& p, const BrickParams& b, const Vec3& color1, const Vec3& color2, const Vec3& mortar,
                    Vec3* color);

}  // namespace candela
