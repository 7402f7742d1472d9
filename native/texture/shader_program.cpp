// Loading and validation of the shader library (textures, ramps, constants, programs).
#include "texture/shader_program.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "input/scene_arrays.h"
#include "texture/node_math.h"
#include "texture/sky.h"
#include "texture/sky_nishita.h"

namespace candela {

const std::vector<std::string>& shader_op_names() {
    static const std::vector<std::string> names = {
        "CONST",        "COORD",       "IMAGE",     "IMAGE_ALPHA",     "MIX",          "MATH",
        "RAMP",         "RAMP_ALPHA",  "LUMINANCE", "AVERAGE",         "COMBINE",      "SEPARATE",
        "MAPPING",      "NORMAL_MAP",  "INVERT",    "BRIGHT_CONTRAST", "TEX_NOISE",    "TEX_WHITE_NOISE",
        "TEX_MUSGRAVE", "TEX_VORONOI", "TEX_WAVE",  "TEX_MAGIC",       "TEX_CHECKER",  "TEX_GRADIENT",
        "TEX_BRICK",    "VECTOR_MATH", "MAP_RANGE", "HUE_SATURATION",  "LAYER_WEIGHT", "FRESNEL",
        "BUMP",         "ATTRIBUTE",   "SKY",       "CURVES",          "BLACKBODY",    "WAVELENGTH"};
    return names;
}
const std::vector<std::string>& coord_kind_names() {
    static const std::vector<std::string> names = {"UV",
                                                   "GENERATED",
                                                   "OBJECT",
                                                   "NORMAL",
                                                   "WORLD_NORMAL",
                                                   "INCOMING",
                                                   "POSITION",
                                                   "TRUE_NORMAL",
                                                   "BACKFACING",
                                                   "REFLECTION",
                                                   "OBJECT_LOCATION",
                                                   "OBJECT_INDEX",
                                                   "TANGENT",
                                                   "IS_CAMERA_RAY",
                                                   "IS_SHADOW_RAY",
                                                   "IS_DIFFUSE_RAY",
                                                   "IS_GLOSSY_RAY",
                                                   "IS_SINGULAR_RAY",
                                                   "IS_REFLECTION_RAY",
                                                   "IS_TRANSMISSION_RAY",
                                                   "RAY_LENGTH",
                                                   "RAY_DEPTH",
                                                   "DIFFUSE_DEPTH",
                                                   "GLOSSY_DEPTH",
                                                   "TRANSPARENT_DEPTH",
                                                   "TRANSMISSION_DEPTH",
                                                   "OBJECT_COLOR",
                                                   "OBJECT_ALPHA",
                                                   "OBJECT_RANDOM",
                                                   "WINDOW"};
    return names;
}
const std::vector<std::string>& image_projection_names() {
    static const std::vector<std::string> names = {"FLAT", "EQUIRECTANGULAR", "MIRROR_BALL"};
    return names;
}
const std::vector<std::string>& color_model_names() {
    static const std::vector<std::string> names = {"RGB", "HSV", "HSL"};
    return names;
}
const std::vector<std::string>& normal_map_space_names() {
    static const std::vector<std::string> names = {"TANGENT", "OBJECT", "WORLD", "BLENDER_OBJECT", "BLENDER_WORLD"};
    return names;
}

const std::vector<std::string>& musgrave_type_names() {
    static const std::vector<std::string> names = {"MULTIFRACTAL", "FBM", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL",
                                                   "HETERO_TERRAIN"};
    return names;
}
const std::vector<std::string>& voronoi_feature_names() {
    static const std::vector<std::string> names = {"F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"};
    return names;
}
const std::vector<std::string>& voronoi_metric_names() {
    static const std::vector<std::string> names = {"EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"};
    return names;
}
const std::vector<std::string>& wave_type_names() {
    static const std::vector<std::string> names = {"BANDS", "RINGS"};
    return names;
}
const std::vector<std::string>& wave_profile_names() {
    static const std::vector<std::string> names = {"SIN", "SAW", "TRI"};
    return names;
}
const std::vector<std::string>& gradient_type_names() {
    static const std::vector<std::string> names = {"LINEAR",    "QUADRATIC",        "EASING", "DIAGONAL",
                                                   "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"};
    return names;
}
const std::vector<std::string>& vector_math_op_names() {
    static const std::vector<std::string> names = {
        "ADD",       "SUBTRACT", "MULTIPLY",    "DIVIDE",      "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT",
        "REFLECT",   "REFRACT",  "FACEFORWARD", "DOT_PRODUCT", "DISTANCE",     "LENGTH",        "SCALE",
        "NORMALIZE", "ABSOLUTE", "MINIMUM",     "MAXIMUM",     "FLOOR",        "CEIL",          "FRACTION",
        "MODULO",    "WRAP",     "SNAP",        "SINE",        "COSINE",       "TANGENT"};
    return names;
}
const std::vector<std::string>& map_range_type_names() {
    static const std::vector<std::string> names = {"LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"};
    return names;
}

const std::vector<std::string>& sky_model_names() {
    static const std::vector<std::string> names = {"PREETHAM", "NISHITA"};
    return names;
}

uint32_t shader_op_register_immediates(ShaderOpCode code) {
    switch (code) {
    case ShaderOpCode::TexMusgrave:
    case ShaderOpCode::TexChecker: return 0b001;
    case ShaderOpCode::TexBrick:
    case ShaderOpCode::MapRange: return 0b111;
    case ShaderOpCode::Bump: return 0b011;
    default: return 0;
    }
}

namespace {

/// Registers each operation reads (a, b, c in that order).
int arity(ShaderOpCode code) {
    switch (code) {
    case ShaderOpCode::Const:
    case ShaderOpCode::Coord:
    case ShaderOpCode::Attribute: return 0;
    case ShaderOpCode::Image:
    case ShaderOpCode::ImageAlpha:
    case ShaderOpCode::Ramp:
    case ShaderOpCode::RampAlpha:
    case ShaderOpCode::Luminance:
    case ShaderOpCode::Average:
    case ShaderOpCode::Separate:
    case ShaderOpCode::Mapping: return 1;
    case ShaderOpCode::NormalMap:
    case ShaderOpCode::Invert: return 2;
    case ShaderOpCode::TexGradient:
    case ShaderOpCode::Sky:
    case ShaderOpCode::Blackbody: return 1;
    case ShaderOpCode::Wavelength: return 1;
    case ShaderOpCode::TexWhiteNoise:
    case ShaderOpCode::TexMagic:
    case ShaderOpCode::LayerWeight:
    case ShaderOpCode::Fresnel: return 2;
    case ShaderOpCode::Mix:
    case ShaderOpCode::Math:
    case ShaderOpCode::Combine:
    case ShaderOpCode::BrightContrast:
    case ShaderOpCode::TexNoise:
    case ShaderOpCode::TexMusgrave:
    case ShaderOpCode::TexVoronoi:
    case ShaderOpCode::TexWave:
    case ShaderOpCode::TexChecker:
    case ShaderOpCode::TexBrick:
    case ShaderOpCode::VectorMath:
    case ShaderOpCode::MapRange:
    case ShaderOpCode::HueSaturation:
    case ShaderOpCode::Bump: return 3;
    case ShaderOpCode::Curves: return 2;
    }
    return 0;
}

}  // namespace

ShaderLibrary::ShaderLibrary(TexturePools textures, std::vector<float> ramps, std::vector<float> consts,
                             std::vector<ShaderOp> ops, std::vector<uint32_t> program_start)
    : m_pools(std::move(textures)),
      m_ramps(std::move(ramps)),
      m_consts(std::move(consts)),
      m_ops(std::move(ops)),
      m_program_start(std::move(program_start)) {
    const size_t counts[2] = {m_pools.floats.size() / 4, m_pools.bytes.size() / 4};
    const char* pools[2] = {"textures", "textures_u8"};
    if (m_pools.info.size() % 5 != 0) throw InvalidScene("'texture_info' needs 5 columns");
    for (size_t t = 0; t < m_pools.info.size() / 5; ++t) {
        const uint32_t* r = &m_pools.info[5 * t];
        const std::string where = "texture_info[" + std::to_string(t) + "]";
        if (r[1] == 0 || r[2] == 0) throw InvalidScene(where + ": an image needs a positive width and height");
        if (r[3] >= tex_color_space_names().size())
            throw InvalidScene(where + ": colour space " + std::to_string(r[3]) + " is unknown");
        if (r[4] >= tex_storage_names().size())
            throw InvalidScene(where + ": storage " + std::to_string(r[4]) + " is unknown");
        if (uint64_t(r[0]) + uint64_t(r[1]) * r[2] > counts[r[4]])
            throw InvalidScene(where + ": texels [" + std::to_string(r[0]) + ", +" +
                               std::to_string(uint64_t(r[1]) * r[2]) + ") run past the " +
                               std::to_string(counts[r[4]]) + " texels of '" + pools[r[4]] + "'");
        ImageTexture img;
        if (TexStorage(r[4]) == TexStorage::Byte)
            img.bytes = m_pools.bytes.data() + 4 * size_t(r[0]);
        else
            img.texels = m_pools.floats.data() + 4 * size_t(r[0]);
        img.width = r[1];
        img.height = r[2];
        img.color_space = TexColorSpace(r[3]);
        m_textures.push_back(img);
    }
    for (size_t i = 0; i < m_pools.floats.size(); ++i)
        if (!std::isfinite(m_pools.floats[i]))
            throw InvalidScene("textures[" + std::to_string(i / 4) + "] is not finite");
    for (size_t i = 0; i < m_ramps.size(); ++i)
        if (!std::isfinite(m_ramps[i])) throw InvalidScene("ramps: entry " + std::to_string(i) + " is not finite");
    for (size_t i = 0; i < m_consts.size(); ++i)
        if (!std::isfinite(m_consts[i])) throw InvalidScene("shader_consts[" + std::to_string(i) + "] is not finite");
    if (m_ramps.size() % (4 * k_ramp_size) != 0) throw InvalidScene("'ramps' must have shape (R, 256, 4)");
    const size_t ramp_count = m_ramps.size() / (4 * k_ramp_size);

    if (m_program_start.empty()) {
        if (!m_ops.empty()) throw InvalidScene("'shader_ops' needs 'shader_programs'");
        return;
    }
    if (m_program_start.front() != 0 || m_program_start.back() != m_ops.size())
        throw InvalidScene("'shader_programs' must start at 0 and end at the operation count " +
                           std::to_string(m_ops.size()));
    m_varying.assign(m_ops.size(), 0);
    m_differentials.assign(m_program_start.size() - 1, 0);
    for (size_t p = 0; p + 1 < m_program_start.size(); ++p) {
        const uint32_t begin = m_program_start[p], end = m_program_start[p + 1];
        if (end <= begin)
            throw InvalidScene("shader program " + std::to_string(p) + " is empty (or the starts decrease)");
        m_max_size = std::max(m_max_size, end - begin);
        for (uint32_t k = begin; k < end; ++k) {
            const ShaderOp& op = m_ops[k];
            const uint32_t r = k - begin;
            const std::string where = "shader program " + std::to_string(p) + ", operation " + std::to_string(r);
            const int n = arity(op.code);
            const uint32_t args[3] = {op.a, op.b, op.c};
            // Nodes that read the shading point themselves (the normal, the view direction) vary with it; the Light
            // Path node's outputs vary with the path instead.
            const bool path_coord = op.code == ShaderOpCode::Coord && op.i[0] < coord_kind_names().size() &&
                                    is_light_path_coord(CoordKind(op.i[0]));
            m_reads_light_path = m_reads_light_path || path_coord;
            m_reads_window =
                m_reads_window || (op.code == ShaderOpCode::Coord && op.i[0] == uint32_t(CoordKind::Window));
            uint8_t varying = (op.code == ShaderOpCode::Coord && !path_coord) || op.code == ShaderOpCode::NormalMap ||
                                      op.code == ShaderOpCode::LayerWeight || op.code == ShaderOpCode::Fresnel ||
                                      op.code == ShaderOpCode::Bump || op.code == ShaderOpCode::Attribute
                                  ? k_spatial
                                  : 0;
            if (path_coord) varying |= k_path;
            std::vector<uint32_t> reads(args, args + n);
            const uint32_t imm_regs = shader_op_register_immediates(op.code);
            for (int j = 0; j < 4; ++j)
                if (imm_regs & (1u << j)) reads.push_back(op.i[j]);
            for (const uint32_t reg : reads) {
                if (reg >= r)
                    throw InvalidScene(where + " (" + shader_op_names()[size_t(op.code)] + ") reads register " +
                                       std::to_string(reg) + ", which is not computed before it");
                varying |= m_varying[begin + reg];
            }
            m_varying[k] = varying;
            auto need = [&](bool ok, const std::string& what) {
                if (!ok) throw InvalidScene(where + " (" + shader_op_names()[size_t(op.code)] + "): " + what);
            };
            switch (op.code) {
            case ShaderOpCode::Const:
                need(size_t(op.i[0]) + 3 <= m_consts.size(), "constant offset out of range");
                break;
            case ShaderOpCode::Coord:
                need(op.i[0] < coord_kind_names().size(), "unknown coordinate kind");
                need(op.i[1] < 3, "offset must be 0, 1 or 2");
                if (op.i[1] != 0) m_differentials[p] = 1;
                break;
            case ShaderOpCode::Image:
            case ShaderOpCode::ImageAlpha:
                need(op.i[0] < m_textures.size(), "texture " + std::to_string(op.i[0]) + " does not exist");
                need(op.i[1] < tex_interpolation_names().size(), "unknown interpolation");
                need(op.i[2] < tex_extension_names().size(), "unknown extension");
                need(op.i[3] < image_projection_names().size(), "unknown projection");
                break;
            case ShaderOpCode::Mix: need(op.i[0] < mix_blend_names().size(), "unknown blend type"); break;
            case ShaderOpCode::Math: need(op.i[0] < math_op_names().size(), "unknown math operation"); break;
            case ShaderOpCode::Ramp:
            case ShaderOpCode::RampAlpha:
                need(op.i[0] < ramp_count, "ramp " + std::to_string(op.i[0]) + " does not exist");
                break;
            case ShaderOpCode::Combine: need(op.i[0] < color_model_names().size(), "unknown colour model"); break;
            case ShaderOpCode::Separate:
                need(op.i[0] < color_model_names().size(), "unknown colour model");
                need(op.i[1] < 3, "channel must be 0, 1 or 2");
                break;
            case ShaderOpCode::Mapping:
                need(size_t(op.i[0]) + 12 <= m_consts.size(), "matrix offset out of range");
                break;
            case ShaderOpCode::NormalMap:
                need(op.i[0] < normal_map_space_names().size(), "unknown normal map space");
                break;
            case ShaderOpCode::TexNoise:
            case ShaderOpCode::TexWhiteNoise:
                need(op.i[0] >= 1 && op.i[0] <= 4, "dimensions must be 1 to 4");
                need(op.i[1] < 2, "unknown output");
                break;
            case ShaderOpCode::TexMusgrave:
                need(op.i[1] >= 1 && op.i[1] <= 4, "dimensions must be 1 to 4");
                need(op.i[2] < musgrave_type_names().size(), "unknown Musgrave type");
                break;
            case ShaderOpCode::TexVoronoi:
                need(op.i[0] >= 1 && op.i[0] <= 4, "dimensions must be 1 to 4");
                need(op.i[1] < voronoi_feature_names().size(), "unknown Voronoi feature");
                need(op.i[2] < voronoi_metric_names().size(), "unknown Voronoi distance metric");
                need(op.i[3] < 5, "unknown output");
                break;
            case ShaderOpCode::TexWave:
                need(op.i[0] < wave_type_names().size(), "unknown wave type");
                need(op.i[1] < 4, "unknown wave direction");
                need(op.i[2] < wave_profile_names().size(), "unknown wave profile");
                break;
            case ShaderOpCode::TexMagic:
                need(op.i[0] <= 10 && op.i[1] < 2, "depth must be 0 to 10, output 0 or 1");
                break;
            case ShaderOpCode::TexChecker: need(op.i[1] < 2, "unknown output"); break;
            case ShaderOpCode::TexGradient:
                need(op.i[0] < gradient_type_names().size(), "unknown gradient type");
                break;
            case ShaderOpCode::TexBrick:
                need(size_t(op.i[3]) + 5 <= m_consts.size(), "constant offset out of range");
                break;
            case ShaderOpCode::VectorMath:
                need(op.i[0] < vector_math_op_names().size(), "unknown vector math operation");
                need(op.i[1] < 2, "unknown output");
                break;
            case ShaderOpCode::MapRange:
                need((op.i[3] & 0xFFu) < map_range_type_names().size(), "unknown map range type");
                break;
            case ShaderOpCode::LayerWeight: need(op.i[0] < 2, "unknown output"); break;
            case ShaderOpCode::Attribute: need(op.i[1] < 3, "unknown output"); break;
            case ShaderOpCode::Sky:
                need(op.i[1] < sky_model_names().size(), "unknown sky model");
                need(size_t(op.i[0]) + sky_state_size(SkyModel(op.i[1])) <= m_consts.size(), "sky state out of range");
                if (SkyModel(op.i[1]) == SkyModel::Nishita) {
                    const float* c = &m_consts[op.i[0]];
                    NishitaParams np;
                    np.sun_elevation = c[0];
                    np.sun_rotation = c[1];
                    np.altitude = clamp(c[2], 0.f, 59999.f);
                    np.air = std::fmax(c[3], 0.f);
                    np.dust = std::fmax(c[4], 0.f);
                    np.ozone = std::fmax(c[5], 0.f);
                    np.sun_disc = c[6] != 0.f;
                    np.sun_size = clamp(c[7], 0.f, k_pi);
                    np.sun_intensity = std::fmax(c[8], 0.f);
                    m_sky_of_op.resize(m_ops.size(), -1);
                    m_sky_of_op[k] = int32_t(m_skies.size());
                    m_skies.emplace_back(np);
                }
                break;
            case ShaderOpCode::Curves:
                need(op.i[0] < ramp_count, "ramp " + std::to_string(op.i[0]) + " does not exist");
                need(size_t(op.i[1]) + 2 <= m_consts.size(), "constant offset out of range");
                need(op.i[2] < 2, "unknown curve mode");
                break;
            default: break;
            }
        }
    }
}

bool ShaderLibrary::sun_disc(uint32_t p, Vec3* direction, float* half_angle) const {
    if (m_sky_of_op.empty()) return false;
    for (uint32_t k = m_program_start[p]; k < m_program_start[p + 1]; ++k) {
        if (m_sky_of_op[k] < 0) continue;
        // Only a sky that reads the view direction as it is has its sun where NishitaSky says.
        const ShaderOp& v = m_ops[m_program_start[p] + m_ops[k].a];
        if (v.code != ShaderOpCode::Coord || v.i[1] != 0 ||
            !(CoordKind(v.i[0]) == CoordKind::Generated || CoordKind(v.i[0]) == CoordKind::Incoming ||
              CoordKind(v.i[0]) == CoordKind::Object))
            continue;
        const NishitaSky& sky = m_skies[size_t(m_sky_of_op[k])];
        if (!(sky.sun_half_angle() > 0.f)) continue;
        *direction = sky.sun_direction();
        *half_angle = sky.sun_half_angle();
        return true;
    }
    return false;
}

std::shared_ptr<const ShaderLibrary> ShaderLibrary::load(const SceneArrays& arrays) {
    auto floats = [&](const char* name) {
        const Array* a = arrays.find(name);
        return a ? std::vector<float>(a->data<float>(), a->data<float>() + a->count()) : std::vector<float>();
    };
    auto uints = [&](const char* name) {
        const Array* a = arrays.find(name);
        return a ? std::vector<uint32_t>(a->data<uint32_t>(), a->data<uint32_t>() + a->count())
                 : std::vector<uint32_t>();
    };
    std::vector<ShaderOp> ops;
    if (const Array* a = arrays.find("shader_ops")) {
        const uint32_t* r = a->data<uint32_t>();
        ops.resize(a->shape[0]);
        for (size_t k = 0; k < ops.size(); ++k, r += 8) {
            if (r[0] >= shader_op_names().size())
                throw InvalidScene("shader_ops[" + std::to_string(k) + "]: operation " + std::to_string(r[0]) +
                                   " is unknown");
            ops[k] = ShaderOp{ShaderOpCode(r[0]), r[1], r[2], r[3], {r[4], r[5], r[6], r[7]}};
        }
    }
    TexturePools pools;
    pools.floats = floats("textures");
    pools.info = uints("texture_info");
    if (const Array* a = arrays.find("textures_u8"))
        pools.bytes.assign(a->data<uint8_t>(), a->data<uint8_t>() + a->count());
    return std::make_shared<const ShaderLibrary>(std::move(pools), floats("ramps"), floats("shader_consts"),
                                                 std::move(ops), uints("shader_programs"));
}

}  // namespace candela
