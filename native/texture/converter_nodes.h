// Cycles 3.4's converter and input nodes that are pure functions of their sockets: Vector Math, Map Range,
// Hue/Saturation/Value, Layer Weight and Fresnel (docs/textures.md, "Input and converter nodes").
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

enum class VectorMathOp : uint32_t {
    Add,
    Subtract,
    Multiply,
    Divide,
    MultiplyAdd,
    CrossProduct,
    Project,
    Reflect,
    Refract,
    Faceforward,
    DotProduct,
    Distance,
    Length,
    Scale,
    Normalize,
    Absolute,
    Minimum,
    Maximum,
    Floor,
    Ceil,
    Fraction,
    Modulo,
    Wrap,
    Snap,
    Sine,
    Cosine,
    Tangent
};
/// The Vector Math node: a, b, c are its three vector sockets, except SCALE and REFRACT, whose Scale socket
/// (the factor, the IOR) arrives as c.x. Value results (dot, distance, length) come back in *value.
Vec3 vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c, float* value);

enum class MapRangeType : uint32_t { Linear, Stepped, SmoothStep, SmootherStep };
float map_range(MapRangeType type, bool clamp_result, float value, float from_min, float from_max, float to_min,
                float to_max, float steps);

/// Hue/Saturation/Value: hue shifts by hue − ½ turns, saturation scales (clamped to [0, 1]), value scales; the
/// result blends with the input by fac and is clamped at 0.
Vec3 hue_saturation(const Vec3& color, float hue, float saturation, float value, float fac);

/// Fresnel reflectance of a dielectric of relative IOR eta at |cos θ| = cosi (1 for total internal reflection).
float fresnel_dielectric_cos(float cosi, float eta);

/// The Fresnel node: n the normal on the viewer's side, i toward the viewer.
float fresnel_node(const Vec3& n, const Vec3& i, float ior, bool backfacing);
/// Cycles' silhouette guard for bent shading normals (Bump, Normal Map): n tilted toward the geometric normal ng
/// just far enough that the view direction i reflected about it stays above the surface (node_ops.cpp explains
/// the construction). All three on the viewer's side.
Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& i, const Vec3& n);

/// The Layer Weight node's Fresnel (facing = false) or Facing output.
float layer_weight(const Vec3& n, const Vec3& i, float blend, bool backfacing, bool facing);

}  // namespace candela
