// Materials from the scene arrays: the fallback diffuse colour, the closure table (Cycles shader nodes with
// their weights), front/back faces of dielectrics, clear errors; and end-to-end white furnaces through the
// path tracer (docs/verification.md §2.7: a convex object under a uniform world of radiance 1 vanishes when
// its BSDF conserves energy).
#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/material.h"
#include "core/error.h"
#include "core/math.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

std::vector<Material> load(const MeshBuilder& b) {
    SceneArrays a = b.arrays();
    return load_materials(a);
}

MeshBuilder one_quad() {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -2, b.add_material(Color(0.2f, 0.4f, 0.6f), Color(0.f))));
    return b;
}

TEST(MaterialLoading, WithoutClosuresTheBaseColourIsALambert) {
    const auto m = load(one_quad());
    const Bsdf& b = m[0].bsdf();
    ASSERT_EQ(b.size(), 1);
    EXPECT_TRUE(std::holds_alternative<LambertBsdf>(b[0].lobe));
    EXPECT_NEAR(bsdf_f(b, Vec3(0, 0, 1), normalize(Vec3(0.3f, 0.f, 1.f))).y, 0.4f * k_inv_pi, 1e-7f);
}

TEST(MaterialLoading, ClosuresReplaceTheBaseColourWithTheirWeights) {
    MeshBuilder b = one_quad();
    // Mix Shader at fac 0.25 of Diffuse (white) and Glossy: the add-on sends weights 0.75 and 0.25.
    b.add_closure(0, "DIFFUSE",
                  {{"weight_r", 0.75f},
                   {"weight_g", 0.75f},
                   {"weight_b", 0.75f},
                   {"color_r", 1.f},
                   {"color_g", 1.f},
                   {"color_b", 1.f}});
    b.add_closure(0, "GLOSSY",
                  {{"weight_r", 0.25f},
                   {"weight_g", 0.25f},
                   {"weight_b", 0.25f},
                   {"color_r", 1.f},
                   {"color_g", 1.f},
                   {"color_b", 1.f},
                   {"roughness", 0.5f}});
    const auto m = load(b);
    ASSERT_EQ(m[0].bsdf().size(), 2);
    EXPECT_FLOAT_EQ(m[0].bsdf()[0].weight.x, 0.75f);
    EXPECT_FLOAT_EQ(m[0].bsdf()[1].weight.x, 0.25f);
}

TEST(MaterialLoading, GlassSeesTheInverseIorFromBehind) {
    MeshBuilder b = one_quad();
    b.add_closure(0, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    const auto m = load(b);
    const auto& front = std::get<MicrofacetDielectric>(m[0].bsdf(false)[0].lobe);
    const auto& back = std::get<MicrofacetDielectric>(m[0].bsdf(true)[0].lobe);
    EXPECT_FLOAT_EQ(front.eta, 1.5f);
    EXPECT_FLOAT_EQ(back.eta, 1.f / 1.5f);
}

TEST(MaterialLoading, BadClosuresNameTheMaterial) {
    MeshBuilder b = one_quad();
    b.add_closure(0, "GLASS", {{"ior", 0.f}});
    try {
        load(b);
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("material 0"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("IOR"), std::string::npos) << e.what();
    }
}

/// A sphere of radius 1 at distance 4 filling the middle of the frame, under a white world (radiance 1).
RenderResult furnace(const std::string& closure, const std::vector<std::pair<std::string, float>>& values,
                     int samples = 64) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(1.f), Color(0.f));
    if (!closure.empty()) b.add_closure(m, closure, values);
    const float xf[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -4, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(1.f, 96, 48, m), xf);
    b.world_color = {1.f, 1.f, 1.f};
    Params p = basic_params(12, 12, samples, 64);
    p.set("lens", 120.0);  // the sphere covers the whole frame
    p.set("rr_start_bounce", int64_t(64));
    return render(b.arrays(), p);
}

void expect_vanishes(const RenderResult& r, const char* what) {
    // Every pixel sees the sphere; with energy conserved it shows exactly the world: 1 (up to the truncation
    // at 64 bounces, which is far below the noise).
    EXPECT_NEAR(r.mean_rgb, 1.0, 4.0 * r.standard_error + 2e-3) << what;
}

TEST(WhiteFurnace, WhiteLambertSphereVanishes) { expect_vanishes(furnace("", {}), "Lambert albedo 1"); }

TEST(WhiteFurnace, SmoothGlassSphereVanishes) {
    expect_vanishes(furnace("GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}}),
                    "smooth glass");
}

TEST(WhiteFurnace, RoughGlassSphereIsNearlyInvisible) {
    // Walter's rough dielectric loses a little energy to single scattering at α = 0.01 (roughness 0.1).
    const RenderResult r =
        furnace("GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}, {"roughness", 0.1f}});
    EXPECT_NEAR(r.mean_rgb, 1.0, 4.0 * r.standard_error + 0.02);
    EXPECT_LE(r.mean_rgb, 1.0 + 4.0 * r.standard_error);
}

TEST(WhiteFurnace, GreyDiffuseSphereShowsItsAlbedo) {
    const RenderResult r = furnace("DIFFUSE", {{"color_r", 0.5f}, {"color_g", 0.5f}, {"color_b", 0.5f}});
    EXPECT_NEAR(r.mean_rgb, 0.5, 4.0 * r.standard_error + 2e-3);
}

}  // namespace
}  // namespace candela::test
