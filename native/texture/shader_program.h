// Shader programs: the node graph feeding a material's closure inputs (or the world's Background), compiled
// by the add-on into a flat list of operations (docs/architecture.md, "Shader programs"). Operation k of a
// program writes register k (a colour, a vector, or a value broadcast to three channels) and reads only
// registers before it, so one forward pass evaluates the whole graph at a shading point.
// Conversions between socket types are explicit operations (LUMINANCE: colour → value, AVERAGE: vector →
// value); value → colour/vector is the broadcast itself.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"
#include "texture/image_texture.h"
#include "texture/sky_nishita.h"

namespace candela {

class SceneArrays;

enum class ShaderOpCode : uint32_t {
    Const,           // i0: offset of 3 floats in shader_consts
    Coord,           // i0: CoordKind, i1: 0 at the point, 1/2 at the point moved by ShadingInputs::dp[0]/[1] (Bump)
    Image,           // a: vector; i0: texture, i1: TexInterpolation, i2: TexExtension, i3: ImageProjection
    ImageAlpha,      // as Image, the alpha channel
    Mix,             // a: factor, b: A, c: B; i0: MixBlend, i1: clamp factor, i2: clamp result, i3: per-channel factor
    Math,            // a, b, c per channel; i0: MathOp, i1: clamp result to [0, 1]
    Ramp,            // a: factor; i0: ramp, i1: interpolate (0 = constant)
    RampAlpha,       // as Ramp, the alpha channel
    Luminance,       // a: colour → Rec.709 luminance
    Average,         // a: vector → (x + y + z)/3
    Combine,         // a, b, c (first channels); i0: ColorModel
    Separate,        // a; i0: ColorModel, i1: channel
    Mapping,         // a: vector; i0: offset of a row-major 3×4 matrix in shader_consts, i1: normalise the result
    NormalMap,       // a: colour, b: strength; i0: NormalMapSpace
    Invert,          // a: factor, b: colour
    BrightContrast,  // a: colour, b: bright, c: contrast
    // Procedural textures (texture/procedural.h, texture/voronoi.h). "(x, y, z)" is one register's channels; a
    // "register i_k" immediate names a further input register (shader_op_register_immediates()).
    TexNoise,  // a: vector, b: (w, scale, detail), c: (roughness, distortion, -); i0: dimensions, i1: 0 fac, 1 colour
    TexWhiteNoise,  // a: vector, b: (w, -, -); i0: dimensions, i1: 0 value, 1 colour
    TexMusgrave,    // a: vector, b: (w, scale, detail), c: (dimension, lacunarity, offset); i0: register (gain);
                    // i1: dimensions, i2: musgrave_types
    TexVoronoi,     // a: vector, b: (w, scale, smoothness), c: (exponent, randomness, -); i0: dimensions,
                    // i1: voronoi_features, i2: voronoi_metrics, i3: 0 distance, 1 colour, 2 position, 3 w, 4 radius
    TexWave,        // a: vector, b: (scale, distortion, detail), c: (detail scale, detail roughness, phase);
                    // i0: wave_types, i1: direction (X, Y, Z, diagonal/spherical), i2: wave_profiles
    TexMagic,       // a: vector, b: (scale, distortion, -); i0: depth, i1: 0 colour, 1 fac
    TexChecker,     // a: vector, b: colour 1, c: colour 2; i0: register (scale); i1: 0 colour, 1 fac
    TexGradient,    // a: vector; i0: gradient_types
    TexBrick,       // a: vector, b: colour 1, c: colour 2; i0: register (mortar colour), i1: register (scale,
                    // mortar size, mortar smooth), i2: register (bias, brick width, row height); i3: offset of 5
                    // constants (offset, offset frequency, squash, squash frequency, output: 0 colour, 1 fac)
    // Input and converter nodes.
    VectorMath,     // a, b, c vectors; i0: vector_math_ops, i1: 0 vector result, 1 value result
    MapRange,       // a: value(s), b: from min, c: from max; i0: register (to min), i1: register (to max),
                    // i2: register (steps); i3: map_range_types | clamp << 8
    HueSaturation,  // a: colour, b: (hue, saturation, value), c: fac
    LayerWeight,    // a: normal, b: blend; i0: 0 Fresnel, 1 Facing
    Fresnel,        // a: normal, b: IOR
    Bump,           // a, b, c: height at the point and at its two offsets; i0: register (strength, distance, -),
                    // i1: register (normal), i2: invert
    Attribute,      // i0: attribute slot (`corner_attributes`), i1: 0 colour/vector, 1 fac (mean of x, y, z), 2 alpha
    Sky,            // a: direction; i0: offset of the model's precomputed state in shader_consts, i1: sky_models
    Curves,         // a: fac, b: value(s); i0: ramp (the curves baked over [min x, max x]), i1: offset of (min x,
                    // x range) in shader_consts, i2: 0 per channel (RGB/Vector Curves), 1 one value (Float Curve)
    Blackbody,      // a: temperature (K) → colour of luminance 1
    Wavelength,     // a: wavelength (nm) → colour (the Wavelength node: the CIE 1931 observer in Rec.709)
};
/// Bit k set: immediate i_k of the operation is a register it reads (validated like a, b, c).
uint32_t shader_op_register_immediates(ShaderOpCode code);
const std::vector<std::string>& shader_op_names();

/// What a COORD operation reads. Surfaces: UV (u, v, 0) of the render UV map, GENERATED (Blender's texture
/// space: the object-space position normalised by the mesh's texture-space box), OBJECT (object-space
/// position), NORMAL (object-space shading normal), WORLD_NORMAL, INCOMING (toward the viewer), POSITION (the
/// world position, Blender's world axes and origin), TRUE_NORMAL (the geometric normal), BACKFACING (1 when the
/// viewer sees the back, else 0), REFLECTION (the view direction mirrored about the normal on the viewer's
/// side, world space), OBJECT_LOCATION (the object's origin in world space). NORMAL, WORLD_NORMAL and
/// TRUE_NORMAL are on the winding side. The world: GENERATED, OBJECT, POSITION, REFLECTION and INCOMING are the
/// view direction, the normals its opposite, UV and OBJECT_LOCATION 0.
enum class CoordKind : uint32_t {
    Uv,
    Generated,
    Object,
    Normal,
    WorldNormal,
    Incoming,
    Position,
    TrueNormal,
    Backfacing,
    Reflection,
    ObjectLocation,
    ObjectIndex,  // the object's pass index (Object Info > Object Index)
    Tangent,      // Geometry > Tangent: the tangent around the object's Z axis of Generated space (Cycles' default)
    // The Light Path node (ShadingInputs::path): 1 or 0 for the ray-type outputs, the counts as values.
    IsCameraRay,
    IsShadowRay,
    IsDiffuseRay,
    IsGlossyRay,
    IsSingularRay,
    IsReflectionRay,
    IsTransmissionRay,
    RayLength,
    RayDepth,
    DiffuseDepth,
    GlossyDepth,
    TransparentDepth,
    TransmissionDepth,
    // Object Info > Color, Alpha and Random (the object's colour, its alpha, a hash of its name in [0, 1)).
    ObjectColor,
    ObjectAlpha,
    ObjectRandom,
    // Texture Coordinate > Window: the point's position on the camera's image, (0, 0) bottom left to (1, 1), z 0.
    Window,
};
/// True for the Light Path node's kinds (they depend on the path, not on the point).
inline bool is_light_path_coord(CoordKind k) {
    return k >= CoordKind::IsCameraRay && k <= CoordKind::TransmissionDepth;
}
// Procedural-texture enumerations by their Blender identifiers.
const std::vector<std::string>& musgrave_type_names();
const std::vector<std::string>& voronoi_feature_names();
const std::vector<std::string>& voronoi_metric_names();
const std::vector<std::string>& wave_type_names();
const std::vector<std::string>& wave_profile_names();
const std::vector<std::string>& gradient_type_names();
const std::vector<std::string>& vector_math_op_names();
const std::vector<std::string>& map_range_type_names();
const std::vector<std::string>& sky_model_names();
const std::vector<std::string>& coord_kind_names();

enum class ImageProjection : uint32_t { Flat, Equirectangular, MirrorBall };
const std::vector<std::string>& image_projection_names();

enum class ColorModel : uint32_t { Rgb, Hsv, Hsl };
const std::vector<std::string>& color_model_names();

/// Spaces of the Normal Map node (Cycles 3.4 svm_node_normal_map).
enum class NormalMapSpace : uint32_t { Tangent, Object, World, BlenderObject, BlenderWorld };
const std::vector<std::string>& normal_map_space_names();

/// Equirectangular (u, v) of a direction, Blender's convention: u = ½ − atan2(y, x)/2π, v = 1 − acos(z)/π
/// (the image centre faces +X, v = 0 is straight down). The direction need not be normalised.
Vec2 direction_to_equirectangular(const Vec3& d);
/// The unit direction of equirectangular (u, v).
Vec3 equirectangular_to_direction(float u, float v);

/// What the Light Path node reads at a shading point: the type of the ray that arrived there and the path's counts,
/// with Cycles 3.4's meaning (docs/light_paths.md). `flags` holds the ray types (several at once: a diffuse
/// reflection ray is DIFFUSE | REFLECTION; a camera ray through a transparent surface is still CAMERA). The depths
/// count the scatterings before the ray (transparent pass-throughs only in transparent_depth). Where no path is
/// known (light sampling evaluating an emitter, the world's importance map) the flags are 0, as Cycles' emission
/// evaluation has them, and depth is the shading vertex's depth + 1.
struct LightPathInfo {
    enum Flag : uint32_t {
        k_camera = 1u << 0,
        k_shadow = 1u << 1,
        k_diffuse = 1u << 2,
        k_glossy = 1u << 3,
        k_singular = 1u << 4,
        k_reflection = 1u << 5,
        k_transmission = 1u << 6,
    };
    uint32_t flags = 0;
    float ray_length = 0.f;  // length of the ray segment that reached the point (Cycles' sd->ray_length)
    int depth = 0, diffuse_depth = 0, glossy_depth = 0, transmission_depth = 0, transparent_depth = 0;
};

/// What the program may read at one shading point. World-space vectors are camera-relative world axes.
struct ShadingInputs {
    Vec3 uv{0.f}, generated{0.f}, object{0.f};
    Vec3 normal_object{0.f, 0.f, 1.f};
    Vec3 normal{0.f, 0.f, 1.f};  // world shading normal, on the side of the winding normal
    Vec3 incoming{0.f, 0.f, 1.f};
    // Tangent-space normal maps: the interpolated UV tangent (world) and bitangent sign.
    Vec3 tangent{0.f};
    float tangent_sign = 1.f;
    bool has_tangent = false;
    Affine normal_to_world;           // object → world for normals (object-space normal maps)
    bool backfacing = false;          // the viewer is on the back (against the winding normal): Cycles flips N there
    Vec3 position{0.f};               // world position (Blender's origin, not camera-relative)
    Vec3 true_normal{0.f, 0.f, 1.f};  // geometric normal, winding side
    Vec3 object_location{0.f};        // the object's origin, world
    float object_index = 0.f;         // its pass index
    Vec3 object_color{1.f};           // Object Info > Color (the object's viewport colour, Object > Viewport Display)
    float object_alpha = 1.f;         // its alpha
    float object_random = 0.f;        // Object Info > Random: a hash of the object's name in [0, 1)
    Vec3 window{0.f};                 // Texture Coordinate > Window (the camera's image coordinates of the point)
    LightPathInfo path;               // the Light Path node's inputs
    // Mesh attributes (Attribute, Color Attribute, UV Map with a named map): the hit triangle's corner values, 4
    // floats per slot, and its barycentrics. Null: the mesh has none (the attributes read 0).
    const float* attributes = nullptr;
    uint32_t attribute_slots = 0;
    float b1 = 0.f, b2 = 0.f;
    // Bump's finite differences (set where the program has offset coordinates): two small world offsets in the
    // tangent plane and what they change in the position-derived coordinates.
    Vec3 dp[2], dobject[2], dgenerated[2], duv[2];

    /// The inputs of the world shader for view direction d.
    static ShadingInputs world(const Vec3& d);
};

struct ShaderOp {
    ShaderOpCode code = ShaderOpCode::Const;
    uint32_t a = 0, b = 0, c = 0;
    uint32_t i[4] = {0, 0, 0, 0};
};

/// The images of a scene: two texel pools and, per image, [first texel, width, height, colour space, storage].
struct TexturePools {
    std::vector<float> floats;   // RGBA float32 texels (`textures`)
    std::vector<uint8_t> bytes;  // RGBA 8-bit texels (`textures_u8`)
    std::vector<uint32_t> info;  // rows of 5 (`texture_info`)
};

/// Every shader program of a scene with the images, ramps and constants they use. Immutable after load.
class ShaderLibrary {
public:
    /// Reads and validates textures, ramps and programs; an empty library if the arrays are absent.
    static std::shared_ptr<const ShaderLibrary> load(const SceneArrays& arrays);

    /// Programs built directly (tests): the pools are taken as they are and validated.
    ShaderLibrary(TexturePools textures, std::vector<float> ramps, std::vector<float> consts, std::vector<ShaderOp> ops,
                  std::vector<uint32_t> program_start);
    ShaderLibrary(const ShaderLibrary&) = delete;  // the texture views point into this object's texel pool
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    size_t program_count() const { return m_program_start.empty() ? 0 : m_program_start.size() - 1; }
    uint32_t program_size(uint32_t p) const { return m_program_start[p + 1] - m_program_start[p]; }
    /// True if program p reads coordinates at offset points (a Bump node): ShadingInputs::dp and friends.
    bool uses_differentials(uint32_t p) const { return m_differentials[p] != 0; }
    /// True if register r of program p depends on the shading point or the path (else it is the same everywhere).
    bool varying(uint32_t p, uint32_t r) const { return m_varying[m_program_start[p] + r] != 0; }
    /// True if it depends on the point itself (a register that varies only with the path, through a Light Path
    /// node, is the same at every point of a surface or in every direction of the world).
    bool spatially_varying(uint32_t p, uint32_t r) const {
        return (m_varying[m_program_start[p] + r] & k_spatial) != 0;
    }
    /// True if it depends on the path (a Light Path node upstream).
    bool path_dependent(uint32_t p, uint32_t r) const { return (m_varying[m_program_start[p] + r] & k_path) != 0; }
    /// True if any program reads a Light Path output.
    bool reads_light_path() const { return m_reads_light_path; }
    /// True if any program reads Texture Coordinate > Window (ShadingInputs::window is then computed).
    bool reads_window() const { return m_reads_window; }

    /// Runs program p; regs must hold program_size(p) entries.
    void evaluate(uint32_t p, const ShadingInputs& in, Vec3* regs) const;

    const std::vector<ImageTexture>& textures() const { return m_textures; }
    const ShaderOp& op(uint32_t p, uint32_t r) const { return m_ops[m_program_start[p] + r]; }

    /// The sun disc of a Nishita Sky Texture in program p that reads the plain view direction: its direction and
    /// angular radius (environment lights sample it as a strategy of its own). False if there is none.
    bool sun_disc(uint32_t p, Vec3* direction, float* half_angle) const;

    /// Largest program size (the register file callers allocate).
    uint32_t max_program_size() const { return m_max_size; }

private:
    Vec3 ramp(uint32_t index, float fac, bool interpolate, bool alpha) const;
    /// Channel c of ramp `index` at f with Cycles' linear extrapolation past [0, 1] (curve tables).
    float curve(uint32_t index, float f, int c) const;
    /// The procedural textures and converter nodes (texture/node_ops.cpp).
    Vec3 evaluate_node(const ShaderOp& op, const Vec3* regs, const ShadingInputs& in) const;

    TexturePools m_pools;
    std::vector<ImageTexture> m_textures;
    std::vector<float> m_ramps;
    std::vector<float> m_consts;
    std::vector<ShaderOp> m_ops;
    std::vector<uint32_t> m_program_start;
    static constexpr uint8_t k_spatial = 1, k_path = 2;
    std::vector<uint8_t> m_varying;  // per operation: k_spatial | k_path bits
    bool m_reads_light_path = false;
    bool m_reads_window = false;
    std::vector<uint8_t> m_differentials;  // per program
    std::vector<NishitaSky> m_skies;       // the Nishita skies, tabulated at load
    std::vector<int32_t> m_sky_of_op;      // per operation: index in m_skies, or −1 (empty without skies)
    uint32_t m_max_size = 0;
};

/// Entries per ColorRamp table (Cycles bakes ramps into 256 entries and interpolates between them).
inline constexpr uint32_t k_ramp_size = 256;

/// A register file for one evaluation: on the stack for the usual small programs.
class ShaderRegisters {
public:
    explicit ShaderRegisters(uint32_t size) {
        if (size > k_inline) m_heap.resize(size);
    }
    Vec3* data() { return m_heap.empty() ? m_inline : m_heap.data(); }
    const Vec3& operator[](uint32_t i) const { return m_heap.empty() ? m_inline[i] : m_heap[i]; }

private:
    static constexpr uint32_t k_inline = 64;
    Vec3 m_inline[k_inline];
    std::vector<Vec3> m_heap;
};

}  // namespace candela
