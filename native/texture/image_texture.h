// Image textures as Cycles 3.4 samples them (kernel/device/cpu/image.h): texel (i, j) covers
// [i/w, (i+1)/w) × [j/h, (j+1)/h) with row 0 at the bottom (v = 0, Blender's pixel order). Closest takes the
// texel containing (u, v); Linear blends the four texels around (u·w − ½, v·h − ½); Cubic uses the uniform cubic
// B-spline over 4×4 texels. Repeat wraps, Extend clamps to the border texels, Clip reads transparent black
// outside the image. 8-bit sRGB images keep their encoded texels and are decoded after interpolation, as
// Cycles does for them; float and Non-Color images are used as they are.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"

namespace candela {

enum class TexInterpolation : uint32_t { Closest = 0, Linear = 1, Cubic = 2 };
enum class TexExtension : uint32_t { Repeat = 0, Extend = 1, Clip = 2 };
enum class TexColorSpace : uint32_t { Linear = 0, Srgb = 1 };
/// Where an image's texels live: the float32 pool `textures` or the 8-bit pool `textures_u8` (value/255).
enum class TexStorage : uint32_t { Float = 0, Byte = 1 };

const std::vector<std::string>& tex_interpolation_names();  // "CLOSEST", "LINEAR", "CUBIC"
const std::vector<std::string>& tex_extension_names();      // "REPEAT", "EXTEND", "CLIP"
const std::vector<std::string>& tex_color_space_names();    // "LINEAR", "SRGB"
const std::vector<std::string>& tex_storage_names();        // "FLOAT", "BYTE"

struct Rgba {
    Color rgb{0.f};
    float a = 0.f;
};

/// A view of one image in the scene's texel pools (RGBA per texel, rows bottom to top): float32 texels, or
/// 8-bit texels (4 bytes each, value/255) for images Blender holds as bytes — a quarter of the memory.
struct ImageTexture {
    const float* texels = nullptr;   // float storage, or
    const uint8_t* bytes = nullptr;  // 8-bit storage
    uint32_t width = 0, height = 0;
    TexColorSpace color_space = TexColorSpace::Linear;

    /// The filtered, decoded (linear) colour and alpha at (u, v).
    Rgba lookup(float u, float v, TexInterpolation interpolation, TexExtension extension) const;
    /// The stored texel (x, y) without decoding; indices must be in range.
    Rgba texel(uint32_t x, uint32_t y) const {
        const size_t i = 4 * (size_t(y) * width + x);
        if (bytes) {
            constexpr float k = 1.f / 255.f;
            const uint8_t* b = bytes + i;
            return {Color(float(b[0]) * k, float(b[1]) * k, float(b[2]) * k), float(b[3]) * k};
        }
        const float* p = texels + i;
        return {Color(p[0], p[1], p[2]), p[3]};
    }
};

}  // namespace candela
