// Colour conversions of the shader inputs: the sRGB transfer function (IEC 61966-2-1) that decodes 8-bit
// sRGB image texels to scene-linear Rec.709, Rec.709 luminance for colour → value sockets, and the HSV / HSL
// models of Blender's Separate/Combine Color nodes.
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

/// sRGB-encoded value → linear. Negative inputs give 0.
inline float srgb_to_linear(float c) {
    if (c < 0.04045f) return c < 0.f ? 0.f : c * (1.f / 12.92f);
    return std::pow((c + 0.055f) * (1.f / 1.055f), 2.4f);
}
inline Color srgb_to_linear(const Color& c) { return {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)}; }

/// Hue, saturation, value in [0, 1] (hue as a fraction of the full turn).
Color rgb_to_hsv(const Color& rgb);
Color hsv_to_rgb(const Color& hsv);
/// Hue, saturation, lightness in [0, 1].
Color rgb_to_hsl(const Color& rgb);
Color hsl_to_rgb(const Color& hsl);

}  // namespace candela
