// A textured emitter (an Image Texture driving the Emission colour of a mesh) is a light: next-event estimation
// samples its triangles and evaluates the radiance at each sampled point through the material's shader program
// (lights/emission_source.h), so light sampling, BSDF sampling and MIS converge to the same image.
//
// Scene: a grey diffuse floor (albedo 0.5, z = −2, filling the view) lit only by a 1 × 1 quad at z = −1.2 off to
// the side (out of the camera's view), emitting through a 4 × 1 image of grey levels 0, 2, 6, 16 across its u
// (closest texel: a step function with a black quarter, far from the average the light selection uses). Direct
// light only (max_bounces 0), so every strategy estimates the same integral.
//
// Agreement: each strategy is rendered with K = 8 seeds (RANDOM sampler: independent renders). Per strategy the
// K image means m_k give a mean m̄ and its standard error s/√K (s the across-seed standard deviation, K − 1 = 7
// degrees of freedom); two strategies agree if |m̄_a − m̄_b| ≤ 5·√(se_a² + se_b²). With ~14 degrees of freedom
// a correct renderer exceeds 5 with probability ~2·10⁻⁴ per pair, while a bias of the size of the texture's
// variation (treating the emitter as its average, ±100 % at a point) is tens of standard errors.
//
// Light sampling is used: with the small emitter LIGHT_ONLY's per-pixel variance is far below BSDF_ONLY's
// (measured ratios 0.05 with area sampling, 0.1 with spherical triangles). The test requires the mean over pixels of the across-seed pixel variance of
// LIGHT_ONLY to be below half of BSDF_ONLY's; when the emitter is not a light, LIGHT_ONLY falls back to the BSDF
// hits (weight 1) and the two renders are identical (ratio exactly 1).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bsdf/material_inputs.h"
#include "scene/scene.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 8, W = 32, H = 24;

SceneArrays textured_emitter_scene() {
    MeshBuilder m;
    const uint32_t floor = m.add_material(Color(0.5f), Color(0.f));
    const uint32_t lamp = m.add_material(Color(0.f), Color(0.f));  // no closures: black base, emission bound below
    m.add_instance(m.add_quad_z(-2.f, 2.f, -2.f, 2.f, -2.f, floor));
    m.add_instance(m.add_quad_z(0.5f, 1.5f, -0.5f, 0.5f, -1.2f, lamp));
    SceneArrays a = m.arrays();
    // UVs: the floor's are unused (zeros); the lamp's run 0..1 (add_quad_z's corner order).
    const float uv[24] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    a.set("uvs", ElemType::F32, {4, 3, 2}, uv);
    ProgramBuilder b;
    const uint32_t tex = b.image(4, 1, {Color(0.f), Color(2.f), Color(6.f), Color(16.f)});
    const uint32_t co = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Uv)});
    const uint32_t reg = b.op(ShaderOpCode::Image, co, 0, 0,
                              {tex, uint32_t(TexInterpolation::Closest), uint32_t(TexExtension::Extend), 0});
    const uint32_t p = b.end_program();
    b.bind(InputTarget::Emission, lamp, 0, 3, p, reg);
    b.add_to(a);
    return a;
}

struct Strategy {
    double mean = 0.0, standard_error = 0.0;
    double pixel_variance = 0.0;  // mean over pixels of the across-seed variance of the pixel value
};

Strategy run(const PreparedScene& scene, const std::string& sampling, const std::string& light_pdf) {
    std::vector<double> means(k_seeds);
    std::vector<double> sum(size_t(W) * H, 0.0), sum_sq(size_t(W) * H, 0.0);
    for (int k = 0; k < k_seeds; ++k) {
        Params o;
        o.set("light_sampling", sampling);
        o.set("light_pdf", light_pdf);
        o.set("seed", int64_t(1000 + k));
        const RenderResult r = scene.render(o);
        means[size_t(k)] = r.mean_rgb;
        for (size_t i = 0; i < sum.size(); ++i) {
            const double v = (double(r.rgba[4 * i]) + r.rgba[4 * i + 1] + r.rgba[4 * i + 2]) / 3.0;
            sum[i] += v;
            sum_sq[i] += v * v;
        }
    }
    Strategy s;
    for (double m : means) s.mean += m / k_seeds;
    double var = 0.0;
    for (double m : means) var += (m - s.mean) * (m - s.mean) / (k_seeds - 1);
    s.standard_error = std::sqrt(var / k_seeds);
    for (size_t i = 0; i < sum.size(); ++i)
        s.pixel_variance += (sum_sq[i] - sum[i] * sum[i] / k_seeds) / (k_seeds - 1) / double(sum.size());
    return s;
}

TEST(TexturedEmitter, IsSampledAsALightAndEveryStrategyAgrees) {
    Params base = basic_params(W, H, 64, 0);
    base.set("sampler", std::string("RANDOM"));
    base.set("threads", int64_t(2));
    const PreparedScene scene(textured_emitter_scene(), base);
    EXPECT_EQ(scene.scene().lights().size(), 2u);  // the lamp's two triangles
    EXPECT_EQ(scene.scene().stats().emissive_triangles, 2u);

    // The light's winding normal is the one a ray hitting the lamp reports (shader programs reading the normal
    // then see the same value from both strategies).
    SurfaceHit hit;
    ASSERT_TRUE(scene.scene().intersect(Ray{Vec3(0.f), normalize(Vec3(1.f, 0.f, -1.2f))}, &hit));
    ASSERT_GE(hit.light, 0);
    EXPECT_GT(dot(std::get<TriangleLight>(scene.scene().lights()[size_t(hit.light)]).normal, hit.ng), 0.999f);

    const Strategy bsdf = run(scene, "BSDF_ONLY", "SOLID_ANGLE");
    const Strategy light_sa = run(scene, "LIGHT_ONLY", "SOLID_ANGLE");  // spherical-triangle sampling: near
    const Strategy light_area = run(scene, "LIGHT_ONLY", "AREA");
    const Strategy mis = run(scene, "MIS", "SOLID_ANGLE");
    ASSERT_GT(bsdf.mean, 0.01);
    const std::pair<const char*, const Strategy*> others[] = {
        {"LIGHT_ONLY (solid angle)", &light_sa}, {"LIGHT_ONLY (area)", &light_area}, {"MIS", &mis}};
    auto agree = [](const char* a_name, const Strategy& a, const char* b_name, const Strategy& b) {
        const double tolerance =
            5.0 * std::sqrt(a.standard_error * a.standard_error + b.standard_error * b.standard_error);
        EXPECT_NEAR(a.mean, b.mean, tolerance)
            << a_name << " against " << b_name << " (σ " << a.standard_error << ", " << b.standard_error << ")";
    };
    for (const auto& [name, s] : others) agree(name, *s, "BSDF_ONLY", bsdf);
    // The light-sampled strategies are much less noisy: compare them with each other too (tighter).
    agree("LIGHT_ONLY (solid angle)", light_sa, "MIS", mis);
    agree("LIGHT_ONLY (area)", light_area, "MIS", mis);
    EXPECT_LT(light_sa.pixel_variance, 0.5 * bsdf.pixel_variance)
        << "light sampling does not see the textured emitter (variance " << light_sa.pixel_variance << " vs BSDF "
        << bsdf.pixel_variance << ")";
    EXPECT_LT(light_area.pixel_variance, 0.5 * bsdf.pixel_variance);
    RecordProperty("variance_ratio_light_sa", std::to_string(light_sa.pixel_variance / bsdf.pixel_variance));
    std::printf(
        "means: bsdf %.5f±%.5f light(sa) %.5f±%.5f light(area) %.5f±%.5f mis %.5f±%.5f; variance ratios %.4f %.4f "
        "%.4f\n",
        bsdf.mean, bsdf.standard_error, light_sa.mean, light_sa.standard_error, light_area.mean,
        light_area.standard_error, mis.mean, mis.standard_error, light_sa.pixel_variance / bsdf.pixel_variance,
        light_area.pixel_variance / bsdf.pixel_variance, mis.pixel_variance / bsdf.pixel_variance);
}

}  // namespace
}  // namespace candela::test
