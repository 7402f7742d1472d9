#include "texture/node_math.h"

#include <cmath>

#include "core/math.h"
#include "texture/color_space.h"

namespace candela {

const std::vector<std::string>& math_op_names() {
    static const std::vector<std::string> names = {
        "ADD",          "SUBTRACT",   "MULTIPLY",   "DIVIDE",   "MULTIPLY_ADD", "POWER",     "LOGARITHM",    "SQRT",
        "INVERSE_SQRT", "ABSOLUTE",   "EXPONENT",   "MINIMUM",  "MAXIMUM",      "LESS_THAN", "GREATER_THAN", "SIGN",
        "COMPARE",      "SMOOTH_MIN", "SMOOTH_MAX", "ROUND",    "FLOOR",        "CEIL",      "TRUNC",        "FRACT",
        "MODULO",       "WRAP",       "SNAP",       "PINGPONG", "SINE",         "COSINE",    "TANGENT",      "ARCSINE",
        "ARCCOSINE",    "ARCTANGENT", "ARCTAN2",    "SINH",     "COSH",         "TANH",      "RADIANS",      "DEGREES"};
    return names;
}

const std::vector<std::string>& mix_blend_names() {
    static const std::vector<std::string> names = {
        "MIX",        "DARKEN",       "MULTIPLY",   "BURN",     "LIGHTEN", "SCREEN", "DODGE",      "ADD",   "OVERLAY",
        "SOFT_LIGHT", "LINEAR_LIGHT", "DIFFERENCE", "SUBTRACT", "DIVIDE",  "HUE",    "SATURATION", "VALUE", "COLOR"};
    return names;
}

namespace {

float safe_divide(float a, float b) { return b != 0.f ? a / b : 0.f; }

float smooth_min(float a, float b, float k) {
    if (k == 0.f) return std::fmin(a, b);
    const float h = std::fmax(k - std::fabs(a - b), 0.f) / k;
    return std::fmin(a, b) - h * h * h * k * (1.f / 6.f);
}

float fract(float x) { return x - std::floor(x); }

}  // namespace

float math_op(MathOp op, float a, float b, float c) {
    switch (op) {
    case MathOp::Add: return a + b;
    case MathOp::Subtract: return a - b;
    case MathOp::Multiply: return a * b;
    case MathOp::Divide: return safe_divide(a, b);
    case MathOp::MultiplyAdd: return a * b + c;
    case MathOp::Power:
        // A negative base only has a real power for integer exponents.
        if (a < 0.f && b != std::trunc(b)) return 0.f;
        return std::pow(a, b);
    case MathOp::Logarithm: return (a <= 0.f || b <= 0.f) ? 0.f : safe_divide(std::log(a), std::log(b));
    case MathOp::Sqrt: return a > 0.f ? std::sqrt(a) : 0.f;
    case MathOp::InverseSqrt: return a > 0.f ? 1.f / std::sqrt(a) : 0.f;
    case MathOp::Absolute: return std::fabs(a);
    case MathOp::Exponent: return std::exp(a);
    case MathOp::Minimum: return std::fmin(a, b);
    case MathOp::Maximum: return std::fmax(a, b);
    case MathOp::LessThan: return a < b ? 1.f : 0.f;
    case MathOp::GreaterThan: return a > b ? 1.f : 0.f;
    case MathOp::Sign: return a == 0.f ? 0.f : std::copysign(1.f, a);
    case MathOp::Compare: return std::fabs(a - b) <= std::fmax(c, 1e-5f) ? 1.f : 0.f;
    case MathOp::SmoothMin: return smooth_min(a, b, c);
    case MathOp::SmoothMax: return -smooth_min(-a, -b, c);
    case MathOp::Round: return std::floor(a + 0.5f);
    case MathOp::Floor: return std::floor(a);
    case MathOp::Ceil: return std::ceil(a);
    case MathOp::Trunc: return std::trunc(a);
    case MathOp::Fract: return fract(a);
    case MathOp::Modulo: return b != 0.f ? std::fmod(a, b) : 0.f;
    case MathOp::Wrap: {  // wrap a into [c, b)
        const float range = b - c;
        return range != 0.f ? a - range * std::floor((a - c) / range) : c;
    }
    case MathOp::Snap: return std::floor(safe_divide(a, b)) * b;
    case MathOp::Pingpong: return b != 0.f ? std::fabs(fract((a - b) / (2.f * b)) * 2.f * b - b) : 0.f;
    case MathOp::Sine: return std::sin(a);
    case MathOp::Cosine: return std::cos(a);
    case MathOp::Tangent: return std::tan(a);
    case MathOp::Arcsine: return std::asin(clamp(a, -1.f, 1.f));
    case MathOp::Arccosine: return std::acos(clamp(a, -1.f, 1.f));
    case MathOp::Arctangent: return std::atan(a);
    case MathOp::Arctan2: return std::atan2(a, b);
    case MathOp::Sinh: return std::sinh(a);
    case MathOp::Cosh: return std::cosh(a);
    case MathOp::Tanh: return std::tanh(a);
    case MathOp::Radians: return a * (k_pi / 180.f);
    case MathOp::Degrees: return a * (180.f / k_pi);
    }
    return 0.f;
}

namespace {

/// Per-component blends written once for one channel.
float overlay(float t, float a, float b) {
    const float tm = 1.f - t;
    return a < 0.5f ? a * (tm + 2.f * t * b) : 1.f - (tm + 2.f * t * (1.f - b)) * (1.f - a);
}
float dodge(float t, float a, float b) {
    if (a == 0.f) return a;
    const float d = 1.f - t * b;
    if (d <= 0.f) return 1.f;
    return std::fmin(a / d, 1.f);
}
float burn(float t, float a, float b) {
    const float d = 1.f - t + t * b;
    if (d <= 0.f) return 0.f;
    return clamp(1.f - (1.f - a) / d, 0.f, 1.f);
}
float divide(float t, float a, float b) { return b != 0.f ? (1.f - t) * a + t * a / b : a; }

template <typename F>
Color per_channel(F f, float t, const Color& a, const Color& b) {
    return {f(t, a.x, b.x), f(t, a.y, b.y), f(t, a.z, b.z)};
}

Color lerp(const Color& a, const Color& b, float t) { return a * (1.f - t) + b * t; }

}  // namespace

Color mix_blend(MixBlend blend, float t, const Color& a, const Color& b) {
    const float tm = 1.f - t;
    switch (blend) {
    case MixBlend::Mix: return lerp(a, b, t);
    case MixBlend::Add: return a + b * t;
    case MixBlend::Multiply: return a * (Color(tm) + b * t);
    case MixBlend::Subtract: return a - b * t;
    case MixBlend::Screen: return Color(1.f) - (Color(tm) + (Color(1.f) - b) * t) * (Color(1.f) - a);
    case MixBlend::Divide: return per_channel(divide, t, a, b);
    case MixBlend::Difference: return lerp(a, vabs(a - b), t);
    case MixBlend::Darken: return lerp(a, vmin(a, b), t);
    case MixBlend::Lighten: return lerp(a, vmax(a, b), t);
    case MixBlend::Overlay: return per_channel(overlay, t, a, b);
    case MixBlend::Dodge: return per_channel(dodge, t, a, b);
    case MixBlend::Burn: return per_channel(burn, t, a, b);
    case MixBlend::SoftLight: {
        const Color screen = Color(1.f) - (Color(1.f) - b) * (Color(1.f) - a);
        return a * tm + ((Color(1.f) - a) * b * a + a * screen) * t;
    }
    case MixBlend::LinearLight: return a + (b * 2.f - Color(1.f)) * t;
    case MixBlend::Hue: {
        const Color hb = rgb_to_hsv(b);
        if (hb.y == 0.f) return a;
        Color ha = rgb_to_hsv(a);
        ha.x = hb.x;
        return lerp(a, hsv_to_rgb(ha), t);
    }
    case MixBlend::Saturation: {
        Color ha = rgb_to_hsv(a);
        if (ha.y == 0.f) return a;
        ha.y = tm * ha.y + t * rgb_to_hsv(b).y;
        return hsv_to_rgb(ha);
    }
    case MixBlend::Value: {
        Color ha = rgb_to_hsv(a);
        ha.z = tm * ha.z + t * rgb_to_hsv(b).z;
        return hsv_to_rgb(ha);
    }
    case MixBlend::Color: {
        const Color hb = rgb_to_hsv(b);
        if (hb.y == 0.f) return a;
        Color ha = rgb_to_hsv(a);
        ha.x = hb.x;
        ha.y = hb.y;
        return lerp(a, hsv_to_rgb(ha), t);
    }
    }
    return a;
}

}  // namespace candela
