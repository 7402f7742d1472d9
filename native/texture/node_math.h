// The arithmetic of Blender's Math node and of the colour blends of Mix / MixRGB, with Cycles 3.4's
// "safe" conventions (svm/math_util.h, svm/color_util.h): division, logarithm, modulo and friends return 0
// where the plain function is undefined, so a texture never injects NaN into a BSDF.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"

namespace candela {

/// Blender's ShaderNodeMath operations, by their RNA identifiers (math_op_names()).
enum class MathOp : uint32_t {
    Add,
    Subtract,
    Multiply,
    Divide,
    MultiplyAdd,
    Power,
    Logarithm,
    Sqrt,
    InverseSqrt,
    Absolute,
    Exponent,
    Minimum,
    Maximum,
    LessThan,
    GreaterThan,
    Sign,
    Compare,
    SmoothMin,
    SmoothMax,
    Round,
    Floor,
    Ceil,
    Trunc,
    Fract,
    Modulo,
    Wrap,
    Snap,
    Pingpong,
    Sine,
    Cosine,
    Tangent,
    Arcsine,
    Arccosine,
    Arctangent,
    Arctan2,
    Sinh,
    Cosh,
    Tanh,
    Radians,
    Degrees
};
const std::vector<std::string>& math_op_names();

/// One Math node evaluation (inputs a, b, c = the node's three Value sockets).
float math_op(MathOp op, float a, float b, float c);

/// Blender's colour blend types (Mix node with data type Color, legacy MixRGB), by RNA identifier.
enum class MixBlend : uint32_t {
    Mix,
    Darken,
    Multiply,
    Burn,
    Lighten,
    Screen,
    Dodge,
    Add,
    Overlay,
    SoftLight,
    LinearLight,
    Difference,
    Subtract,
    Divide,
    Hue,
    Saturation,
    Value,
    Color
};
const std::vector<std::string>& mix_blend_names();

/// Blend of colour a (the upper socket, A / Color1) with b at factor t (already clamped by the caller if
/// the node clamps its factor).
Color mix_blend(MixBlend blend, float t, const Color& a, const Color& b);

}  // namespace candela
