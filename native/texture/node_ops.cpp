// The shader program's procedural-texture and converter operations: unpacking their registers and immediates
// (texture/shader_program.h) into the node functions of texture/procedural.h, voronoi.h and converter_nodes.h.
#include "texture/converter_nodes.h"
#include "texture/procedural.h"
#include "texture/shader_program.h"
#include "texture/voronoi.h"

namespace candela {

namespace {

Vec4 with_w(const Vec3& v, float w) { return {v.x, v.y, v.z, w}; }

}  // namespace

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
            p.offset_frequency = int(k[1]);
            p.squash = k[2];
            p.squash_frequency = int(k[3]);
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
        default: return Vec3(0.f);
    }
}

}  // namespace candela
