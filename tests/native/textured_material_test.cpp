// Materials driven by shader programs, end to end through the path tracer: a texture seen through UV and
// Generated coordinates, a textured diffuse colour in a white furnace, constant folding (the fast path), a
// flat normal map that must change nothing, and validation of bindings.
#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/material_inputs.h"
#include "core/error.h"
#include "core/math.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"
#include "texture/node_math.h"

namespace candela::test {
namespace {

uint32_t column(const char* name) {
    const auto& c = closure_columns();
    return uint32_t(std::find(c.begin(), c.end(), name) - c.begin());
}

/// A quad [−1, 1]² at z = −2 facing the camera (it fills the 50 mm view), UVs 0..1 over it.
MeshBuilder quad(Color base, Color emission) {
    MeshBuilder m;
    const uint32_t mat = m.add_material(base, emission);
    m.add_instance(m.add_quad_z(-1, 1, -1, 1, -2, mat));
    return m;
}
void add_quad_uvs(SceneArrays& a) {
    // Corners (x0,y0) (x1,y0) (x1,y1) | (x0,y0) (x1,y1) (x0,y1) as add_quad_z orders them.
    const float uv[12] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    a.set("uvs", ElemType::F32, {2, 3, 2}, uv);
}

/// Program: image (2 × 1: left `l`, right `r`, closest) at the coordinate `kind`.
uint32_t two_tone(ProgramBuilder& b, Color l, Color r, CoordKind kind, uint32_t* reg) {
    const uint32_t tex = b.image(2, 1, {l, r});
    const uint32_t co = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(kind)});
    *reg = b.op(ShaderOpCode::Image, co, 0, 0,
                {tex, uint32_t(TexInterpolation::Closest), uint32_t(TexExtension::Extend), 0});
    return b.end_program();
}

/// Mean colour of the pixels whose centre is left (x < w/2 − 1) or right (x > w/2) of the middle.
Color half_mean(const RenderResult& r, bool left) {
    Color sum(0.f);
    int n = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            if (left ? x >= r.width / 2 - 1 : x <= r.width / 2) continue;
            const float* p = &r.rgba[4 * (size_t(y) * r.width + x)];
            sum += Color(p[0], p[1], p[2]);
            ++n;
        }
    return sum / float(n);
}

TEST(TexturedMaterial, EmissionTextureThroughUvs) {
    MeshBuilder m = quad(Color(0.f), Color(0.f));
    SceneArrays a = m.arrays();
    add_quad_uvs(a);
    ProgramBuilder b;
    uint32_t reg;
    const uint32_t p = two_tone(b, Color(1.f, 0.f, 0.f), Color(0.f, 0.5f, 0.f), CoordKind::Uv, &reg);
    b.bind(InputTarget::Emission, 0, 0, 3, p, reg);
    b.add_to(a);
    const RenderResult r = render(std::move(a), basic_params(16, 12, 4, 0));
    // Directly seen emission has no noise: each half shows its texel exactly.
    const Color l = half_mean(r, true), rr = half_mean(r, false);
    EXPECT_NEAR(l.x, 1.f, 1e-5f);
    EXPECT_NEAR(l.y, 0.f, 1e-5f);
    EXPECT_NEAR(rr.x, 0.f, 1e-5f);
    EXPECT_NEAR(rr.y, 0.5f, 1e-5f);
}

TEST(TexturedMaterial, GeneratedCoordinatesFollowTheObjectNotTheWorld) {
    // The quad is built at z = 0 and moved by its instance transform; its texture space is the unit box, so
    // Generated x = (x_object + 1)/2 splits the quad in the middle whatever the transform.
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(0.f), Color(0.f));
    const float xf[16] = {1, 0, 0, 0.f, 0, 1, 0, 0, 0, 0, 1, -2, 0, 0, 0, 1};
    m.add_instance(m.add_quad_z(-1, 1, -1, 1, 0, mat), xf);
    SceneArrays a = m.arrays();
    const float texspace[6] = {0, 0, 0, 1, 1, 1};
    a.set("mesh_texspace", ElemType::F32, {1, 6}, texspace);
    ProgramBuilder b;
    uint32_t reg;
    const uint32_t p = two_tone(b, Color(0.f, 0.f, 1.f), Color(1.f), CoordKind::Generated, &reg);
    b.bind(InputTarget::Emission, 0, 0, 3, p, reg);
    b.add_to(a);
    const RenderResult r = render(std::move(a), basic_params(16, 12, 4, 0));
    EXPECT_NEAR(half_mean(r, true).z, 1.f, 1e-5f);
    EXPECT_NEAR(half_mean(r, true).x, 0.f, 1e-5f);
    EXPECT_NEAR(half_mean(r, false).x, 1.f, 1e-5f);
}

TEST(TexturedMaterial, WithoutUvsTheCoordinateIsZero) {
    MeshBuilder m = quad(Color(0.f), Color(0.f));
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    uint32_t reg;
    const uint32_t p = two_tone(b, Color(0.25f), Color(1.f), CoordKind::Uv, &reg);
    b.bind(InputTarget::Emission, 0, 0, 3, p, reg);
    b.add_to(a);
    const RenderResult r = render(std::move(a), basic_params(8, 6, 2, 0));
    EXPECT_NEAR(r.mean_rgb, 0.25, 1e-5);  // UV (0, 0) everywhere: the left texel
}

RenderResult textured_diffuse_furnace(bool flat_normal_map) {
    MeshBuilder m = quad(Color(1.f), Color(0.f));
    m.add_closure(0, "DIFFUSE", {{"color_r", 0.5f}, {"color_g", 0.5f}, {"color_b", 0.5f}});
    m.world_color = {1.f, 1.f, 1.f};
    SceneArrays a = m.arrays();
    add_quad_uvs(a);
    // Tangent +X (the UV u direction), sign +1, at every corner.
    const std::vector<float> tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    a.set("tangents", ElemType::F32, {2, 3, 4}, tangents.data());
    ProgramBuilder b;
    uint32_t reg;
    const uint32_t p = two_tone(b, Color(0.2f), Color(0.8f), CoordKind::Uv, &reg);
    if (flat_normal_map) {
        const uint32_t n = b.op(ShaderOpCode::NormalMap, b.constant(Vec3(0.5f, 0.5f, 1.f)), b.constant(Vec3(1.f)), 0,
                                {uint32_t(NormalMapSpace::Tangent)});
        b.program_start.pop_back();  // extend program p
        b.program_start.push_back(uint32_t(b.ops.size()));
        b.bind(InputTarget::Normal, 0, 0, 3, p, n);
    }
    b.bind(InputTarget::Closure, 0, column("color_r"), 3, p, reg);
    b.add_to(a);
    return render(std::move(a), basic_params(16, 12, 256, 4));
}

/// Mean and standard error over one half, from the per-pixel noise estimates.
std::pair<double, double> half_stats(const RenderResult& r, bool left) {
    double sum = 0.0, var = 0.0;
    int n = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            if (left ? x >= r.width / 2 - 1 : x <= r.width / 2) continue;
            const size_t i = size_t(y) * r.width + x;
            sum += (r.rgba[4 * i] + r.rgba[4 * i + 1] + r.rgba[4 * i + 2]) / 3.0;
            var += double(r.noise[i]) * r.noise[i];
            ++n;
        }
    return {sum / n, std::sqrt(var) / n};
}

TEST(TexturedMaterial, TexturedDiffuseInAWhiteFurnaceShowsItsAlbedo) {
    // A lone diffuse plane under uniform radiance 1 reflects exactly its albedo: 0.2 left, 0.8 right.
    const RenderResult r = textured_diffuse_furnace(false);
    const auto [l, sl] = half_stats(r, true);
    const auto [rr, sr] = half_stats(r, false);
    EXPECT_NEAR(l, 0.2, 4.0 * sl + 1e-4);
    EXPECT_NEAR(rr, 0.8, 4.0 * sr + 1e-4);
}

TEST(TexturedMaterial, FlatNormalMapChangesNothing) {
    const RenderResult a = textured_diffuse_furnace(false), b = textured_diffuse_furnace(true);
    // Same sample sequences, and the flat map returns the same normal up to rounding: images agree to far
    // below the noise.
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    double max_diff = 0.0;
    for (size_t i = 0; i < a.rgba.size(); ++i) max_diff = std::fmax(max_diff, std::fabs(a.rgba[i] - b.rgba[i]));
    EXPECT_LT(max_diff, 1e-4);
}

TEST(TexturedMaterial, ConstantProgramsAreFoldedIntoTheFastPath) {
    MeshBuilder m = quad(Color(1.f), Color(0.f));
    m.add_closure(0, "DIFFUSE", {{"color_r", 0.9f}, {"color_g", 0.9f}, {"color_b", 0.9f}});
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    // colour = 0.25 · (0.4, 0.8, 1.2) computed by a Math node; emission = constant (1, 2, 3).
    const uint32_t c = b.op(ShaderOpCode::Math, b.constant(Vec3(0.4f, 0.8f, 1.2f)), b.constant(Vec3(0.25f)), 0,
                            {uint32_t(MathOp::Multiply), 0});
    const uint32_t e = b.constant(Vec3(1.f, 2.f, 3.f));
    const uint32_t p = b.end_program();
    b.bind(InputTarget::Closure, 0, column("color_r"), 3, p, c);
    b.bind(InputTarget::Emission, 0, 0, 3, p, e);
    b.add_to(a);
    auto materials = load_materials(a);
    const auto lib = ShaderLibrary::load(a);
    int32_t wp, wr;
    const auto inputs = load_material_inputs(a, *lib, materials, &wp, &wr);
    EXPECT_TRUE(inputs.empty());
    EXPECT_EQ(materials[0].inputs, -1);
    EXPECT_NEAR(materials[0].front[0].weight.y, 0.2f, 1e-6f);
    EXPECT_NEAR(materials[0].emission.z, 3.f, 1e-6f);
    EXPECT_EQ(wp, -1);
}

TEST(TexturedMaterial, BadBindingsNameTheBinding) {
    MeshBuilder m = quad(Color(1.f), Color(0.f));
    m.add_closure(0, "DIFFUSE", {});
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    const uint32_t k = b.constant(Vec3(1.f));
    const uint32_t p = b.end_program();
    b.bind(InputTarget::Closure, 0, column("color_r") + 1, 3, p, k + 5);  // register past the program
    b.add_to(a);
    auto materials = load_materials(a);
    const auto lib = ShaderLibrary::load(a);
    int32_t wp, wr;
    try {
        load_material_inputs(a, *lib, materials, &wp, &wr);
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("input_bindings[0]"), std::string::npos) << e.what();
    }
}

/// Mean alpha of the pixels clearly left or right of the middle.
float half_alpha(const RenderResult& r, bool left) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            if (left ? x >= r.width / 2 - 1 : x <= r.width / 2) continue;
            sum += r.rgba[4 * (size_t(y) * r.width + x) + 3];
            ++n;
        }
    return float(sum / n);
}

TEST(TexturedMaterial, TexturedHoldoutWeightIsEvaluatedPerHit) {
    // A Diffuse quad whose Holdout weight is a texture (a Mix Shader factor from an Image Texture, as the add-on
    // compiles it): 0.25 on the left half, 1 on the right. Cycles takes the weight out of alpha where the camera
    // sees the surface: alpha 0.75 left, 0 right (a full holdout). Exact: every sample of a pixel sees one texel.
    MeshBuilder m = quad(Color(0.5f), Color(0.f));
    m.add_closure(0, "DIFFUSE", {{"color_r", 0.5f}, {"color_g", 0.5f}, {"color_b", 0.5f}});
    SceneArrays a = m.arrays();
    add_quad_uvs(a);
    const float placeholder = 0.f;
    a.set("material_holdout", ElemType::F32, {1}, &placeholder);
    ProgramBuilder b;
    uint32_t reg;
    const uint32_t p = two_tone(b, Color(0.25f), Color(1.f), CoordKind::Uv, &reg);
    b.bind(InputTarget::Holdout, 0, 0, 3, p, reg);
    b.add_to(a);
    const RenderResult r = render(std::move(a), basic_params(16, 12, 4, 1));
    EXPECT_NEAR(half_alpha(r, true), 0.75f, 1e-5f);
    EXPECT_NEAR(half_alpha(r, false), 0.f, 1e-6f);
    EXPECT_NEAR(half_mean(r, false).x, 0.f, 1e-6f);  // a full holdout ends the path: no radiance
}

TEST(TexturedMaterial, ConstantHoldoutBindingIsFolded) {
    // A HOLDOUT binding that does not vary is folded into the material's weight at load: alpha 1 − 0.4.
    MeshBuilder m = quad(Color(0.5f), Color(0.f));
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    const uint32_t reg = b.constant(Vec3(0.2f, 0.4f, 0.6f));  // mean 0.4
    const uint32_t p = b.end_program();
    b.bind(InputTarget::Holdout, 0, 0, 3, p, reg);
    b.add_to(a);
    const RenderResult r = render(std::move(a), basic_params(8, 6, 2, 0));
    EXPECT_NEAR(half_alpha(r, true), 0.6f, 1e-5f);
    EXPECT_NEAR(half_alpha(r, false), 0.6f, 1e-5f);
}

}  // namespace
}  // namespace candela::test
