// The shader program's procedural-texture and converter operations: unpacking their registers and immediates
// (texture/shader_program.h) into the node functions of texture/procedural.h, voronoi.h and converter_nodes.h.
#include <cmath>

#include "core/math.h"
#include "texture/cie.h"
#include "texture/converter_nodes.h"
#include "texture/procedural.h"
#include "texture/shader_program.h"
#include "texture/sky.h"
#include "texture/voronoi.h"

namespace candela {

namespace {

Vec4 with_w(const Vec3& v, float w) { return {v.x, v.y, v.z, w}; }

/// Cycles' Bump node from heights at p, p + dx, p + dy (dx, dy in the tangent plane): with the surface tangents
/// Rx = dy × N, Ry = N × dx and det = dx·Rx, the height's surface gradient is ((h_x − h_c)·Rx + (h_y − h_c)·Ry)/det
/// (Mikkelsen 2008, "Simulation of wrinkled surfaces revisited", eq. 4), and the bumped normal is
/// normalize(N − distance·gradient), written without the division: normalize(|det|·N − distance·sign(det)·(…)).
/// Strength blends it with N. Computed on the winding side (the viewer's side only negates everything).
Vec3 bump_normal(const Vec3& n_in, const Vec3& dx, const Vec3& dy, float hc, float hx, float hy, float strength,
                 float distance, bool invert) {
    const float len = length(n_in);
    if (!(len > 0.f)) return n_in;
    const Vec3 n = n_in / len;
    const Vec3 rx = cross(dy, n), ry = cross(n, dx);
    const float det = dot(dx, rx);
    const Vec3 surfgrad = rx * (hx - hc) + ry * (hy - hc);
    if (invert) distance = -distance;
    strength = std::fmax(strength, 0.f);
    Vec3 out = n * std::fabs(det) - surfgrad * (distance * (det < 0.f ? -1.f : (det > 0.f ? 1.f : 0.f)));
    const float out_len = length(out);
    if (!(out_len > 0.f) || !std::isfinite(out_len)) return n;
    out = out / out_len;
    out = out * strength + n * (1.f - strength);
    const float l2 = length(out);
    return l2 > 0.f ? out / l2 : n;
}

/// Cycles' guard against shading normals that mirror the view direction below the surface (Cycles 2.90+,
/// "ensure valid reflection"): if the reflection R of the view direction i about n dips under the threshold
/// t = min(0.9·(ng·i), 0.01) above the geometric plane, n is tilted toward ng — within the plane of ng and n —
/// just far enough that R·ng = t. With n' = x·X + z·ng (X the unit part of n orthogonal to ng, x = √(1 − z²)),
/// R'·ng = 2(x·i_x + z·i_z)·z − i_z = t is a quadratic in z²: z² = (c ± b)/(2a) with a = i_x² + i_z²,
/// b = √(i_x²·(a − t²)), c = i_z·t + a. Of the roots in (0, 1], the one whose reflection stays above the plane
/// (the shallower one if both do) is taken; ng itself if none is. All vectors on the viewer's side.
Vec3 valid_reflection(const Vec3& ng, const Vec3& i, const Vec3& n) {
    const float t = std::fmin(0.9f * dot(ng, i), 0.01f);
    const Vec3 r = n * (2.f * dot(n, i)) - i;
    if (dot(ng, r) >= t) return n;
    const Vec3 ortho = n - ng * dot(n, ng);
    const float ortho_len = length(ortho);
    if (!(ortho_len > 0.f)) return ng;
    const Vec3 x_axis = ortho / ortho_len;
    const float ix = dot(i, x_axis), iz = dot(i, ng);
    const float a = ix * ix + iz * iz;
    const float b = std::sqrt(std::fmax(ix * ix * (a - t * t), 0.f));
    const float c = iz * t + a;
    const float z2[2] = {0.5f * (c + b) / a, 0.5f * (c - b) / a};
    float best_x = 0.f, best_z = 0.f, best_r = 0.f;
    int found = 0;
    for (const float q : z2) {
        if (!(q > 1e-5f && q <= 1.f + 1e-5f)) continue;
        const float z = std::sqrt(std::fmin(q, 1.f)), x = std::sqrt(std::fmax(1.f - q, 0.f));
        const float rz = 2.f * (x * ix + z * iz) * z - iz;  // the new reflection's height over the plane
        // Prefer a reflection above the plane; of two such, the shallower (closer to the input normal).
        const bool better = found == 0 || (rz >= 1e-5f && (best_r < 1e-5f || rz < best_r)) ||
                            (rz < 1e-5f && best_r < 1e-5f && rz > best_r);
        if (better) {
            best_x = x;
            best_z = z;
            best_r = rz;
        }
        ++found;
    }
    if (found == 0) return ng;
    return x_axis * best_x + ng * best_z;
}

}  // namespace

Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& i, const Vec3& n) { return valid_reflection(ng, i, n); }

Vec3 ShaderLibrary::evaluate_node(const ShaderOp& op, const Vec3* regs, const ShadingInputs& in) const {
    const Vec3& a = regs[op.a];
    const Vec3& b = regs[op.b];
    const Vec3& c = regs[op.c];
    switch (op.code) {
    case ShaderOpCode::TexNoise: {
        NoiseParams n{b.y, b.z, c.x, c.y};
        float fac;
        Vec3 color;
        noise_texture(int(op.i[0]), with_w(a, b.x), n, op.i[1] == 1, &fac, &color);
        return op.i[1] == 1 ? color : Vec3(fac);
    }
    case ShaderOpCode::TexWhiteNoise: {
        float value;
        Vec3 color;
        white_noise_texture(int(op.i[0]), with_w(a, b.x), &value, &color);
        return op.i[1] == 1 ? color : Vec3(value);
    }
    case ShaderOpCode::TexMusgrave: {
        MusgraveParams m;
        m.type = MusgraveType(op.i[2]);
        m.detail = b.z;
        m.dimension = c.x;
        m.lacunarity = c.y;
        m.offset = c.z;
        m.gain = regs[op.i[0]].x;
        return Vec3(musgrave_texture(int(op.i[1]), with_w(a, b.x), b.y, m));
    }
    case ShaderOpCode::TexVoronoi: {
        VoronoiParams v;
        v.feature = VoronoiFeature(op.i[1]);
        v.metric = VoronoiMetric(op.i[2]);
        v.scale = b.y;
        v.smoothness = b.z;
        v.exponent = c.x;
        v.randomness = c.y;
        const int dims = int(op.i[0]);
        const VoronoiResult r = voronoi(dims, with_w(a, b.x), v);
        switch (op.i[3]) {
        case 0: return Vec3(r.distance);
        case 1: return r.color;
        case 2: return dims == 1 ? Vec3(0.f) : Vec3(r.position.x, r.position.y, r.position.z);
        case 3: return Vec3(dims == 1 ? r.position.x : r.position.w);
        default: return Vec3(r.radius);
        }
    }
    case ShaderOpCode::TexWave: {
        WaveParams w;
        w.type = WaveType(op.i[0]);
        w.direction = WaveDirection(op.i[1]);
        w.profile = WaveProfile(op.i[2]);
        w.scale = b.x;
        w.distortion = b.y;
        w.detail = b.z;
        w.detail_scale = c.x;
        w.detail_roughness = c.y;
        w.phase = c.z;
        return Vec3(wave_texture(a, w));
    }
    case ShaderOpCode::TexMagic: {
        const Vec3 color = magic_texture(a, int(op.i[0]), b.x, b.y);
        return op.i[1] == 1 ? Vec3((color.x + color.y + color.z) * (1.f / 3.f)) : color;
    }
    case ShaderOpCode::TexChecker: {
        const float f = checker_texture(a, regs[op.i[0]].x);
        return op.i[1] == 1 ? Vec3(f) : (f == 1.f ? b : c);
    }
    case ShaderOpCode::TexGradient: return Vec3(gradient_texture(a, GradientType(op.i[0])));
    case ShaderOpCode::TexBrick: {
        const float* k = &m_consts[op.i[3]];
        const Vec3& s = regs[op.i[1]];
        const Vec3& t = regs[op.i[2]];
        BrickParams p;
        p.scale = s.x;
        p.mortar_size = s.y;
        p.mortar_smooth = s.z;
        p.bias = t.x;
        p.brick_width = t.y;
        p.row_height = t.z;
        p.offset = k[0];
        p.offset_frequency = int(clamp(k[1], -65536.f, 65536.f));  // Blender's UI range is 1–99
        p.squash = k[2];
        p.squash_frequency = int(clamp(k[3], -65536.f, 65536.f));
        Vec3 color;
        const float f = brick_texture(a, p, b, c, regs[op.i[0]], &color);
        return k[4] == 1.f ? Vec3(f) : color;
    }
    case ShaderOpCode::VectorMath: {
        float value;
        const Vec3 v = vector_math(VectorMathOp(op.i[0]), a, b, c, &value);
        return op.i[1] == 1 ? Vec3(value) : v;
    }
    case ShaderOpCode::MapRange: {
        const Vec3& to_min = regs[op.i[0]];
        const Vec3& to_max = regs[op.i[1]];
        const Vec3& steps = regs[op.i[2]];
        const auto type = MapRangeType(op.i[3] & 0xFFu);
        const bool clamp_result = (op.i[3] >> 8) != 0;
        Vec3 out;
        for (int k = 0; k < 3; ++k)
            out[k] = map_range(type, clamp_result, a[k], b[k], c[k], to_min[k], to_max[k], steps[k]);
        return out;
    }
    case ShaderOpCode::HueSaturation: return hue_saturation(a, b.x, b.y, b.z, c.x);
    case ShaderOpCode::LayerWeight:
        return Vec3(layer_weight(in.backfacing ? -a : a, in.incoming, b.x, in.backfacing, op.i[0] == 1));
    case ShaderOpCode::Fresnel: return Vec3(fresnel_node(in.backfacing ? -a : a, in.incoming, b.x, in.backfacing));
    case ShaderOpCode::Bump: {
        const Vec3& params = regs[op.i[0]];
        const Vec3 n = bump_normal(regs[op.i[1]], in.dp[0], in.dp[1], a.x, b.x, c.x, params.x, params.y, op.i[2] != 0);
        const float side = in.backfacing ? -1.f : 1.f;  // on the viewer's side for the check, then back
        return valid_reflection(in.true_normal * side, in.incoming, n * side) * side;
    }
    case ShaderOpCode::Attribute: {
        // A slot the mesh does not have reads 0 (and alpha 0), as Cycles reads a missing attribute.
        if (!in.attributes || op.i[0] >= in.attribute_slots) return Vec3(0.f);
        const size_t stride = 4 * size_t(in.attribute_slots);
        const float* c0 = in.attributes + 4 * size_t(op.i[0]);
        const float w0 = 1.f - in.b1 - in.b2;
        float v[4];
        for (int k = 0; k < 4; ++k) v[k] = w0 * c0[k] + in.b1 * c0[stride + k] + in.b2 * c0[2 * stride + k];
        if (op.i[1] == 1) return Vec3((v[0] + v[1] + v[2]) * (1.f / 3.f));
        if (op.i[1] == 2) return Vec3(v[3]);
        return Vec3(v[0], v[1], v[2]);
    }
    case ShaderOpCode::Sky:
        if (SkyModel(op.i[1]) == SkyModel::Nishita)
            return m_skies[size_t(m_sky_of_op[size_t(&op - m_ops.data())])].radiance(a);
        return sky_radiance(SkyModel(op.i[1]), &m_consts[op.i[0]], a);
    case ShaderOpCode::Blackbody: return blackbody_rec709(a.x);
    case ShaderOpCode::Wavelength: return wavelength_rec709(a.x);
    case ShaderOpCode::Curves: {
        // Cycles' RGB/Vector/Float Curves: the baked curves read at (v − min x)/range, extrapolated linearly
        // past the ends, blended with the input by fac.
        const float min_x = m_consts[op.i[1]], range = m_consts[op.i[1] + 1];
        const float inv = range != 0.f ? 1.f / range : 0.f;
        Vec3 out;
        if (op.i[2] == 1) {
            out = Vec3(curve(op.i[0], (b.x - min_x) * inv, 0));
        } else {
            for (int k = 0; k < 3; ++k) out[k] = curve(op.i[0], (b[k] - min_x) * inv, k);
        }
        return b * (1.f - a.x) + out * a.x;
    }
    default: return Vec3(0.f);
    }
}

}  // namespace candela
