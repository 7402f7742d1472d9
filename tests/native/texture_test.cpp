// Image lookup (sRGB decoding, wrap modes, closest / bilinear / cubic), shader program operations, the
// Normal Map node's frame and Blender's equirectangular mapping. Expected values are computed by hand from
// the definitions (Cycles 3.4's image and node semantics), so every check can fail.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "shader_test_helpers.h"
#include "texture/color_space.h"
#include "texture/converter_nodes.h"
#include "texture/node_math.h"

namespace candela::test {
namespace {

constexpr float k_eps = 1e-6f;

void expect_vec(const Vec3& got, const Vec3& want, float tol, const char* what) {
    EXPECT_NEAR(got.x, want.x, tol) << what;
    EXPECT_NEAR(got.y, want.y, tol) << what;
    EXPECT_NEAR(got.z, want.z, tol) << what;
}

// ---- colour space -------------------------------------------------------------------------------------------

TEST(ColorSpace, SrgbDecodeMatchesTheStandard) {
    EXPECT_EQ(srgb_to_linear(0.f), 0.f);
    EXPECT_NEAR(srgb_to_linear(1.f), 1.f, k_eps);
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.214041140f, 1e-6f);     // ((0.5 + 0.055)/1.055)^2.4
    EXPECT_NEAR(srgb_to_linear(0.04f), 0.04f / 12.92f, 1e-9f);  // linear segment
    EXPECT_EQ(srgb_to_linear(-0.2f), 0.f);
    // The two pieces meet at the threshold (continuity to 1e-6 relative).
    EXPECT_NEAR(srgb_to_linear(0.04045f - 1e-7f), srgb_to_linear(0.04045f), 1e-6f);
}

TEST(ColorSpace, HsvAndHslRoundTrip) {
    for (const Color c : {Color(0.8f, 0.2f, 0.4f), Color(0.1f, 0.9f, 0.3f), Color(0.2f, 0.3f, 0.7f), Color(0.5f)}) {
        expect_vec(hsv_to_rgb(rgb_to_hsv(c)), c, 1e-5f, "hsv");
        expect_vec(hsl_to_rgb(rgb_to_hsl(c)), c, 1e-5f, "hsl");
    }
    expect_vec(rgb_to_hsv(Color(1.f, 0.f, 0.f)), Vec3(0.f, 1.f, 1.f), k_eps, "red");
    expect_vec(rgb_to_hsv(Color(0.f, 0.5f, 0.f)), Vec3(1.f / 3.f, 1.f, 0.5f), k_eps, "green");
}

// ---- image lookup -------------------------------------------------------------------------------------------

/// 2×2 image: bottom row (v < ½) black, white; top row red, blue.
ProgramBuilder two_by_two(TexColorSpace cs = TexColorSpace::Linear) {
    ProgramBuilder b;
    b.image(2, 2, {Color(0.f), Color(1.f), Color(1.f, 0.f, 0.f), Color(0.f, 0.f, 1.f)}, cs);
    return b;
}

TEST(ImageTexture, ClosestTakesTheTexelUnderThePoint) {
    const auto lib = two_by_two().library();
    const ImageTexture& t = lib->textures()[0];
    expect_vec(t.lookup(0.1f, 0.1f, TexInterpolation::Closest, TexExtension::Repeat).rgb, Color(0.f), k_eps, "bl");
    expect_vec(t.lookup(0.9f, 0.1f, TexInterpolation::Closest, TexExtension::Repeat).rgb, Color(1.f), k_eps, "br");
    expect_vec(t.lookup(0.1f, 0.9f, TexInterpolation::Closest, TexExtension::Repeat).rgb, Color(1, 0, 0), k_eps, "tl");
    expect_vec(t.lookup(0.9f, 0.9f, TexInterpolation::Closest, TexExtension::Repeat).rgb, Color(0, 0, 1), k_eps, "tr");
}

TEST(ImageTexture, BilinearIsExactAtTexelCentresAndAveragesBetween) {
    const auto lib = two_by_two().library();
    const ImageTexture& t = lib->textures()[0];
    const auto L = TexInterpolation::Linear;
    expect_vec(t.lookup(0.25f, 0.25f, L, TexExtension::Extend).rgb, Color(0.f), k_eps, "centre bl");
    expect_vec(t.lookup(0.75f, 0.75f, L, TexExtension::Extend).rgb, Color(0, 0, 1), k_eps, "centre tr");
    // The image centre weighs all four texels by ¼.
    expect_vec(t.lookup(0.5f, 0.5f, L, TexExtension::Extend).rgb, Color(0.5f, 0.25f, 0.5f), k_eps, "middle");
    // A quarter texel right of the bottom-left centre: ¾ black + ¼ white.
    expect_vec(t.lookup(0.375f, 0.25f, L, TexExtension::Extend).rgb, Color(0.25f), k_eps, "quarter");
    EXPECT_NEAR(t.lookup(0.5f, 0.5f, L, TexExtension::Extend).a, 1.f, k_eps);
}

TEST(ImageTexture, WrapModes) {
    const auto lib = two_by_two().library();
    const ImageTexture& t = lib->textures()[0];
    const auto C = TexInterpolation::Closest, L = TexInterpolation::Linear;
    // Repeat: u + k ≡ u, also for negative coordinates.
    expect_vec(t.lookup(2.9f, -0.9f, C, TexExtension::Repeat).rgb, Color(1.f), k_eps, "repeat");
    // Bilinear across the seam: at u = 0 the left and right columns blend half and half.
    expect_vec(t.lookup(0.f, 0.25f, L, TexExtension::Repeat).rgb, Color(0.5f), k_eps, "repeat seam");
    // Extend: the border texel continues outward.
    expect_vec(t.lookup(-5.f, 0.25f, L, TexExtension::Extend).rgb, Color(0.f), k_eps, "extend left");
    expect_vec(t.lookup(7.f, 0.25f, L, TexExtension::Extend).rgb, Color(1.f), k_eps, "extend right");
    // Clip: transparent black outside; at the border the outer half of the filter reads black.
    const Rgba out = t.lookup(1.5f, 0.25f, C, TexExtension::Clip);
    expect_vec(out.rgb, Color(0.f), k_eps, "clip outside");
    EXPECT_EQ(out.a, 0.f);
    expect_vec(t.lookup(1.f, 0.25f, L, TexExtension::Clip).rgb, Color(0.5f), k_eps, "clip border");
}

TEST(ImageTexture, SrgbImagesAreDecodedAfterInterpolation) {
    const auto lib = two_by_two(TexColorSpace::Srgb).library();
    const ImageTexture& t = lib->textures()[0];
    // Texel white (1) stays 1; the black/white midpoint is decode(0.5), not 0.5 (Cycles' byte sRGB images).
    expect_vec(t.lookup(0.75f, 0.25f, TexInterpolation::Linear, TexExtension::Extend).rgb, Color(1.f), k_eps, "white");
    expect_vec(t.lookup(0.5f, 0.25f, TexInterpolation::Linear, TexExtension::Extend).rgb, Color(srgb_to_linear(0.5f)),
               k_eps, "midpoint");
}

TEST(ImageTexture, ByteImagesReadValueOver255AndDecodeAfterFiltering) {
    ProgramBuilder b;
    b.byte_image(2, 1, {{{0, 128, 255}}, {{255, 64, 0}}}, TexColorSpace::Srgb);
    b.byte_image(2, 1, {{{0, 128, 255}}, {{255, 64, 0}}}, TexColorSpace::Linear);
    const auto lib = b.library();
    const auto L = TexInterpolation::Linear;
    const auto E = TexExtension::Extend;
    expect_vec(lib->textures()[1].lookup(0.25f, 0.5f, L, E).rgb, Color(0.f, 128.f / 255.f, 1.f), k_eps, "raw texel");
    EXPECT_NEAR(lib->textures()[1].lookup(0.25f, 0.5f, L, E).a, 1.f, k_eps);
    // Halfway between the texels the encoded values average first: decode((0 + 255)/2/255) etc.
    expect_vec(lib->textures()[0].lookup(0.5f, 0.5f, L, E).rgb,
               srgb_to_linear(Color(0.5f, (128.f + 64.f) / 510.f, 0.5f)), 1e-6f, "decoded midpoint");
}

TEST(ImageTexture, CubicReproducesAConstantImage) {
    ProgramBuilder b;
    b.image(3, 3, std::vector<Color>(9, Color(0.3f, 0.6f, 0.9f)));
    const auto lib = b.library();
    for (float u : {0.f, 0.13f, 0.5f, 0.97f})
        expect_vec(lib->textures()[0].lookup(u, 0.4f, TexInterpolation::Cubic, TexExtension::Repeat).rgb,
                   Color(0.3f, 0.6f, 0.9f), 1e-5f, "cubic");
}

// ---- program operations -------------------------------------------------------------------------------------

TEST(ShaderProgram, ConstCoordAndImage) {
    ProgramBuilder b = two_by_two();
    const uint32_t k = b.constant(Vec3(0.1f, 0.2f, 0.3f));
    const uint32_t uv = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Uv)});
    const uint32_t img = b.op(ShaderOpCode::Image, uv, 0, 0, {0, uint32_t(TexInterpolation::Closest), 0, 0});
    const uint32_t alpha = b.op(ShaderOpCode::ImageAlpha, uv, 0, 0, {0, 0, 0, 0});
    b.end_program();
    const auto lib = b.library();
    ShadingInputs in;
    in.uv = Vec3(0.9f, 0.9f, 0.f);
    expect_vec(eval(*lib, 0, k, in), Vec3(0.1f, 0.2f, 0.3f), k_eps, "const");
    expect_vec(eval(*lib, 0, uv, in), in.uv, k_eps, "uv");
    expect_vec(eval(*lib, 0, img, in), Color(0, 0, 1), k_eps, "image");
    expect_vec(eval(*lib, 0, alpha, in), Vec3(1.f), k_eps, "alpha");
    EXPECT_FALSE(lib->varying(0, k));
    EXPECT_TRUE(lib->varying(0, img));
}

TEST(ShaderProgram, MathOperationsFollowCyclesSafeRules) {
    struct Case {
        MathOp op;
        float a, b, c, want;
    };
    const Case cases[] = {
        {MathOp::Add, 1.5f, 2.f, 0.f, 3.5f},
        {MathOp::Subtract, 1.f, 3.f, 0.f, -2.f},
        {MathOp::Multiply, 2.f, -3.f, 0.f, -6.f},
        {MathOp::Divide, 1.f, 0.f, 0.f, 0.f},
        {MathOp::Divide, 1.f, 4.f, 0.f, 0.25f},
        {MathOp::MultiplyAdd, 2.f, 3.f, 1.f, 7.f},
        {MathOp::Power, 2.f, 3.f, 0.f, 8.f},
        {MathOp::Power, -2.f, 0.5f, 0.f, 0.f},
        {MathOp::Power, -2.f, 3.f, 0.f, -8.f},
        {MathOp::Logarithm, 8.f, 2.f, 0.f, 3.f},
        {MathOp::Logarithm, -1.f, 2.f, 0.f, 0.f},
        {MathOp::Sqrt, -4.f, 0.f, 0.f, 0.f},
        {MathOp::InverseSqrt, 4.f, 0.f, 0.f, 0.5f},
        {MathOp::Absolute, -3.f, 0.f, 0.f, 3.f},
        {MathOp::Minimum, 1.f, 2.f, 0.f, 1.f},
        {MathOp::Maximum, 1.f, 2.f, 0.f, 2.f},
        {MathOp::LessThan, 1.f, 2.f, 0.f, 1.f},
        {MathOp::GreaterThan, 1.f, 2.f, 0.f, 0.f},
        {MathOp::Sign, -0.3f, 0.f, 0.f, -1.f},
        {MathOp::Compare, 1.f, 1.05f, 0.1f, 1.f},
        {MathOp::Compare, 1.f, 1.5f, 0.1f, 0.f},
        {MathOp::Round, 2.5f, 0.f, 0.f, 3.f},
        {MathOp::Floor, -1.5f, 0.f, 0.f, -2.f},
        {MathOp::Ceil, -1.5f, 0.f, 0.f, -1.f},
        {MathOp::Trunc, -1.5f, 0.f, 0.f, -1.f},
        {MathOp::Fract, -1.25f, 0.f, 0.f, 0.75f},
        {MathOp::Modulo, -5.f, 3.f, 0.f, -2.f},
        {MathOp::Modulo, 5.f, 0.f, 0.f, 0.f},
        {MathOp::Wrap, 5.5f, 2.f, 1.f, 1.5f},
        {MathOp::Snap, 5.3f, 2.f, 0.f, 4.f},
        {MathOp::Pingpong, 3.f, 2.f, 0.f, 1.f},
        {MathOp::Sine, k_pi / 2, 0.f, 0.f, 1.f},
        {MathOp::Arccosine, 2.f, 0.f, 0.f, 0.f},
        {MathOp::Arctan2, 1.f, 1.f, 0.f, k_pi / 4},
        {MathOp::Radians, 180.f, 0.f, 0.f, k_pi},
        {MathOp::Degrees, k_pi, 0.f, 0.f, 180.f},
        {MathOp::SmoothMin, 1.f, 1.f, 0.f, 1.f},
        {MathOp::SmoothMin, 1.f, 1.f, 1.f, 1.f - 1.f / 6.f},
        {MathOp::SmoothMax, 1.f, 1.f, 1.f, 1.f + 1.f / 6.f},
    };
    for (const Case& c : cases)
        EXPECT_NEAR(math_op(c.op, c.a, c.b, c.c), c.want, 1e-5f) << math_op_names()[size_t(c.op)];

    // Through a program: per channel, and the clamp flag saturates.
    ProgramBuilder b;
    const uint32_t x = b.constant(Vec3(0.5f, 2.f, -1.f)), y = b.constant(Vec3(2.f));
    const uint32_t m = b.op(ShaderOpCode::Math, x, y, y, {uint32_t(MathOp::Multiply), 0});
    const uint32_t mc = b.op(ShaderOpCode::Math, x, y, y, {uint32_t(MathOp::Multiply), 1});
    b.end_program();
    const auto lib = b.library();
    expect_vec(eval(*lib, 0, m), Vec3(1.f, 4.f, -2.f), k_eps, "math");
    expect_vec(eval(*lib, 0, mc), Vec3(1.f, 1.f, 0.f), k_eps, "math clamp");
}

TEST(ShaderProgram, MixBlends) {
    const Color a(0.2f, 0.4f, 0.8f), c(0.5f, 0.5f, 1.f);
    expect_vec(mix_blend(MixBlend::Mix, 0.25f, a, c), a * 0.75f + c * 0.25f, k_eps, "mix");
    expect_vec(mix_blend(MixBlend::Multiply, 1.f, a, c), a * c, k_eps, "multiply");
    expect_vec(mix_blend(MixBlend::Multiply, 0.5f, a, c), a * (Color(0.5f) + c * 0.5f), k_eps, "multiply half");
    expect_vec(mix_blend(MixBlend::Add, 0.5f, a, c), a + c * 0.5f, k_eps, "add");
    expect_vec(mix_blend(MixBlend::Subtract, 1.f, a, c), a - c, k_eps, "subtract");
    expect_vec(mix_blend(MixBlend::Screen, 1.f, a, c), Color(1.f) - (Color(1.f) - a) * (Color(1.f) - c), k_eps,
               "screen");
    expect_vec(mix_blend(MixBlend::Difference, 1.f, a, c), vabs(a - c), k_eps, "difference");
    expect_vec(mix_blend(MixBlend::Darken, 1.f, a, c), vmin(a, c), k_eps, "darken");
    expect_vec(mix_blend(MixBlend::Lighten, 1.f, a, c), vmax(a, c), k_eps, "lighten");
    // Cycles blends toward the maximum (svm_mix_light), unlike Blender's compositor max(a, t·b).
    expect_vec(mix_blend(MixBlend::Lighten, 0.5f, Color(0.2f), Color(0.8f)), Color(0.5f), k_eps, "lighten half");
    expect_vec(mix_blend(MixBlend::Divide, 1.f, a, c), a / c, k_eps, "divide");
    expect_vec(mix_blend(MixBlend::LinearLight, 1.f, a, c), a + c * 2.f - Color(1.f), k_eps, "linear light");
    // Value blend at t = 1 takes b's value with a's hue and saturation.
    expect_vec(mix_blend(MixBlend::Value, 1.f, Color(0.5f, 0.25f, 0.f), Color(1.f)), Color(1.f, 0.5f, 0.f), 1e-5f,
               "value");

    // Through a program: the factor clamps when asked, the result clamps when asked.
    ProgramBuilder b;
    const uint32_t f = b.constant(Vec3(2.f)), ka = b.constant(a), kc = b.constant(c);
    const uint32_t raw = b.op(ShaderOpCode::Mix, f, ka, kc, {uint32_t(MixBlend::Mix), 0, 0, 0});
    const uint32_t clamped = b.op(ShaderOpCode::Mix, f, ka, kc, {uint32_t(MixBlend::Mix), 1, 0, 0});
    const uint32_t add = b.op(ShaderOpCode::Mix, f, ka, kc, {uint32_t(MixBlend::Add), 1, 1, 0});
    b.end_program();
    const auto lib = b.library();
    expect_vec(eval(*lib, 0, raw), a * -1.f + c * 2.f, k_eps, "unclamped factor");
    expect_vec(eval(*lib, 0, clamped), c, k_eps, "clamped factor");
    expect_vec(eval(*lib, 0, add), Vec3(0.7f, 0.9f, 1.f), k_eps, "clamped result");
}

TEST(ShaderProgram, RampConversionsAndColourModels) {
    ProgramBuilder b;
    std::vector<std::array<float, 4>> table(k_ramp_size);
    for (uint32_t i = 0; i < k_ramp_size; ++i) {
        const float t = float(i) / float(k_ramp_size - 1);
        table[i] = {t, 1.f - t, 0.5f, t * t};
    }
    const uint32_t ramp = b.ramp(table);
    const float f = 0.3f;
    const uint32_t fac = b.constant(Vec3(f));
    const uint32_t lin = b.op(ShaderOpCode::Ramp, fac, 0, 0, {ramp, 1});
    const uint32_t cst = b.op(ShaderOpCode::Ramp, fac, 0, 0, {ramp, 0});
    const uint32_t alpha = b.op(ShaderOpCode::RampAlpha, fac, 0, 0, {ramp, 1});
    const uint32_t col = b.constant(Vec3(0.2f, 0.5f, 0.9f));
    const uint32_t lum = b.op(ShaderOpCode::Luminance, col);
    const uint32_t avg = b.op(ShaderOpCode::Average, col);
    const uint32_t hsv = b.op(ShaderOpCode::Separate, col, 0, 0, {uint32_t(ColorModel::Hsv), 2});
    const uint32_t rebuilt = b.op(ShaderOpCode::Combine, b.op(ShaderOpCode::Separate, col, 0, 0, {1, 0}),
                                  b.op(ShaderOpCode::Separate, col, 0, 0, {1, 1}), hsv, {uint32_t(ColorModel::Hsv)});
    const uint32_t inv = b.op(ShaderOpCode::Invert, b.constant(Vec3(0.25f)), col);
    const uint32_t bc = b.op(ShaderOpCode::BrightContrast, col, b.constant(Vec3(0.1f)), b.constant(Vec3(0.5f)));
    b.end_program();
    const auto lib = b.library();
    // 256-entry table, linear between entries (Cycles' rgb_ramp_lookup): x = 0.3·255 = 76.5.
    const float x = f * 255.f, t0 = 76.f / 255.f, t1 = 77.f / 255.f, w = x - 76.f;
    expect_vec(eval(*lib, 0, lin), Vec3(t0 * (1 - w) + t1 * w, 1.f - (t0 * (1 - w) + t1 * w), 0.5f), 1e-6f, "ramp");
    expect_vec(eval(*lib, 0, cst), Vec3(t0, 1.f - t0, 0.5f), 1e-6f, "ramp constant");
    EXPECT_NEAR(eval(*lib, 0, alpha).x, t0 * t0 * (1 - w) + t1 * t1 * w, 1e-6f);
    expect_vec(eval(*lib, 0, lum), Vec3(0.2126f * 0.2f + 0.7152f * 0.5f + 0.0722f * 0.9f), 1e-6f, "luminance");
    expect_vec(eval(*lib, 0, avg), Vec3(1.6f / 3.f), 1e-6f, "average");
    expect_vec(eval(*lib, 0, hsv), Vec3(0.9f), 1e-6f, "hsv value");
    expect_vec(eval(*lib, 0, rebuilt), Vec3(0.2f, 0.5f, 0.9f), 1e-5f, "hsv round trip");
    expect_vec(eval(*lib, 0, inv), Vec3(0.2f, 0.5f, 0.9f) * 0.75f + Vec3(0.8f, 0.5f, 0.1f) * 0.25f, 1e-6f, "invert");
    // Bright/Contrast: (1 + c)·x + (bright − c/2), floored at 0.
    expect_vec(eval(*lib, 0, bc), Vec3(0.15f, 0.6f, 1.2f), 1e-6f, "bright contrast");
}

TEST(ShaderProgram, MappingAppliesItsMatrix) {
    ProgramBuilder b;
    // Rotation by 90° about Z, then translation (1, 2, 3): (x, y, z) → (−y + 1, x + 2, z + 3).
    const uint32_t offset = uint32_t(b.consts.size());
    b.consts.insert(b.consts.end(), {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3});
    const uint32_t v = b.constant(Vec3(1.f, 0.f, 0.f));
    const uint32_t m = b.op(ShaderOpCode::Mapping, v, 0, 0, {offset, 0});
    const uint32_t n = b.op(ShaderOpCode::Mapping, v, 0, 0, {offset, 1});
    b.end_program();
    const auto lib = b.library();
    expect_vec(eval(*lib, 0, m), Vec3(1.f, 3.f, 3.f), k_eps, "point");
    expect_vec(eval(*lib, 0, n), normalize(Vec3(1.f, 3.f, 3.f)), 1e-6f, "normalised");
}

TEST(ShaderProgram, InvalidProgramsAreRejectedWithTheOperation) {
    ProgramBuilder b;
    b.op(ShaderOpCode::Luminance, 0);  // reads register 0 before it is computed
    b.end_program();
    try {
        b.library();
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("operation 0"), std::string::npos) << e.what();
    }
    ProgramBuilder c;
    c.op(ShaderOpCode::Image, 0, 0, 0, {3, 0, 0, 0});
    c.end_program();
    EXPECT_THROW(c.library(), InvalidScene);  // no texture 3
}

ShadingInputs tilted_frame();  // a shading frame with a tangent (below)

TEST(ShaderProgram, RandomProgramsStayFinite) {
    // Programs of random operations on extreme constants (±1e30, 0, tiny) and random coordinates: every register
    // must stay finite, so a texture network can never put NaN or Inf into a BSDF or the film.
    Pcg32 rng(17, 3);
    auto pick = [&](uint32_t n) { return std::min(uint32_t(rng.next_float() * float(n)), n - 1); };
    for (int trial = 0; trial < 300; ++trial) {
        ProgramBuilder b;
        b.image(3, 2, {Color(0.f), Color(1e30f), Color(0.5f), Color(-2.f), Color(3.f), Color(1e-30f)});
        std::vector<std::array<float, 4>> table(k_ramp_size, {1e30f, -1e30f, 0.f, 1.f});
        b.ramp(table);
        b.consts.insert(b.consts.end(), {1e30f, -1e30f, 0.f, 0.f, 1e-30f, 2.f, -1.f, 0.5f, 1e30f, 0.f, 0.f, 0.f});
        const float extremes[] = {1e30f, -1e30f, 0.f, 1e-30f, -0.5f, 3.f};
        for (int k = 0; k < 4; ++k) b.constant(Vec3(extremes[pick(6)], extremes[pick(6)], extremes[pick(6)]));
        for (int k = 0; k < 30; ++k) {
            const uint32_t r = uint32_t(b.ops.size());
            const auto code = ShaderOpCode(1 + pick(uint32_t(shader_op_names().size()) - 1));
            std::array<uint32_t, 4> imm = {0, 0, 0, 0};
            switch (code) {
            case ShaderOpCode::Coord: imm[0] = pick(uint32_t(coord_kind_names().size())); break;
            case ShaderOpCode::Image:
            case ShaderOpCode::ImageAlpha: imm = {0, pick(3), pick(3), pick(3)}; break;
            case ShaderOpCode::Mix: imm = {pick(uint32_t(mix_blend_names().size())), pick(2), pick(2), pick(2)}; break;
            case ShaderOpCode::Math: imm = {pick(uint32_t(math_op_names().size())), pick(2), 0, 0}; break;
            case ShaderOpCode::Ramp:
            case ShaderOpCode::RampAlpha: imm = {0, pick(2), 0, 0}; break;
            case ShaderOpCode::Combine: imm[0] = pick(3); break;
            case ShaderOpCode::Separate: imm = {pick(3), pick(3), 0, 0}; break;
            case ShaderOpCode::Mapping: imm = {0, pick(2), 0, 0}; break;
            case ShaderOpCode::NormalMap: imm[0] = pick(uint32_t(normal_map_space_names().size())); break;
            // The procedural textures and converters (register immediates name earlier registers).
            case ShaderOpCode::TexNoise:
            case ShaderOpCode::TexWhiteNoise: imm = {1 + pick(4), pick(2), 0, 0}; break;
            case ShaderOpCode::TexMusgrave:
                imm = {pick(r), 1 + pick(4), pick(uint32_t(musgrave_type_names().size())), 0};
                break;
            case ShaderOpCode::TexVoronoi:
                imm = {1 + pick(4), pick(uint32_t(voronoi_feature_names().size())),
                       pick(uint32_t(voronoi_metric_names().size())), pick(5)};
                break;
            case ShaderOpCode::TexWave: imm = {pick(2), pick(4), pick(3), 0}; break;
            case ShaderOpCode::TexMagic: imm = {pick(11), pick(2), 0, 0}; break;
            case ShaderOpCode::TexChecker: imm = {pick(r), pick(2), 0, 0}; break;
            case ShaderOpCode::TexGradient: imm[0] = pick(uint32_t(gradient_type_names().size())); break;
            case ShaderOpCode::TexBrick:
                imm = {pick(r), pick(r), pick(r), 0};
                break;  // consts 0..4: ±1e30, 0, 0, 1e-30
            case ShaderOpCode::VectorMath: imm = {pick(uint32_t(vector_math_op_names().size())), pick(2), 0, 0}; break;
            case ShaderOpCode::MapRange: imm = {pick(r), pick(r), pick(r), pick(4) | (pick(2) << 8)}; break;
            case ShaderOpCode::LayerWeight: imm[0] = pick(2); break;
            case ShaderOpCode::Bump: imm = {pick(r), pick(r), pick(2), 0}; break;
            default: break;
            }
            b.op(code, pick(r), pick(r), pick(r), imm);
        }
        b.end_program();
        const auto lib = b.library();
        ShadingInputs in = tilted_frame();
        in.uv = Vec3(extremes[pick(6)], extremes[pick(6)], 0.f);
        in.generated = in.object = Vec3(extremes[pick(6)], -1.f, 2.f);
        in.dp[0] = Vec3(1e-3f, 0.f, 0.f);
        in.dp[1] = Vec3(0.f, 1e-3f, 0.f);
        ShaderRegisters regs(lib->program_size(0));
        lib->evaluate(0, in, regs.data());
        for (uint32_t r = 0; r < lib->program_size(0); ++r)
            ASSERT_TRUE(is_finite(regs[r])) << "trial " << trial << ", register " << r << " ("
                                            << shader_op_names()[size_t(lib->op(0, r).code)] << ")";
    }
}

// ---- normal map ---------------------------------------------------------------------------------------------

ShadingInputs tilted_frame() {
    ShadingInputs in;
    in.normal = normalize(Vec3(0.2f, -0.1f, 1.f));
    in.tangent = normalize(cross(Vec3(0.f, 1.f, 0.f), in.normal));
    in.tangent_sign = 1.f;
    in.has_tangent = true;
    return in;
}

Vec3 normal_map_of(const ShadingInputs& in, NormalMapSpace space, const Vec3& color, float strength) {
    ProgramBuilder b;
    const uint32_t c = b.constant(color), s = b.constant(Vec3(strength));
    const uint32_t n = b.op(ShaderOpCode::NormalMap, c, s, 0, {uint32_t(space)});
    b.end_program();
    return eval(*b.library(), 0, n, in);
}

/// What the node returns for a mapped normal n: n after Cycles' silhouette guard (ensure_valid_reflection: the view
/// direction's mirror image about it stays above the surface). These tests check the mapping; the guard moves only
/// normals that tilt far from the geometric one, such as the tangent itself.
Vec3 guarded(const ShadingInputs& in, const Vec3& n) { return ensure_valid_reflection(in.true_normal, in.incoming, n); }

TEST(NormalMap, FlatMapChangesNothing) {
    const ShadingInputs in = tilted_frame();
    for (float strength : {1.f, 0.5f, 2.f})
        expect_vec(normal_map_of(in, NormalMapSpace::Tangent, Vec3(0.5f, 0.5f, 1.f), strength), in.normal, 1e-6f,
                   "flat");
}

TEST(NormalMap, TangentSpaceTiltsAlongTheTangentFrame) {
    const ShadingInputs in = tilted_frame();
    // (1, 0.5, 0.5) encodes n = (1, 0, 0): the tangent itself.
    expect_vec(normal_map_of(in, NormalMapSpace::Tangent, Vec3(1.f, 0.5f, 0.5f), 1.f), guarded(in, in.tangent), 1e-6f,
               "tangent");
    {  // the guard did move it: the tangent mirrors the view direction into the surface, the result does not
        const Vec3 n = normal_map_of(in, NormalMapSpace::Tangent, Vec3(1.f, 0.5f, 0.5f), 1.f);
        EXPECT_LT(dot(in.tangent * (2.f * dot(in.tangent, in.incoming)) - in.incoming, in.true_normal), 0.f);
        EXPECT_GE(dot(n * (2.f * dot(n, in.incoming)) - in.incoming, in.true_normal), 0.f);
    }
    // (0.5, 1, 0.5) encodes the bitangent sign·(N × T); a negative sign mirrors it.
    const Vec3 bt = cross(in.normal, in.tangent);
    expect_vec(normal_map_of(in, NormalMapSpace::Tangent, Vec3(0.5f, 1.f, 0.5f), 1.f), guarded(in, bt), 1e-6f,
               "bitangent");
    ShadingInputs mirrored = in;
    mirrored.tangent_sign = -1.f;
    expect_vec(normal_map_of(mirrored, NormalMapSpace::Tangent, Vec3(0.5f, 1.f, 0.5f), 1.f), guarded(in, -bt), 1e-6f,
               "mirrored");
    // 45° toward the tangent, at strength ½: normalize(N + ½(n − N)).
    const Vec3 n45 = normalize(in.tangent + in.normal);
    expect_vec(normal_map_of(in, NormalMapSpace::Tangent, Vec3(1.f, 0.5f, 1.f), 0.5f),
               guarded(in, normalize(in.normal + (n45 - in.normal) * 0.5f)), 1e-6f, "strength");
    // Strength 0 keeps the normal; no tangents keep it too (Cycles' fallback).
    expect_vec(normal_map_of(in, NormalMapSpace::Tangent, Vec3(1.f, 0.5f, 1.f), 0.f), in.normal, 1e-6f, "strength 0");
    ShadingInputs none = in;
    none.has_tangent = false;
    expect_vec(normal_map_of(none, NormalMapSpace::Tangent, Vec3(1.f, 0.5f, 1.f), 1.f), in.normal, 1e-6f, "no tangent");
}

TEST(NormalMap, ObjectAndWorldSpaces) {
    ShadingInputs in = tilted_frame();
    // Object rotated 90° about Z: object +X is world +Y.
    in.normal_to_world = Affine();
    in.normal_to_world.m[0][0] = 0.f;
    in.normal_to_world.m[0][1] = -1.f;
    in.normal_to_world.m[1][0] = 1.f;
    in.normal_to_world.m[1][1] = 0.f;
    expect_vec(normal_map_of(in, NormalMapSpace::World, Vec3(1.f, 0.5f, 0.5f), 1.f), guarded(in, Vec3(1, 0, 0)), 1e-6f,
               "world");
    expect_vec(normal_map_of(in, NormalMapSpace::Object, Vec3(1.f, 0.5f, 0.5f), 1.f), guarded(in, Vec3(0, 1, 0)), 1e-6f,
               "object");
    // Blender's own convention negates y and z.
    expect_vec(normal_map_of(in, NormalMapSpace::BlenderWorld, Vec3(0.5f, 1.f, 0.5f), 1.f), guarded(in, Vec3(0, -1, 0)),
               1e-6f, "blender world");
}

// ---- equirectangular mapping --------------------------------------------------------------------------------

TEST(Equirectangular, BlenderConvention) {
    auto uv = [](Vec3 d) { return direction_to_equirectangular(d); };
    EXPECT_NEAR(uv(Vec3(1, 0, 0)).x, 0.5f, k_eps);  // the image centre faces +X
    EXPECT_NEAR(uv(Vec3(1, 0, 0)).y, 0.5f, k_eps);
    EXPECT_NEAR(uv(Vec3(0, 1, 0)).x, 0.25f, k_eps);  // +Y is a quarter turn left of centre
    EXPECT_NEAR(uv(Vec3(0, -1, 0)).x, 0.75f, k_eps);
    EXPECT_NEAR(uv(Vec3(0, 0, 1)).y, 1.f, k_eps);  // up is the top row
    EXPECT_NEAR(uv(Vec3(0, 0, -1)).y, 0.f, k_eps);
    for (const Vec3 d : {normalize(Vec3(0.3f, -0.5f, 0.2f)), normalize(Vec3(-0.7f, 0.1f, -0.6f))}) {
        const Vec2 p = uv(d);
        expect_vec(equirectangular_to_direction(p.x, p.y), d, 1e-5f, "round trip");
    }
}

}  // namespace
}  // namespace candela::test
