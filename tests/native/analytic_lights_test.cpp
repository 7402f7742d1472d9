// Per-pixel closed forms through the real path tracer (docs/verification.md §2.2–§2.6 and the §3 table):
// a white Lambertian receiver (ρ = 1) at the origin, facing +Z, under
//   a disk light        radius 1 at height 1, L = 1:       Lo = ρ·L·a²/(a² + h²)                  = 0.5
//   a square light      2 × 2 centred at height 1, L = 1:  Lo = ρ·L·4·F_corner(1, 1, 1)            = 0.554126
//   a triangle light    (0,0,1) (1,0,1) (0,1,1), L = 1:    Lo = ρ·L·(Lambert's polygon formula)/π  = 0.096225
//   a sphere light      radius 1 at distance 2, L = 1:     Lo = ρ·L·(r/d)²                         = 0.25
// and an off-centre point light inside a diffuse sphere (§2.6): R = 1, ρ = 0.5, I = 1 at (0, 0, 0.5), seen at
// (0, 0, 1): L = (ρ/π)·(I·cosθ/d² + ρI/((1 − ρ)R²)) = (0.5/π)(4 + 1) = 0.795775.
// The disk and square are Blender area lights (radiance = power/(4·area)), the triangle and the sphere emissive
// meshes (emission strength = radiance). The sphere light is a 64 × 32 UV sphere, so its exact value is
// Lambert's polygon formula summed over the facets that face the receiver (a convex mesh: they tile its
// silhouette); it is 0.23 % below the smooth sphere's 0.25, which the test also checks.
//
// Each light is rendered with light_sampling LIGHT_ONLY, BSDF_ONLY and MIS and light_pdf AREA and SOLID_ANGLE
// (BSDF_ONLY does not use the light pdf: once). The point light, which no ray can hit, must be sampled by all
// three strategies alike. "Per pixel": an orthographic camera with a 0.001-wide view looks at the receiver point
// from the side (never through a light). It looks down at about 8°, which stretches its footprint on the receiver
// ~7× along the view, so every pixel sees the receiver point to within 0.004; the irradiance is smooth there and
// changes by second order, < 10⁻⁵ of its value. (A 0.01-wide view, 100× that, put the image mean 1.5–2·10⁻⁴ below
// the exact value: larger than 4σ of the solid-angle estimators, which are nearly noise-free here.)
//
// Tolerance: |mean − exact| < 4σ + b, σ the standard error of the image mean from the per-pixel sample
// variances (an overestimate for QMC samplers, hence conservative), b the geometric bias bound (0 for the
// flat lights, whose geometry is exact); each render must also be precise enough that 4σ + b < 1 % of the
// exact value, so passing means "within 1 %" as the issue asks. 23 renders at 4σ: the chance that a correct
// renderer fails one is ≈ 23 · 6·10⁻⁵ = 1.5·10⁻³.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/math.h"
#include "reference_scenes.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// E/L at x (normal n) from a closed convex emissive mesh: its facets that face x tile its silhouette.
double convex_mesh_irradiance(const MeshBuilder& b, Vec3 offset, Vec3 centre, Vec3 x, Vec3 n) {
    double e = 0.0;
    for (size_t t = 0; t < b.triangles.size(); t += 3) {
        std::vector<Vec3> p;
        for (int k = 0; k < 3; ++k) {
            const uint32_t i = b.triangles[t + k];
            p.push_back(Vec3(b.positions[3 * i], b.positions[3 * i + 1], b.positions[3 * i + 2]) + offset);
        }
        Vec3 normal = cross(p[1] - p[0], p[2] - p[0]);
        const Vec3 c = (p[0] + p[1] + p[2]) / 3.f;
        if (dot(normal, c - centre) < 0.f) normal = -normal;  // outward
        if (dot(normal, x - c) > 0.f) e += polygon_irradiance(p, x, n);
    }
    return e;
}

constexpr float k_receiver_half = 5.f;
constexpr int k_film = 8;  // 8 × 8 pixels, tiles of 4: both cores busy

/// Orthographic view of a 0.001-wide patch around `target` from `eye`.
Params camera_params(Vec3 eye, Vec3 target, Vec3 up, std::vector<float>* rows) {
    *rows = look_at(eye, target, up);
    Params p = basic_params(k_film, k_film, 1, 40);
    p.set("camera_type", std::string("ORTHO"));
    p.set("ortho_scale", 0.001);
    p.set("clip_start", 0.01);
    p.set("tile_size", int64_t(4));
    return p;
}

struct Case {
    std::string name;
    MeshBuilder builder;
    std::vector<float> camera;
    Params base;
    double exact = 0.0;
    double bias = 0.0;  // bound on the geometric error of the expected value
    // Relative σ per sample of LIGHT_ONLY and of MIS (measured, rounded up; they set the sample counts).
    double light_sigma = 0.6, mis_sigma = 0.5;
};

/// The receiver under a light: eye on the side, looking down at the origin below every light.
Case receiver_case(const std::string& name) {
    Case c;
    c.name = name;
    const uint32_t white = c.builder.add_material(Color(1.f), Color(0.f));
    c.builder.add_instance(
        c.builder.add_quad_z(-k_receiver_half, k_receiver_half, -k_receiver_half, k_receiver_half, 0.f, white));
    c.base = camera_params(Vec3(4.f, 1.5f, 0.6f), Vec3(0.f), Vec3(0.f, 0.f, 1.f), &c.camera);
    return c;
}

/// The receiver under an emissive 64 × 32 UV sphere of radius 1 and radiance 1 centred 2 above it; the exact
/// value sums Lambert's polygon formula over the facets facing the receiver.
Case sphere_light_case(const std::string& name) {
    Case c = receiver_case(name);
    const uint32_t lamp = c.builder.add_material(Color(0.f), Color(1.f));
    MeshBuilder sphere;
    sphere.add_sphere(1.f, 64, 32, 0);
    const float at[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 2, 0, 0, 0, 1};
    c.builder.add_instance(c.builder.add_sphere(1.f, 64, 32, lamp), at);
    c.exact =
        convex_mesh_irradiance(sphere, Vec3(0.f, 0.f, 2.f), Vec3(0.f, 0.f, 2.f), Vec3(0.f), Vec3(0.f, 0.f, 1.f)) / k_pi;
    return c;
}

/// Renders `c` with one light-sampling configuration and checks it against the exact value.
void check(const PreparedScene& scene, const Case& c, const std::string& light_sampling, const std::string& light_pdf,
           int samples) {
    Params p;
    p.set("light_sampling", light_sampling);
    p.set("light_pdf", light_pdf);
    p.set("samples", int64_t(samples));
    const RenderResult r = scene.render(p);
    const std::string what = c.name + " " + light_sampling + " " + light_pdf;
    const double tolerance = 4.0 * r.standard_error + c.bias;
    EXPECT_LT(tolerance, 0.01 * c.exact) << what << ": too few samples to resolve 1 %";
    EXPECT_NEAR(r.mean_rgb, c.exact, tolerance) << what << " (σ " << r.standard_error << ")";
    ::testing::Test::RecordProperty(what, std::to_string(r.mean_rgb) + " ± " + std::to_string(r.standard_error) +
                                              " (exact " + std::to_string(c.exact) + ")");
}

/// Samples per pixel that bring 4σ to ~0.85 % of the value: a hit-or-miss BSDF estimate with hit probability
/// q = Lo/(ρL) (cosine sampling, uniform radiance) has relative σ √((1 − q)/q) per sample; light sampling of one
/// uniform emitter, and MIS with it, are far less noisy (σ ≈ 0.3–0.5 measured here; the sphere mesh's light
/// samples often land on its far side, which its near side hides: σ ≈ 1.4 and 1.1).
int samples_for(const Case& c, const std::string& light_sampling) {
    const double q = c.exact;  // ρ = L = 1
    const double rel_sigma = light_sampling == "LIGHT_ONLY" ? c.light_sigma
                             : light_sampling == "MIS"      ? c.mis_sigma
                                                            : std::sqrt((1.0 - q) / q);
    const double n = std::pow(4.0 * rel_sigma / 0.0085, 2.0);
    return std::max(64, int(std::ceil(n / (k_film * k_film))));
}

void run_all(Case& c) {
    const PreparedScene scene(c.builder.arrays(c.camera.data()), c.base);
    for (const char* pdf : {"AREA", "SOLID_ANGLE"})
        for (const char* ls : {"LIGHT_ONLY", "BSDF_ONLY", "MIS"}) {
            if (std::string(ls) == "BSDF_ONLY" && std::string(pdf) == "SOLID_ANGLE") continue;
            check(scene, c, ls, pdf, samples_for(c, ls));
        }
}

TEST(AnalyticLights, PolygonFormulaReproducesTheTable) {
    // The oracle itself against docs/verification.md §2.3 and §2.4.
    const Vec3 x(0.f), n(0.f, 0.f, 1.f);
    EXPECT_NEAR(polygon_irradiance({{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}, x, n), 1.740840, 1e-5);
    EXPECT_NEAR(polygon_irradiance({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, x, n), 0.302300, 1e-5);
}

TEST(AnalyticLights, DiskLightOverDiffuseReceiver) {
    Case c = receiver_case("disk");
    // Radius 1: diameters u, v of length 2, area π; power 4·A·L for radiance 1; shines down (−Z).
    c.builder.add_area_light(Vec3(0.f, 0.f, 1.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 2.f, 0.f), Vec3(0.f, 0.f, -1.f),
                             Color(4.f * k_pi), true);
    c.exact = 1.0 * 1.0 / (1.0 + 1.0);
    run_all(c);
}

TEST(AnalyticLights, SquareLightOverDiffuseReceiver) {
    Case c = receiver_case("square");
    c.builder.add_area_light(Vec3(0.f, 0.f, 1.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 2.f, 0.f), Vec3(0.f, 0.f, -1.f),
                             Color(16.f), false);
    c.exact = 1.740840 / k_pi;  // E/L of docs/verification.md §2.3 over π
    run_all(c);
}

TEST(AnalyticLights, TriangleLightOverDiffuseReceiver) {
    Case c = receiver_case("triangle");
    const uint32_t lamp = c.builder.add_material(Color(0.f), Color(1.f));
    c.builder.add_instance(c.builder.add_triangle(Vec3(0.f, 0.f, 1.f), Vec3(1.f, 0.f, 1.f), Vec3(0.f, 1.f, 1.f), lamp));
    c.exact = 0.302300 / k_pi;
    run_all(c);
}

TEST(AnalyticLights, SphereLightOverDiffuseReceiver) {
    Case c = sphere_light_case("sphere");
    // The inscribed mesh shows a slightly smaller silhouette than the sphere: E = π·L·(r/d)² minus 0.23 %.
    EXPECT_NEAR(c.exact, 0.25, 0.0025);
    EXPECT_LT(c.exact, 0.25);
    c.light_sigma = 1.5;
    c.mis_sigma = 1.2;
    run_all(c);
}

// The sphere light to a few tenths of a percent: light sampling of every facet (ALL) with independent samples.
// The tolerance is 4σ plus 0.1 % for the float evaluation of the exact value, the pixels' footprint and the
// shadow rays' 10⁻⁴ shortening (measured residual: −0.02 %). Samples on the far facets are hidden by the near ones,
// so σ ≈ 9·10⁻⁵ (0.035 %) at 128 samples per pixel; the test must resolve the shadow-ray bug it was written for,
// so 4σ + 0.1 % must stay below 0.3 %. That bug (integrators/shadow_ray.h): shadow rays started at the offset
// origin but kept the direction computed from the shading point, so toward points seen at grazing incidence on the
// emitter (the sphere's rim facets) the shifted ray met the emitter's plane before tmax and the sample was lost:
// 0.248527 instead of 0.249436 (−0.37 %), while BSDF_ONLY agreed.
TEST(AnalyticLights, SphereLightLightSamplingToAFewTenthsOfAPercent) {
    Case c = sphere_light_case("sphere (precise)");
    const PreparedScene scene(c.builder.arrays(c.camera.data()), c.base);
    Params p;
    p.set("light_sampling", std::string("LIGHT_ONLY"));
    p.set("light_selection", std::string("ALL"));
    p.set("sampler", std::string("RANDOM"));  // independent samples: σ from the sample variance is exact
    p.set("samples", int64_t(128));
    const RenderResult r = scene.render(p);
    const double tolerance = 4.0 * r.standard_error + 0.001 * c.exact;
    EXPECT_LT(tolerance, 0.003 * c.exact) << "too few samples to resolve the −0.37 % of the shadow-ray bug";
    EXPECT_NEAR(r.mean_rgb, c.exact, tolerance) << "σ " << r.standard_error;
}

TEST(AnalyticLights, OffCentrePointLightInDiffuseSphere) {
    Case c;
    c.name = "point light in sphere";
    const uint32_t grey = c.builder.add_material(Color(0.5f), Color(0.f));
    // A 256 × 128 UV sphere, turned so the view point (0, 0, 1) lies inside a facet rather than on the pole.
    const float a = 0.7f, ca = std::cos(a), sa = std::sin(a);
    const float turn[16] = {1, 0, 0, 0, 0, ca, -sa, 0, 0, sa, ca, 0, 0, 0, 0, 1};
    c.builder.add_instance(c.builder.add_sphere(1.f, 256, 128, grey), turn);
    c.builder.add_point_light(Vec3(0.f, 0.f, 0.5f), Color(4.f * k_pi));  // I = S/(4π) = 1
    c.base = camera_params(Vec3(0.f), Vec3(0.f, 0.f, 1.f), Vec3(0.f, 1.f, 0.f), &c.camera);
    const double rho = 0.5, I = 1.0, d = 0.5;
    c.exact = rho / k_pi * (I / (d * d) + rho * I / (1.0 - rho));
    EXPECT_NEAR(c.exact, 0.795775, 1e-6);
    // Geometry: the facets are within 8·10⁻⁵ of the sphere and tilted by < 0.7° (direct term: < 2·10⁻⁴
    // relative); the indirect term scales with 4π/area(mesh) − 1 (furnace_facet_bias); doubled as a bound.
    c.bias = c.exact * 2.0 * (2e-4 + furnace_facet_bias(256, 128));
    const PreparedScene scene(c.builder.arrays(c.camera.data()), c.base);
    // Nothing can hit a point light: every strategy must still sample it (BSDF_ONLY included).
    for (const char* ls : {"LIGHT_ONLY", "BSDF_ONLY", "MIS"}) check(scene, c, ls, "SOLID_ANGLE", 1024);
}

}  // namespace
}  // namespace candela::test
