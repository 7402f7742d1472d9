// One forward pass over a shader program, and the coordinate mappings it uses.
#include <cmath>

#include "core/math.h"
#include "texture/color_space.h"
#include "texture/converter_nodes.h"
#include "texture/node_math.h"
#include "texture/shader_program.h"

namespace candela {

Vec2 direction_to_equirectangular(const Vec3& d) {
    const float len = length(d);
    if (!(len > 0.f)) return {0.f, 0.f};
    const float u = 0.5f - std::atan2(d.y, d.x) * k_inv_two_pi;
    const float v = 1.f - std::acos(clamp(d.z / len, -1.f, 1.f)) * k_inv_pi;
    return {u, v};
}

Vec3 equirectangular_to_direction(float u, float v) {
    const float phi = k_pi * (1.f - 2.f * u), theta = k_pi * (1.f - v);
    const float s = std::sin(theta);
    return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

ShadingInputs ShadingInputs::world(const Vec3& d) {
    ShadingInputs in;
    in.generated = in.object = in.incoming = in.position = d;
    in.normal = in.normal_object = in.true_normal = -d;
    return in;
}

namespace {

/// Blender's mirror-ball mapping of a direction (the ball seen from −Y).
Vec2 direction_to_mirror_ball(Vec3 d) {
    d.y -= 1.f;
    const float div = 2.f * std::sqrt(std::fmax(-0.5f * d.y, 0.f));
    if (div > 0.f) d = d / div;
    return {0.5f * (d.x + 1.f), 0.5f * (d.z + 1.f)};
}

Vec2 project(ImageProjection projection, const Vec3& v) {
    switch (projection) {
    case ImageProjection::Flat: return {v.x, v.y};
    case ImageProjection::Equirectangular: return direction_to_equirectangular(v);
    case ImageProjection::MirrorBall: {
        const float len = length(v);
        return direction_to_mirror_ball(len > 0.f ? v / len : v);
    }
    }
    return {0.f, 0.f};
}

Vec3 safe_normalize(const Vec3& v) {
    const float len = length(v);
    return len > 0.f ? v / len : Vec3(0.f);
}

Color convert_from_rgb(ColorModel m, const Color& c) {
    return m == ColorModel::Hsv ? rgb_to_hsv(c) : (m == ColorModel::Hsl ? rgb_to_hsl(c) : c);
}
Color convert_to_rgb(ColorModel m, const Color& c) {
    return m == ColorModel::Hsv ? hsv_to_rgb(c) : (m == ColorModel::Hsl ? hsl_to_rgb(c) : c);
}

/// Cycles 3.4's Normal Map node, on the winding side (the integrator flips the result with the face):
/// the colour encodes n = 2c − 1 in the chosen space; strength s blends from the unperturbed normal N as
/// normalize(N + s·(n − N)); then the silhouette guard Bump applies too (ensure_valid_reflection: the view
/// direction's mirror image about the new normal must stay above the surface).
Vec3 normal_map(const ShadingInputs& in, NormalMapSpace space, const Color& color, float strength) {
    Vec3 n = color * 2.f - Vec3(1.f);
    Vec3 result;
    if (space == NormalMapSpace::Tangent) {
        if (!in.has_tangent) return in.normal;  // no UV tangents: Cycles keeps the normal as it is
        const Vec3 bitangent = cross(in.normal, in.tangent) * in.tangent_sign;
        result = safe_normalize(in.tangent * n.x + bitangent * n.y + in.normal * n.z);
    } else {
        if (space == NormalMapSpace::BlenderObject || space == NormalMapSpace::BlenderWorld) {
            n.y = -n.y;
            n.z = -n.z;
        }
        const bool object = space == NormalMapSpace::Object || space == NormalMapSpace::BlenderObject;
        result = safe_normalize(object ? in.normal_to_world.vector(n) : n);
    }
    if (strength != 1.f) result = safe_normalize(in.normal + (result - in.normal) * std::fmax(strength, 0.f));
    if (is_black(result)) return in.normal;
    const float side = in.backfacing ? -1.f : 1.f;  // on the viewer's side for the check, then back
    return ensure_valid_reflection(in.true_normal * side, in.incoming, result * side) * side;
}

Vec3 coord(const ShadingInputs& in, CoordKind kind, uint32_t offset) {
    // Offsets 1, 2 (Bump's finite differences) move the position-derived coordinates; the normals and the view
    // direction stay (as in Cycles' bump evaluation).
    if (offset != 0) {
        const int k = int(offset) - 1;
        switch (kind) {
        case CoordKind::Uv: return in.uv + in.duv[k];
        case CoordKind::Generated: return in.generated + in.dgenerated[k];
        case CoordKind::Object: return in.object + in.dobject[k];
        case CoordKind::Position: return in.position + in.dp[k];
        default: break;
        }
    }
    switch (kind) {
    case CoordKind::Uv: return in.uv;
    case CoordKind::Generated: return in.generated;
    case CoordKind::Object: return in.object;
    case CoordKind::Normal: return in.normal_object;
    case CoordKind::WorldNormal: return in.normal;
    case CoordKind::Incoming: return in.incoming;
    case CoordKind::Position: return in.position;
    case CoordKind::TrueNormal: return in.true_normal;
    case CoordKind::Backfacing: return Vec3(in.backfacing ? 1.f : 0.f);
    case CoordKind::Reflection: {
        const Vec3 n = in.backfacing ? -in.normal : in.normal;
        return n * (2.f * dot(n, in.incoming)) - in.incoming;
    }
    case CoordKind::ObjectLocation: return in.object_location;
    case CoordKind::ObjectIndex: return Vec3(in.object_index);
    case CoordKind::IsCameraRay: return Vec3((in.path.flags & LightPathInfo::k_camera) ? 1.f : 0.f);
    case CoordKind::IsShadowRay: return Vec3((in.path.flags & LightPathInfo::k_shadow) ? 1.f : 0.f);
    case CoordKind::IsDiffuseRay: return Vec3((in.path.flags & LightPathInfo::k_diffuse) ? 1.f : 0.f);
    case CoordKind::IsGlossyRay: return Vec3((in.path.flags & LightPathInfo::k_glossy) ? 1.f : 0.f);
    case CoordKind::IsSingularRay: return Vec3((in.path.flags & LightPathInfo::k_singular) ? 1.f : 0.f);
    case CoordKind::IsReflectionRay: return Vec3((in.path.flags & LightPathInfo::k_reflection) ? 1.f : 0.f);
    case CoordKind::IsTransmissionRay: return Vec3((in.path.flags & LightPathInfo::k_transmission) ? 1.f : 0.f);
    case CoordKind::RayLength: return Vec3(in.path.ray_length);
    case CoordKind::RayDepth: return Vec3(float(in.path.depth));
    case CoordKind::DiffuseDepth: return Vec3(float(in.path.diffuse_depth));
    case CoordKind::GlossyDepth: return Vec3(float(in.path.glossy_depth));
    case CoordKind::TransparentDepth: return Vec3(float(in.path.transparent_depth));
    case CoordKind::TransmissionDepth: return Vec3(float(in.path.transmission_depth));
    case CoordKind::ObjectColor: return in.object_color;
    case CoordKind::ObjectAlpha: return Vec3(in.object_alpha);
    case CoordKind::ObjectRandom: return Vec3(in.object_random);
    case CoordKind::Window: return in.window;
    case CoordKind::Tangent: {
        // The direction around the texture space's Z axis, (−(g_y − ½), g_x − ½, 0), carried to world space as
        // a normal (Cycles does), then projected into the shading plane.
        const Vec3 around(-(in.generated.y - 0.5f), in.generated.x - 0.5f, 0.f);
        const Vec3 t = safe_normalize(cross(in.normal_to_world.vector(around), in.normal));
        return cross(in.normal, t);
    }
    }
    return Vec3(0.f);
}

Vec3 saturate(const Vec3& v) { return {clamp(v.x, 0.f, 1.f), clamp(v.y, 0.f, 1.f), clamp(v.z, 0.f, 1.f)}; }

}  // namespace

Vec3 ShaderLibrary::ramp(uint32_t index, float fac, bool interpolate, bool alpha) const {
    const float* table = m_ramps.data() + size_t(index) * k_ramp_size * 4;
    const float f = clamp(std::isfinite(fac) ? fac : 0.f, 0.f, 1.f) * float(k_ramp_size - 1);
    const uint32_t i = std::min(uint32_t(f), k_ramp_size - 1);
    const float t = f - float(i);
    const float* a = table + 4 * i;
    if (alpha) {
        float v = a[3];
        if (interpolate && t > 0.f) v = (1.f - t) * v + t * a[7];
        return Vec3(v);
    }
    Color c(a[0], a[1], a[2]);
    if (interpolate && t > 0.f) c = c * (1.f - t) + Color(a[4], a[5], a[6]) * t;
    return c;
}

float ShaderLibrary::curve(uint32_t index, float f, int c) const {
    const float* table = m_ramps.data() + size_t(index) * k_ramp_size * 4;
    const float last = float(k_ramp_size - 1);
    if (!std::isfinite(f)) f = 0.f;
    if (f < 0.f) return table[c] + (table[c] - table[4 + c]) * (-f) * last;
    if (f > 1.f) {
        const float* t0 = table + 4 * (k_ramp_size - 1);
        return t0[c] + (t0[c] - t0[c - 4]) * (f - 1.f) * last;
    }
    const float x = f * last;
    const uint32_t i = std::min(uint32_t(x), k_ramp_size - 1);
    const float t = x - float(i);
    const float v = table[4 * i + c];
    return t > 0.f ? (1.f - t) * v + t * table[4 * (i + 1) + c] : v;
}

void ShaderLibrary::evaluate(uint32_t p, const ShadingInputs& in, Vec3* regs) const {
    const uint32_t begin = m_program_start[p], n = m_program_start[p + 1] - begin;
    for (uint32_t r = 0; r < n; ++r) {
        const ShaderOp& op = m_ops[begin + r];
        const Vec3& a = regs[op.a < r ? op.a : 0];
        const Vec3& b = regs[op.b < r ? op.b : 0];
        const Vec3& c = regs[op.c < r ? op.c : 0];
        Vec3 out(0.f);
        switch (op.code) {
        case ShaderOpCode::Const: out = Vec3(m_consts[op.i[0]], m_consts[op.i[0] + 1], m_consts[op.i[0] + 2]); break;
        case ShaderOpCode::Coord: out = coord(in, CoordKind(op.i[0]), op.i[1]); break;
        case ShaderOpCode::Image:
        case ShaderOpCode::ImageAlpha: {
            const Vec2 uv = project(ImageProjection(op.i[3]), a);
            const Rgba t = m_textures[op.i[0]].lookup(uv.x, uv.y, TexInterpolation(op.i[1]), TexExtension(op.i[2]));
            out = op.code == ShaderOpCode::Image ? t.rgb : Vec3(t.a);
            break;
        }
        case ShaderOpCode::Mix: {
            if (op.i[3]) {  // per-channel factor (vector mix, non-uniform)
                const Vec3 t = op.i[1] ? saturate(a) : a;
                out = b * (Vec3(1.f) - t) + c * t;
            } else {
                out = mix_blend(MixBlend(op.i[0]), op.i[1] ? clamp(a.x, 0.f, 1.f) : a.x, b, c);
            }
            if (op.i[2]) out = saturate(out);
            break;
        }
        case ShaderOpCode::Math: {
            const MathOp m = MathOp(op.i[0]);
            out = Vec3(math_op(m, a.x, b.x, c.x), math_op(m, a.y, b.y, c.y), math_op(m, a.z, b.z, c.z));
            if (op.i[1]) out = saturate(out);
            break;
        }
        case ShaderOpCode::Ramp:
        case ShaderOpCode::RampAlpha: out = ramp(op.i[0], a.x, op.i[1] != 0, op.code == ShaderOpCode::RampAlpha); break;
        case ShaderOpCode::Luminance: out = Vec3(luminance(a)); break;
        case ShaderOpCode::Average: out = Vec3((a.x + a.y + a.z) * (1.f / 3.f)); break;
        case ShaderOpCode::Combine: out = convert_to_rgb(ColorModel(op.i[0]), Vec3(a.x, b.x, c.x)); break;
        case ShaderOpCode::Separate: out = Vec3(convert_from_rgb(ColorModel(op.i[0]), a)[int(op.i[1])]); break;
        case ShaderOpCode::Mapping: {
            const float* m = &m_consts[op.i[0]];
            out = Vec3(m[0] * a.x + m[1] * a.y + m[2] * a.z + m[3], m[4] * a.x + m[5] * a.y + m[6] * a.z + m[7],
                       m[8] * a.x + m[9] * a.y + m[10] * a.z + m[11]);
            if (op.i[1]) out = safe_normalize(out);
            break;
        }
        case ShaderOpCode::NormalMap: out = normal_map(in, NormalMapSpace(op.i[0]), a, b.x); break;
        case ShaderOpCode::Invert: out = b * (1.f - a.x) + (Vec3(1.f) - b) * a.x; break;
        case ShaderOpCode::BrightContrast: {
            const float k = 1.f + c.x, off = b.x - 0.5f * c.x;
            out = vmax(a * k + Vec3(off), Vec3(0.f));
            break;
        }
        default: out = evaluate_node(op, regs, in); break;
        }
        // A non-finite value (overflowing math) must never reach a BSDF or the film.
        if (!is_finite(out))
            out = Vec3(std::isfinite(out.x) ? out.x : 0.f, std::isfinite(out.y) ? out.y : 0.f,
                       std::isfinite(out.z) ? out.z : 0.f);
        regs[r] = out;
    }
}

}  // namespace candela
