// Data passes (film/aov_film.h, integrators/camera_hit.h) against analytic scenes: a plane facing the camera at a
// known distance has exactly that Depth, its normal in the Normal pass, its material's albedo in the Albedo pass
// and its object's pass index in IndexOB; the background has Cycles' values (Depth 1e10, zeros elsewhere).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "bsdf/material_inputs.h"
#include "core/error.h"
#include "session/session.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr int W = 24, H = 16;

struct Passes {
    std::vector<float> depth, normal, albedo, index;
};

Passes render_passes(SceneArrays arrays, Params p) {
    Session s(std::move(arrays), std::move(p));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    Passes out;
    int ch = 0;
    out.depth = s.get_pass("Depth", &ch);
    EXPECT_EQ(ch, 1);
    out.normal = s.get_pass("Normal", &ch);
    EXPECT_EQ(ch, 3);
    out.albedo = s.get_pass("Albedo", &ch);
    EXPECT_EQ(ch, 3);
    out.index = s.get_pass("IndexOB", &ch);
    EXPECT_EQ(ch, 1);
    return out;
}

Params pass_params(int samples = 4) {
    Params p = basic_params(W, H, samples, 1);
    p.set("passes", std::string("Combined, Depth,Normal,Albedo,IndexOB"));
    return p;
}

TEST(Aov, PlaneFacingTheCameraHasItsDepthNormalAlbedoAndIndex) {
    // A plane 4 m in front of the camera covering the whole view, lit or not (the passes do not care).
    MeshBuilder b;
    b.add_instance(
        b.add_quad_z(-100.f, 100.f, -100.f, 100.f, -4.f, b.add_material(Color(0.25f, 0.5f, 0.75f), Color(0.f))));
    SceneArrays a = b.arrays();
    const uint32_t pass_index = 7;
    a.set("instance_pass_index", ElemType::U32, {1}, &pass_index);
    const Passes p = render_passes(std::move(a), pass_params());
    ASSERT_EQ(p.depth.size(), size_t(W * H));
    for (size_t i = 0; i < size_t(W * H); ++i) {
        EXPECT_NEAR(p.depth[i], 4.f, 4e-6f * 4.f) << i;  // z depth, not the distance along the ray
        EXPECT_NEAR(p.normal[3 * i], 0.f, 1e-6f);
        EXPECT_NEAR(p.normal[3 * i + 1], 0.f, 1e-6f);
        EXPECT_NEAR(p.normal[3 * i + 2], 1.f, 1e-6f);  // facing the camera, whatever the winding
        EXPECT_NEAR(p.albedo[3 * i], 0.25f, 1e-6f);    // Lambert: its albedo is its colour
        EXPECT_NEAR(p.albedo[3 * i + 1], 0.5f, 1e-6f);
        EXPECT_NEAR(p.albedo[3 * i + 2], 0.75f, 1e-6f);
        EXPECT_EQ(p.index[i], 7.f);
    }
}

uint32_t closure_column(const char* name) {
    const auto& c = closure_columns();
    return uint32_t(std::find(c.begin(), c.end(), name) - c.begin());
}

/// A quad [−1, 1]² at z = −2 filling the view, UVs 0..1 over it, with material 0 = `closure` whose colour
/// input (`column`) is a 2 × 1 image: `left` for u < ½, `right` beyond (closest texel).
SceneArrays two_tone_quad(const char* closure, const char* column, Color left, Color right,
                          std::vector<std::pair<std::string, float>> values = {}) {
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(0.9f), Color(0.f));  // base: unused once the material has closures
    m.add_instance(m.add_quad_z(-1, 1, -1, 1, -2, mat));
    for (const char* c : {"color_r", "color_g", "color_b"}) values.emplace_back(c, 0.5f);
    m.add_closure(mat, closure, values);
    SceneArrays a = m.arrays();
    const float uv[12] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};  // add_quad_z's corner order
    a.set("uvs", ElemType::F32, {2, 3, 2}, uv);
    ProgramBuilder b;
    const uint32_t tex = b.image(2, 1, {left, right});
    const uint32_t co = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Uv)});
    const uint32_t reg = b.op(ShaderOpCode::Image, co, 0, 0,
                              {tex, uint32_t(TexInterpolation::Closest), uint32_t(TexExtension::Extend), 0});
    const uint32_t p = b.end_program();
    b.bind(InputTarget::Closure, 0, closure_column(column), 3, p, reg);
    b.add_to(a);
    return a;
}

/// Per-pixel value of channel c of a 3-channel pass, averaged over the pixels clearly left or right of the middle.
float half_mean(const std::vector<float>& pass, int c, bool left) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (left ? x >= W / 2 - 1 : x <= W / 2) continue;
            sum += pass[3 * (size_t(y) * W + x) + c];
            ++n;
        }
    return float(sum / n);
}

TEST(Aov, AlbedoShowsTheTexturedDiffuseColour) {
    // Cycles' albedo of a Diffuse BSDF is its colour, here a texture: each half of the quad shows its texel
    // exactly (no noise: every sample of a pixel lands on one texel), not the closure's 0.5 placeholder.
    const Passes p = render_passes(
        two_tone_quad("DIFFUSE", "color_r", Color(0.1f, 0.2f, 0.3f), Color(0.9f, 0.6f, 0.4f)), pass_params());
    EXPECT_NEAR(half_mean(p.albedo, 0, true), 0.1f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 1, true), 0.2f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 2, true), 0.3f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 0, false), 0.9f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 1, false), 0.6f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 2, false), 0.4f, 1e-6f);
}

TEST(Aov, AlbedoShowsTheTexturedPrincipledBaseColour) {
    // Principled, metallic 0, specular 0, no sheen/clearcoat/transmission: one diffuse closure of weight base
    // colour, so Cycles' albedo is the textured base colour.
    const Passes p =
        render_passes(two_tone_quad("PRINCIPLED", "color_r", Color(0.25f, 0.5f, 0.75f), Color(0.8f, 0.1f, 0.2f),
                                    {{"specular", 0.f}, {"roughness", 0.5f}, {"ior", 1.45f}}),
                      pass_params());
    EXPECT_NEAR(half_mean(p.albedo, 0, true), 0.25f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 2, true), 0.75f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 0, false), 0.8f, 1e-6f);
    EXPECT_NEAR(half_mean(p.albedo, 1, false), 0.1f, 1e-6f);
}

TEST(Aov, AlbedoLeavesOutTransparentClosures) {
    // Mix of Diffuse (colour 0.6, weight 0.3) and Transparent (weight 0.7): Cycles' albedo is the diffuse
    // closure's colour weight 0.18 only.
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(0.9f), Color(0.f));
    m.add_instance(m.add_quad_z(-1, 1, -1, 1, -2, mat));
    m.add_closure(mat, "DIFFUSE",
                  {{"weight_r", 0.3f},
                   {"weight_g", 0.3f},
                   {"weight_b", 0.3f},
                   {"color_r", 0.6f},
                   {"color_g", 0.6f},
                   {"color_b", 0.6f}});
    m.add_closure(mat, "TRANSPARENT",
                  {{"weight_r", 0.7f},
                   {"weight_g", 0.7f},
                   {"weight_b", 0.7f},
                   {"color_r", 1.f},
                   {"color_g", 1.f},
                   {"color_b", 1.f}});
    const Passes p = render_passes(m.arrays(), pass_params());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(half_mean(p.albedo, c, true), 0.18f, 1e-6f);
}

TEST(Aov, NormalPassShowsTheNormalMappedShadingNormal) {
    // A World-space Normal Map of the constant colour (0.64, 0.5, 0.98) is the unit normal (0.28, 0, 0.96) at every
    // hit (camera-world = world here: the camera sits at the origin), tilted little enough that the node's
    // silhouette guard (ensure_valid_reflection) leaves it alone everywhere in view. Cycles writes that shading
    // normal, not the quad's geometric (0, 0, 1). Exact up to float rounding: every sample sees the same normal.
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(0.5f), Color(0.f));
    m.add_instance(m.add_quad_z(-1, 1, -1, 1, -2, mat));
    m.add_closure(mat, "DIFFUSE", {{"color_r", 0.5f}, {"color_g", 0.5f}, {"color_b", 0.5f}});
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    const uint32_t n = b.op(ShaderOpCode::NormalMap, b.constant(Vec3(0.64f, 0.5f, 0.98f)), b.constant(Vec3(1.f)), 0,
                            {uint32_t(NormalMapSpace::World)});
    const uint32_t prog = b.end_program();
    b.bind(InputTarget::Normal, 0, 0, 3, prog, n);
    b.add_to(a);
    const Passes p = render_passes(std::move(a), pass_params());
    for (bool left : {true, false}) {
        EXPECT_NEAR(half_mean(p.normal, 0, left), 0.28f, 1e-5f);
        EXPECT_NEAR(half_mean(p.normal, 1, left), 0.f, 1e-5f);
        EXPECT_NEAR(half_mean(p.normal, 2, left), 0.96f, 1e-5f);
    }
}

TEST(Aov, TiltedPlaneDepthIsTheViewAxisDistanceAtSampleZero) {
    // The plane z = −4 − 0.5·x (camera space) rotated about y: its unit normal is (0.5, 0, 1)/|…| toward the camera.
    // Depth comes from each pixel's sample 0, which lies somewhere in the pixel (box filter, width 1), so it lies
    // between the plane's depths over the pixel's footprint.
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const float xf[16] = {1, 0, 0, 0, 0, 1, 0, 0, -0.5f, 0, 1, -4.f, 0, 0, 0, 1};  // shear: z' = z − 0.5x − 4
    // A shear keeps the plane flat; the quad spans x in [−3, 3] (inside the 36 mm × 50 mm view at 4 m).
    b.add_instance(b.add_quad_z(-3.f, 3.f, -3.f, 3.f, 0.f, m), xf);
    const Passes p = render_passes(b.arrays(), pass_params(1));
    const float tan_x = 18.f / 50.f;  // horizontal fit: the frame spans ±tan_x
    const Vec3 n = normalize(Vec3(0.5f, 0.f, 1.f));
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + x;
            // Along direction (t, ·, −1) the plane z = −4 − 0.5·X with X = t·d is met at depth d = 4/(1 − 0.5·t).
            const float t0 = (2.f * x / W - 1.f) * tan_x, t1 = (2.f * (x + 1) / W - 1.f) * tan_x;
            const float d0 = 4.f / (1.f - 0.5f * t0), d1 = 4.f / (1.f - 0.5f * t1);
            EXPECT_GE(p.depth[i], std::min(d0, d1) * (1.f - 1e-5f)) << x << "," << y;
            EXPECT_LE(p.depth[i], std::max(d0, d1) * (1.f + 1e-5f)) << x << "," << y;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.normal[3 * i + c], n[c], 1e-5f);
        }
}

TEST(Aov, BackgroundHasCyclesValues) {
    MeshBuilder b;  // a small quad off to the side leaves most of the frame empty
    b.add_instance(b.add_quad_z(50.f, 51.f, 0.f, 1.f, -4.f, b.add_material(Color(0.5f), Color(0.f))));
    const Passes p = render_passes(b.arrays(), pass_params());
    for (size_t i = 0; i < size_t(W * H); ++i) {
        EXPECT_EQ(p.depth[i], 1e10f);
        EXPECT_EQ(p.index[i], 0.f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(p.normal[3 * i + c], 0.f);
            EXPECT_EQ(p.albedo[3 * i + c], 0.f);
        }
    }
}

TEST(Aov, PassesAreOnlyWrittenWhenAskedFor) {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1.f, 1.f, -1.f, 1.f, -4.f, b.add_material(Color(0.5f), Color(0.f))));
    Params p = basic_params(W, H, 1, 1);
    p.set("passes", std::string("Depth"));
    Session s(b.arrays(), std::move(p));
    s.start();
    s.join();
    int ch = 0;
    EXPECT_FALSE(s.get_pass("Depth", &ch).empty());
    EXPECT_TRUE(s.get_pass("Normal", &ch).empty());
    EXPECT_EQ(ch, 0);
    Params bad = basic_params(W, H, 1, 1);
    bad.set("passes", std::string("Depth,Nromal"));
    EXPECT_THROW(Session(b.arrays(), std::move(bad)), InvalidParameter);
}

TEST(Aov, PassesDoNotDependOnTheThreadCount) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_sphere(1.f, 24, 12, m),
                   std::array<float, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -4, 0, 0, 0, 1}.data());
    Params p1 = pass_params(8), p2 = pass_params(8);
    p1.set("threads", int64_t(1));
    p2.set("threads", int64_t(2));
    p1.set("tile_size", int64_t(5));
    const Passes a = render_passes(b.arrays(), std::move(p1)), c = render_passes(b.arrays(), std::move(p2));
    EXPECT_EQ(a.depth, c.depth);
    EXPECT_EQ(a.normal, c.normal);
    EXPECT_EQ(a.albedo, c.albedo);
}

}  // namespace
}  // namespace candela::test
