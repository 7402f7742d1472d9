// Blender light units (Cycles 3.4, docs/conventions.md §2–§3) and light sampling estimators checked
// against closed forms (docs/verification.md §2).
#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "core/rng.h"
#include "input/scene_arrays.h"
#include "lights/light.h"
#include "lights/light_bounds.h"

namespace candela {
namespace {

SceneArrays light_arrays(uint32_t type, const std::vector<float>& row) {
    SceneArrays a;
    a.set("light_type", ElemType::U32, {1}, &type);
    a.set("lights", ElemType::F32, {1, row.size()}, row.data());
    return a;
}

std::vector<float> row(Color strength, Vec3 pos, Vec3 dir) {
    std::vector<float> r(light_columns().size(), 0.f);
    r[0] = strength.x;
    r[1] = strength.y;
    r[2] = strength.z;
    r[3] = pos.x;
    r[4] = pos.y;
    r[5] = pos.z;
    r[6] = dir.x;
    r[7] = dir.y;
    r[8] = dir.z;
    return r;
}

/// Irradiance at ctx (normal n) estimated by light sampling, and its standard error.
std::pair<double, double> irradiance(const Light& light, const LightSampleContext& ctx, int n = 200000) {
    Pcg32 rng(11, 12);
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < n; ++i) {
        const LightSample s = light_sample_li(light, ctx, {rng.next_float(), rng.next_float()});
        double v = 0;
        if (s.valid()) v = luminance(s.Li) * std::max(0.f, dot(s.wi, ctx.n)) / s.pdf;
        sum += v;
        sum_sq += v * v;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n)};
}

TEST(BlenderLights, PointLightIntensityIsPowerOverFourPi) {
    // Cycles table: point 1000 W two metres above a white plane: Lo = P/(4π)·cosθ/r²/π.
    const auto lights =
        load_blender_lights(light_arrays(0, row(Color(1000.f), Vec3(0, 0, 2), Vec3(0, 0, -1))), Vec3(0.f));
    ASSERT_EQ(lights.size(), 1u);
    const LightSampleContext ctx{Vec3(1.f, 0.f, 0.f), Vec3(0, 0, 1)};
    const auto [E, se] = irradiance(lights[0], ctx, 16);
    const double expected_Lo = 1000.0 / (4 * M_PI) * (2.0 / std::sqrt(5.0)) / 5.0 / M_PI;  // 4.531 in the table
    EXPECT_NEAR(E / M_PI, expected_Lo, 1e-4);
    EXPECT_NEAR(expected_Lo, 4.531, 1e-3);
}

TEST(BlenderLights, SpotLightHasCycles34CosineFactor) {
    std::vector<float> r = row(Color(1000.f), Vec3(0, 0, 2), Vec3(0, 0, -1));
    r[16] = 150.f * k_pi / 180.f;  // spot_size
    r[17] = 0.f;                   // blend
    const auto lights = load_blender_lights(light_arrays(1, r), Vec3(0.f));
    const auto [E, se] = irradiance(lights[0], {Vec3(1.f, 0.f, 0.f), Vec3(0, 0, 1)}, 16);
    EXPECT_NEAR(E / M_PI, 4.053, 2e-3);  // docs/conventions.md §3, the formula with the extra cosθ
}

TEST(BlenderLights, SunGivesItsStrengthAsIrradiance) {
    std::vector<float> r = row(Color(3.f), Vec3(0, 0, 5), Vec3(0, 0, -1));
    const auto lights = load_blender_lights(light_arrays(2, r), Vec3(0.f));
    const auto [E, se] = irradiance(lights[0], {Vec3(0.f), Vec3(0, 0, 1)}, 16);
    EXPECT_NEAR(E / M_PI, 0.9549, 1e-4);
}

TEST(BlenderLights, SoftSunKeepsItsIrradianceNearTheAxis) {
    std::vector<float> r = row(Color(3.f), Vec3(0, 0, 5), Vec3(0, 0, -1));
    r[18] = 0.1f;  // angle
    const auto lights = load_blender_lights(light_arrays(2, r), Vec3(0.f));
    const auto [E, se] = irradiance(lights[0], {Vec3(0.f), Vec3(0, 0, 1)});
    // Each sample contributes S·cosθ; over a 0.05 rad disk the mean cosθ is above 0.999.
    EXPECT_NEAR(E, 3.0, 0.004);
}

TEST(BlenderLights, SpotWithRadiusEvaluatesTheConeFromTheSampledPoint) {
    // Cycles 3.4 evaluates a spot light's cone at the direction from the sampled disk point to the shading
    // point (kernel/light/light.h: spot_light_attenuation(…, −ls->D)). Just outside the cone seen from the
    // centre, part of the disk still lights the point: the exact irradiance is the integral over the disk
    // (radius a, facing the point) of L·att(w)·cosθ_r·cosθ_l/d², L = I/(πa²), done here on a fine polar grid.
    // Evaluating the cone from the centre instead gives exactly 0 at this point, so the test can fail.
    std::vector<float> r = row(Color(1000.f), Vec3(0, 0, 2), Vec3(0, 0, -1));
    r[15] = 0.3f;                 // radius
    r[16] = 60.f * k_pi / 180.f;  // spot_size: the cone's edge meets the plane at 2·tan 30° = 1.155 m
    r[17] = 0.f;                  // blend
    const auto lights = load_blender_lights(light_arrays(1, r), Vec3(0.f));
    const auto& spot = std::get<PointLight>(lights[0]);
    const LightSampleContext ctx{Vec3(1.2f, 0.f, 0.f), Vec3(0, 0, 1)};
    ASSERT_EQ(spot.spot.attenuation(normalize(ctx.p - spot.position)), 0.f);
    const Vec3 axis = normalize(ctx.p - spot.position);  // the disk's normal, toward the point
    const Frame frame(axis);
    const double I = 1000.0 / (4 * M_PI), a = 0.3;
    double exact = 0.0;
    const int nr = 600, nphi = 600;
    for (int i = 0; i < nr; ++i) {
        const double rho = a * (i + 0.5) / nr;
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2 * M_PI * (j + 0.5) / nphi;
            const Vec3 q =
                spot.position + (frame.s * float(rho * std::cos(phi)) + frame.t * float(rho * std::sin(phi)));
            Vec3 w = ctx.p - q;  // light point → shading point
            const double d2 = length_squared(w);
            w = w / float(std::sqrt(d2));
            const double cos_r = std::max(0.f, -dot(w, ctx.n)), cos_l = std::max(0.f, dot(w, axis));
            const double dA = rho * (a / nr) * (2 * M_PI / nphi);
            exact += I / (M_PI * a * a) * spot.spot.attenuation(w) * cos_r * cos_l / d2 * dA;
        }
    }
    const auto [E, se] = irradiance(lights[0], ctx, 400000);
    std::printf("spot with radius outside the centre's cone: E = %.6f ± %.6f, exact %.6f\n", E, se, exact);
    EXPECT_GT(exact, 20 * se);                     // clearly lit: the centre-only evaluation (0) would fail
    EXPECT_NEAR(E, exact, 5 * se + 1e-4 * exact);  // 5σ, plus the grid's quadrature error
    // The WARD selection's bound must stay an upper bound of what the light delivers there.
    EXPECT_GE(light_irradiance_bound(lights[0], ctx), E);
}

TEST(BlenderLights, PointLightWithRadiusKeepsItsIntensity) {
    // A disk of radius r facing the point: E = I/(r² + d²) exactly (on the axis).
    auto r = row(Color(1000.f), Vec3(0, 0, 2), Vec3(0, 0, -1));
    r[15] = 0.5f;
    const auto lights = load_blender_lights(light_arrays(0, r), Vec3(0.f));
    const auto [E, se] = irradiance(lights[0], {Vec3(0.f), Vec3(0, 0, 1)});
    EXPECT_NEAR(E, 1000.0 / (4 * M_PI) / (0.25 + 4.0), 5 * se + 1e-6);
}

TEST(BlenderLights, AreaLightMatchesTheViewFactor) {
    // 1×1 m area light of 100 W two metres above the receiver: L = P/(4A) = 25; on the axis the
    // irradiance is πL·F with F the centred-square view factor (4 corner rectangles 0.5 × 0.5 at c = 2).
    auto r = row(Color(100.f), Vec3(0, 0, 2), Vec3(0, 0, -1));
    r[9] = 1.f;   // u = (1, 0, 0)
    r[13] = 1.f;  // v = (0, 1, 0)
    const auto lights = load_blender_lights(light_arrays(3, r), Vec3(0.f));
    const double X = 0.25, Y = 0.25;
    const double Fc = (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                       Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
                      (2 * M_PI);
    const double expected_E = M_PI * 25.0 * 4.0 * Fc;
    const auto [E, se] = irradiance(lights[0], {Vec3(0.f), Vec3(0, 0, 1)});
    EXPECT_NEAR(E, expected_E, 5 * se);
    EXPECT_NEAR(expected_E / M_PI, 1.837, 0.01);  // the formula value in docs/conventions.md §3
}

TEST(BlenderLights, DiskAreaLightUsesEllipseArea) {
    auto r = row(Color(100.f), Vec3(0, 0, 1), Vec3(0, 0, -1));
    r[9] = 2.f;
    r[13] = 2.f;  // diameter 2: radius a = 1 at height h = 1
    r[19] = 1.f;
    const auto lights = load_blender_lights(light_arrays(3, r), Vec3(0.f));
    const double L = 100.0 / (4.0 * M_PI);  // A = π/4·2·2 = π
    const auto [E, se] = irradiance(lights[0], {Vec3(0.f), Vec3(0, 0, 1)});
    EXPECT_NEAR(E, M_PI * L * 0.5, 5 * se);  // docs/verification.md §2.2: E = πL·a²/(a² + h²)
}

TEST(BlenderLights, AreaLightIsOneSided) {
    auto r = row(Color(100.f), Vec3(0, 0, 2), Vec3(0, 0, 1));  // faces away from the receiver
    r[9] = 1.f;
    r[13] = 1.f;
    const auto lights = load_blender_lights(light_arrays(3, r), Vec3(0.f));
    const auto [E, se] = irradiance(lights[0], {Vec3(0.f), Vec3(0, 0, 1)}, 1000);
    EXPECT_EQ(E, 0.0);
}

TEST(TriangleLight, MatchesLambertsPolygonFormula) {
    // Triangle (0,0,1), (1,0,1), (0,1,1) over the origin: E/L = 0.302300 (docs/verification.md §2.4).
    TriangleLight t;
    t.p0 = Vec3(0, 0, 1);
    t.p1 = Vec3(1, 0, 1);
    t.p2 = Vec3(0, 1, 1);
    t.normal = Vec3(0, 0, -1);
    t.area = 0.5f;
    t.radiance = Color(1.f);
    const auto [E, se] = irradiance(Light(t), {Vec3(0.f), Vec3(0, 0, 1)});
    EXPECT_NEAR(E, 0.302300, 5 * se);
}

TEST(LightSet, SelectionIsProportionalToPower) {
    LightSet set;
    PointLight a, b;
    a.intensity = Color(1.f);
    b.intensity = Color(3.f);
    set.add(a);
    set.add(b);
    set.finalize(1.f);
    EXPECT_FLOAT_EQ(set.selection_pmf(0), 0.25f);
    EXPECT_FLOAT_EQ(set.selection_pmf(1), 0.75f);
    float pmf;
    EXPECT_EQ(set.select(0.5f, &pmf), 1u);
    EXPECT_FLOAT_EQ(pmf, 0.75f);
}

}  // namespace
}  // namespace candela
