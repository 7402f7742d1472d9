// The environment light (lights/environment_light.h): its 2-D distribution, a χ² test of its direction
// sampling against its pdf, pdf consistency, Blender's direction → texel mapping, and furnace-style renders:
// a constant environment image equals the constant world colour, and MIS, light-only and BSDF-only estimates
// of an environment-lit plane agree.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <algorithm>
#include "chi2.h"
#include "core/math.h"
#include "core/rng.h"
#include "lights/environment_light.h"
#include "sampling/distribution_2d.h"
#include "scene/scene.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"
#include "texture/node_math.h"

namespace candela::test {
namespace {

TEST(Distribution2D, SampledPdfMatchesEvaluatedPdfAndIntegratesToOne) {
    const size_t nu = 7, nv = 5;
    std::vector<float> w(nu * nv);
    Pcg32 rng(3, 1);
    for (float& x : w) x = rng.next_float() < 0.2f ? 0.f : rng.next_float();
    const Distribution2D d(w, nu, nv);
    double integral = 0.0;
    for (size_t j = 0; j < nv; ++j)
        for (size_t i = 0; i < nu; ++i) integral += d.pdf({(i + 0.5f) / nu, (j + 0.5f) / nv}) / double(nu * nv);
    EXPECT_NEAR(integral, 1.0, 1e-5);
    for (int k = 0; k < 1000; ++k) {
        float pdf = 0.f;
        const Vec2 p = d.sample({rng.next_float(), rng.next_float()}, &pdf);
        ASSERT_GT(pdf, 0.f);
        EXPECT_NEAR(d.pdf(p), pdf, 1e-5f * pdf);
        // Zero-weight cells are never drawn.
        EXPECT_GT(w[size_t(p.y * nv) * nu + size_t(p.x * nu)], 0.f);
    }
}

/// A 32×16 environment with a bright spot, a gradient and a dark band, read through an equirectangular
/// Environment Texture node (COORD GENERATED = the direction), strength 2.
struct TestEnvironment {
    ProgramBuilder b;
    uint32_t program = 0, reg = 0;
    std::vector<Color> texels;
    TestEnvironment() {
        const uint32_t w = 32, h = 16;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                Color c(0.1f + 0.8f * float(x) / w, 0.3f, 0.2f + 0.5f * float(y) / h);
                if (y == 4) c = Color(0.f);                           // a black band
                if (x == 20 && y == 11) c = Color(60.f, 50.f, 40.f);  // a small sun
                texels.push_back(c);
            }
        const uint32_t tex = b.image(w, h, texels);
        const uint32_t dir = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
        const uint32_t img = b.op(ShaderOpCode::Image, dir, 0, 0,
                                  {tex, uint32_t(TexInterpolation::Linear), uint32_t(TexExtension::Repeat),
                                   uint32_t(ImageProjection::Equirectangular)});
        reg = b.op(ShaderOpCode::Math, img, b.constant(Vec3(2.f)), 0, {uint32_t(MathOp::Multiply), 0});
        program = b.end_program();
    }
};

TEST(EnvironmentLight, RadianceIsTheImageAtBlendersMapping) {
    TestEnvironment e;
    const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
    EXPECT_EQ(env.width(), 32u);
    EXPECT_EQ(env.height(), 16u);
    // The centre of texel (x, y) lies at u = (x + ½)/32, v = (y + ½)/16; there bilinear filtering is exact.
    for (auto [x, y] : {std::pair<uint32_t, uint32_t>{20, 11}, {3, 2}, {31, 15}, {10, 4}}) {
        const Vec3 d = equirectangular_to_direction((x + 0.5f) / 32.f, (y + 0.5f) / 16.f);
        const Color want = e.texels[y * 32 + x] * 2.f;
        const Color got = env.Le(d);
        EXPECT_NEAR(got.x, want.x, 1e-3f * (1.f + want.x)) << x << "," << y;
        EXPECT_NEAR(got.z, want.z, 1e-3f * (1.f + want.z)) << x << "," << y;
    }
}

TEST(EnvironmentLight, SampledPdfEqualsEvaluatedPdf) {
    TestEnvironment e;
    const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
    Pcg32 rng(7, 2);
    for (int k = 0; k < 2000; ++k) {
        const LightSample s = env.sample({rng.next_float(), rng.next_float()});
        ASSERT_GT(s.pdf, 0.f);
        ASSERT_NEAR(length(s.wi), 1.f, 1e-5f);
        EXPECT_NEAR(env.pdf(s.wi), s.pdf, 2e-3f * s.pdf);
        const Color le = env.Le(s.wi);
        EXPECT_NEAR(s.Li.x, le.x, 1e-6f * (1.f + le.x));
    }
}

TEST(EnvironmentLight, Chi2SamplingMatchesPdf) {
    // χ² over the equirectangular (u, v) square rather than chi2.h's (cos θ, φ) cells: the density in
    // solid angle has the 1/sin θ pole and a step at every texel, which defeats that harness's Simpson
    // quadrature. Cells are the texels split 2 × 2; the expected mass is ∫ pdf(ω(u, v))·2π² sin θ du dv by the
    // midpoint rule on 4 × 4 points per cell: the map of this Linear image is bilinear times sin θ on each cell,
    // which the rule integrates to ~10⁻⁵ relative (below the counting noise). Both maps: the plain one and the
    // MIS-compensated one (each sampled and evaluated with its own pdf).
    TestEnvironment e;
    const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
    for (bool compensated : {false, true}) {
        const int nu = 64, nv = 32, sub = 4;
        const uint64_t n = 1000000;
        std::vector<double> expected(size_t(nu) * nv, 0.0), observed(expected.size(), 0.0);
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                double mass = 0.0;
                for (int b = 0; b < sub; ++b)
                    for (int a = 0; a < sub; ++a) {
                        const float u = (i + (a + 0.5f) / sub) / nu, v = (j + (b + 0.5f) / sub) / nv;
                        const double jac = 2.0 * M_PI * M_PI * std::sin(M_PI * (1.0 - v));
                        mass += env.pdf(equirectangular_to_direction(u, v), compensated) * jac /
                                (double(sub) * sub * nu * nv);
                    }
                expected[size_t(j) * nu + i] = mass * double(n);
            }
        Pcg32 rng(11, 5);
        uint64_t invalid = 0;
        for (uint64_t k = 0; k < n; ++k) {
            const Vec2 uu{rng.next_float(), rng.next_float()};
            const LightSample s = env.sample(uu, compensated);
            // The compensated map is 0 on part of the sphere: a uniform number exactly on the edge of such a region
            // (u = 0 here, probability 2⁻²⁴ per draw) gives a point of density 0, returned as an invalid sample
            // (no contribution: a null set). Allowed at 10⁻⁵ of the draws, counted as not drawn.
            if (!(s.pdf > 0.f)) {
                ++invalid;
                continue;
            }
            Vec2 uv = direction_to_equirectangular(s.wi);
            uv.x -= std::floor(uv.x);
            const int i = std::min(int(uv.x * nu), nu - 1), j = std::min(int(uv.y * nv), nv - 1);
            observed[size_t(j) * nu + i] += 1.0;
        }
        // Pool cells expected below 5 (Cochran's rule) into one.
        double chi2 = 0.0, pool_e = 0.0, pool_o = 0.0, total = 0.0;
        int dof = -1;
        for (size_t c = 0; c < expected.size(); ++c) {
            total += expected[c];
            if (expected[c] < 5.0) {
                pool_e += expected[c];
                pool_o += observed[c];
                continue;
            }
            chi2 += (observed[c] - expected[c]) * (observed[c] - expected[c]) / expected[c];
            ++dof;
        }
        if (pool_e > 0.0) {
            chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            ++dof;
        }
        const double p = chi2_survival(chi2, dof);
        std::printf("chi2 environment (u, v), %s map: statistic %.1f, dof %d, p = %.4f, ∫pdf = %.6f\n",
                    compensated ? "compensated" : "plain", chi2, dof, p, total / n);
        EXPECT_GT(p, 0.005) << compensated;                        // two maps at a family-wise 1 %
        EXPECT_NEAR(total / double(n), 1.0, 1e-4) << compensated;  // the pdf integrates to one over the sphere
    }
}

TEST(EnvironmentLight, MeanRadianceIsTheSolidAngleAverage) {
    ProgramBuilder b;
    // Upper hemisphere 1, lower 0: the sphere average is ½ (cells straddle no boundary: 16 rows).
    std::vector<Color> t(16 * 8, Color(0.f));
    for (size_t i = 16 * 4; i < t.size(); ++i) t[i] = Color(1.f);
    const uint32_t tex = b.image(16, 8, t);
    const uint32_t dir = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
    const uint32_t img =
        b.op(ShaderOpCode::Image, dir, 0, 0,
             {tex, uint32_t(TexInterpolation::Closest), 0, uint32_t(ImageProjection::Equirectangular)});
    const uint32_t p = b.end_program();
    const EnvironmentMap env(b.library(), p, img, 1);
    EXPECT_NEAR(env.mean_radiance().x, 0.5f, 1e-4f);
}

// ---- renders ------------------------------------------------------------------------------------------------

/// A sphere of radius 1 at distance 4 filling the frame (as the material furnace tests), diffuse colour ρ.
MeshBuilder sphere_scene(float rho) {
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(rho), Color(0.f));
    const float xf[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -4, 0, 0, 0, 1};
    m.add_instance(m.add_sphere(1.f, 96, 48, mat), xf);
    return m;
}

/// World = a constant-colour environment image (equirectangular, bilinear) of colour c.
void constant_environment(ProgramBuilder& b, const Color& c) {
    const uint32_t tex = b.image(8, 4, std::vector<Color>(32, c));
    const uint32_t dir = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
    const uint32_t img = b.op(ShaderOpCode::Image, dir, 0, 0,
                              {tex, uint32_t(TexInterpolation::Linear), 0, uint32_t(ImageProjection::Equirectangular)});
    const uint32_t p = b.end_program();
    b.bind(InputTarget::World, 0, 0, 3, p, img);
}

Params sphere_params(int samples) {
    Params p = basic_params(12, 12, samples, 64);
    p.set("lens", 120.0);  // the sphere covers the whole frame
    p.set("rr_start_bounce", int64_t(64));
    return p;
}

TEST(EnvironmentFurnace, WhiteSphereVanishesInAConstantEnvironmentImage) {
    MeshBuilder m = sphere_scene(1.f);
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    constant_environment(b, Color(1.f));
    b.add_to(a);
    const RenderResult r = render(std::move(a), sphere_params(64));
    // Albedo 1 under radiance 1: every pixel is exactly 1 in expectation; 4σ of the estimated noise.
    EXPECT_NEAR(r.mean_rgb, 1.0, 4.0 * r.standard_error + 2e-3);
}

TEST(EnvironmentFurnace, ConstantImageEqualsTheConstantWorldColour) {
    const Color c(0.3f, 0.6f, 0.9f);
    MeshBuilder with_color = sphere_scene(0.5f);
    with_color.world_color = {c.x, c.y, c.z};
    const RenderResult ref = render(with_color.arrays(), sphere_params(64));
    MeshBuilder m = sphere_scene(0.5f);
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    constant_environment(b, c);
    b.add_to(a);
    const RenderResult env = render(std::move(a), sphere_params(64));
    // Both are ρ·mean(c) = 0.5·0.6 = 0.3 in expectation (a convex diffuse object in a uniform furnace).
    const double sigma = std::sqrt(ref.standard_error * ref.standard_error + env.standard_error * env.standard_error);
    EXPECT_NEAR(env.mean_rgb, ref.mean_rgb, 4.0 * sigma + 1e-3);
    EXPECT_NEAR(env.mean_rgb, 0.3, 4.0 * env.standard_error + 2e-3);
}

// A constant world colour is not light-sampled (LightSet::set_background): the light set stays empty, so no
// shadow ray is spent on it, and every estimator finds it through escaping rays with weight 1. A diffuse quad of
// albedo 0.8 facing up under a uniform sky of radiance 0.5, nothing above it: Lo = ρ·L = 0.4 exactly, for
// BSDF_ONLY, LIGHT_ONLY (weight 1 because light sampling cannot produce it) and MIS alike; 4σ of each render.
TEST(EnvironmentFurnace, ConstantWorldIsNotALightAndEveryEstimatorFindsIt) {
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(0.8f), Color(0.f));
    m.add_instance(m.add_quad_z(-10, 10, -10, 10, -2, mat));
    m.world_color = {0.5f, 0.5f, 0.5f};
    const PreparedScene scene(m.arrays(), basic_params(8, 8, 64, 0));
    EXPECT_TRUE(scene.scene().lights().empty());
    EXPECT_EQ(scene.scene().lights().world_light(), -1);
    EXPECT_FLOAT_EQ(scene.scene().lights().background().y, 0.5f);
    for (const char* mode : {"BSDF_ONLY", "LIGHT_ONLY", "MIS"}) {
        Params p;
        p.set("light_sampling", std::string(mode));
        const RenderResult r = scene.render(p);
        EXPECT_NEAR(r.mean_rgb, 0.4, 4.0 * r.standard_error + 1e-6) << mode << ", σ " << r.standard_error;
    }
}

TEST(EnvironmentFurnace, MisLightOnlyAndBsdfOnlyAgree) {
    // A diffuse quad facing the camera, lit by the test environment (sun, gradient, black band): the three
    // estimators have the same expectation; the tolerance is 4σ of the two renders' combined noise.
    auto scene = [] {
        MeshBuilder m;
        const uint32_t mat = m.add_material(Color(0.8f), Color(0.f));
        m.add_instance(m.add_quad_z(-1, 1, -1, 1, -2, mat));
        SceneArrays a = m.arrays();
        TestEnvironment e;
        e.b.bind(InputTarget::World, 0, 0, 3, e.program, e.reg);
        e.b.add_to(a);
        return a;
    };
    auto run = [&](const char* mode, int samples) {
        Params p = basic_params(8, 8, samples, 0);
        p.set("light_sampling", std::string(mode));
        return render(scene(), p);
    };
    const RenderResult mis = run("MIS", 256), light = run("LIGHT_ONLY", 256), bsdf = run("BSDF_ONLY", 2048);
    auto close = [](const RenderResult& a, const RenderResult& b, const char* what) {
        const double s = std::sqrt(a.standard_error * a.standard_error + b.standard_error * b.standard_error);
        EXPECT_NEAR(a.mean_rgb, b.mean_rgb, 4.0 * s) << what;
    };
    close(mis, light, "MIS vs light only");
    close(mis, bsdf, "MIS vs BSDF only");
    std::printf("environment plane: MIS %.4f ± %.4f, light %.4f ± %.4f, BSDF %.4f ± %.4f\n", mis.mean_rgb,
                mis.standard_error, light.mean_rgb, light.standard_error, bsdf.mean_rgb, bsdf.standard_error);
}

TEST(EnvironmentFurnace, EveryIntegratorAgreesUnderTheEnvironment) {
    // The plane of MisLightOnlyAndBsdfOnlyAgree, rendered by every unbiased integrator: PATH with MIS (next-event
    // estimation from the MIS-compensated map, which is 0 on the black band and the dim half of the gradient),
    // the path generators (their receivers' next-event estimation under MIS, the gathered one without), AUTO's,
    // BDPT and light tracing (the plain map, through light emission). Each against PATH LIGHT_ONLY (the plain map
    // alone) within 4σ of the two renders' combined noise: 8 comparisons at 6·10⁻⁵ each, family-wise 5·10⁻⁴.
    auto scene = [] {
        MeshBuilder m;
        const uint32_t mat = m.add_material(Color(0.8f), Color(0.f));
        m.add_instance(m.add_quad_z(-1, 1, -1, 1, -2, mat));
        SceneArrays a = m.arrays();
        TestEnvironment e;
        e.b.bind(InputTarget::World, 0, 0, 3, e.program, e.reg);
        e.b.add_to(a);
        return a;
    };
    auto run = [&](const char* integrator, const char* mode, int samples, bool generators_mis = false) {
        Params p = basic_params(8, 8, samples, 2);
        p.set("integrator", std::string(integrator));
        p.set("light_sampling", std::string(mode));
        if (generators_mis) p.set("generators_mis", true);
        return render(scene(), p);
    };
    const RenderResult reference = run("PATH", "LIGHT_ONLY", 512);
    struct Config {
        const char* integrator;
        int samples;
        bool generators_mis;
    };
    const Config configs[] = {{"PATH", 256, false},
                              {"AUTO", 256, false},
                              {"BDPT", 128, false},
                              {"LIGHT", 512, false},
                              {"SURFACE_SAMPLING", 128, false},
                              {"SOURCE_SHOOTING", 128, false},
                              {"RECEIVER_GATHERING", 128, false},
                              {"RECEIVER_GATHERING", 128, true}};
    for (const Config& c : configs) {
        const RenderResult r = run(c.integrator, "MIS", c.samples, c.generators_mis);
        const double s = std::hypot(r.standard_error, reference.standard_error);
        std::printf("environment plane, %s%s: %.4f ± %.4f (PATH LIGHT_ONLY %.4f ± %.4f)\n", c.integrator,
                    c.generators_mis ? " + MIS" : "", r.mean_rgb, r.standard_error, reference.mean_rgb,
                    reference.standard_error);
        EXPECT_GT(r.standard_error, 0.0) << c.integrator;
        EXPECT_NEAR(r.mean_rgb, reference.mean_rgb, 4.0 * s) << c.integrator << (c.generators_mis ? " + MIS" : "");
    }
}

}  // namespace
}  // namespace candela::test
