#include "texture/converter_nodes.h"

#include <cmath>

#include "core/math.h"
#include "texture/color_space.h"

namespace candela {

namespace {

float safe_divide(float a, float b) { return b != 0.f ? a / b : 0.f; }
float safe_fmod(float a, float b) { return b != 0.f ? std::fmod(a, b) : 0.f; }
float wrap(float v, float max, float min) {
    const float range = max - min;
    return range != 0.f ? v - range * std::floor((v - min) / range) : min;
}
Vec3 safe_normalize(const Vec3& v) {
    const float len = length(v);
    return len != 0.f ? v / len : Vec3(0.f);
}
template <typename F>
Vec3 per(const Vec3& a, F f) {
    return {f(a.x), f(a.y), f(a.z)};
}
template <typename F>
Vec3 per(const Vec3& a, const Vec3& b, F f) {
    return {f(a.x, b.x), f(a.y, b.y), f(a.z, b.z)};
}

}  // namespace

Vec3 vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c, float* value) {
    *value = 0.f;
    switch (op) {
    case VectorMathOp::Add: return a + b;
    case VectorMathOp::Subtract: return a - b;
    case VectorMathOp::Multiply: return a * b;
    case VectorMathOp::Divide: return per(a, b, safe_divide);
    case VectorMathOp::MultiplyAdd: return a * b + c;
    case VectorMathOp::CrossProduct: return cross(a, b);
    case VectorMathOp::Project: {
        const float l2 = dot(b, b);
        return l2 != 0.f ? b * (dot(a, b) / l2) : Vec3(0.f);
    }
    case VectorMathOp::Reflect: {
        const Vec3 n = safe_normalize(b);
        return a - n * (2.f * dot(n, a));
    }
    case VectorMathOp::Refract: {
        const Vec3 n = safe_normalize(b);
        const float eta = c.x, d = dot(n, a);
        const float k = 1.f - eta * eta * (1.f - d * d);
        return k < 0.f ? Vec3(0.f) : a * eta - n * (eta * d + std::sqrt(k));
    }
    case VectorMathOp::Faceforward: return dot(c, b) < 0.f ? a : -a;
    case VectorMathOp::DotProduct: *value = dot(a, b); return Vec3(0.f);
    case VectorMathOp::Distance: *value = length(a - b); return Vec3(0.f);
    case VectorMathOp::Length: *value = length(a); return Vec3(0.f);
    case VectorMathOp::Scale: return a * c.x;
    case VectorMathOp::Normalize: return safe_normalize(a);
    case VectorMathOp::Absolute: return vabs(a);
    case VectorMathOp::Minimum: return vmin(a, b);
    case VectorMathOp::Maximum: return vmax(a, b);
    case VectorMathOp::Floor: return per(a, [](float x) { return std::floor(x); });
    case VectorMathOp::Ceil: return per(a, [](float x) { return std::ceil(x); });
    case VectorMathOp::Fraction: return per(a, [](float x) { return x - std::floor(x); });
    case VectorMathOp::Modulo: return per(a, b, safe_fmod);
    case VectorMathOp::Wrap: return {wrap(a.x, b.x, c.x), wrap(a.y, b.y, c.y), wrap(a.z, b.z, c.z)};
    case VectorMathOp::Snap: return per(a, b, [](float x, float y) { return std::floor(safe_divide(x, y)) * y; });
    case VectorMathOp::Sine: return per(a, [](float x) { return std::sin(x); });
    case VectorMathOp::Cosine: return per(a, [](float x) { return std::cos(x); });
    case VectorMathOp::Tangent: return per(a, [](float x) { return std::tan(x); });
    }
    return Vec3(0.f);
}

namespace {

float smoothstep(float e0, float e1, float x) {
    const float t = clamp(safe_divide(x - e0, e1 - e0), 0.f, 1.f);
    return t * t * (3.f - 2.f * t);
}
float smootherstep(float e0, float e1, float x) {
    const float t = clamp(safe_divide(x - e0, e1 - e0), 0.f, 1.f);
    return t * t * t * (t * (t * 6.f - 15.f) + 10.f);
}

}  // namespace

float map_range(MapRangeType type, bool clamp_result, float value, float from_min, float from_max, float to_min,
                float to_max, float steps) {
    float factor = 0.f;
    switch (type) {
    case MapRangeType::Linear: factor = safe_divide(value - from_min, from_max - from_min); break;
    case MapRangeType::Stepped:
        factor = safe_divide(value - from_min, from_max - from_min);
        factor = steps > 0.f ? std::floor(factor * (steps + 1.f)) / steps : 0.f;
        break;
    case MapRangeType::SmoothStep:
        factor =
            from_min > from_max ? 1.f - smoothstep(from_max, from_min, value) : smoothstep(from_min, from_max, value);
        break;
    case MapRangeType::SmootherStep:
        factor = from_min > from_max ? 1.f - smootherstep(from_max, from_min, value)
                                     : smootherstep(from_min, from_max, value);
        break;
    }
    float result = to_min + factor * (to_max - to_min);
    if (clamp_result) result = to_min > to_max ? clamp(result, to_max, to_min) : clamp(result, to_min, to_max);
    return result;
}

Vec3 hue_saturation(const Vec3& in, float hue, float saturation, float value, float fac) {
    Vec3 hsv = rgb_to_hsv(in);
    hsv.x = std::fmod(hsv.x + hue + 0.5f, 1.f);  // fmod, as the node does: a negative sum stays negative
    hsv.y = clamp(hsv.y * saturation, 0.f, 1.f);
    hsv.z *= value;
    const Vec3 out = hsv_to_rgb(hsv) * fac + in * (1.f - fac);
    return vmax(out, Vec3(0.f));
}

float fresnel_dielectric_cos(float cosi, float eta) {
    const float c = std::fabs(cosi);
    float g = eta * eta - 1.f + c * c;
    if (!(g > 0.f)) return 1.f;
    g = std::sqrt(g);
    const float a = (g - c) / (g + c);
    const float b = (c * (g + c) - 1.f) / (c * (g - c) + 1.f);
    return 0.5f * a * a * (1.f + b * b);
}

float fresnel_node(const Vec3& n, const Vec3& i, float ior, bool backfacing) {
    float eta = std::fmax(ior, 1e-5f);
    if (backfacing) eta = 1.f / eta;
    return fresnel_dielectric_cos(dot(i, n), eta);
}

float layer_weight(const Vec3& n, const Vec3& i, float blend, bool backfacing, bool facing) {
    if (!facing) {
        float eta = std::fmax(1.f - blend, 1e-5f);
        if (!backfacing) eta = 1.f / eta;
        return fresnel_dielectric_cos(dot(i, n), eta);
    }
    float f = std::fabs(dot(i, n));
    if (blend != 0.5f) {
        float b = clamp(blend, 0.f, 1.f - 1e-5f);
        b = b < 0.5f ? 2.f * b : 0.5f / (1.f - b);
        f = std::pow(f, b);
    }
    return 1.f - f;
}

}  // namespace candela
