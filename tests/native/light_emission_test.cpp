// Emission sampling of every light (lights/light_emission.h) and the emitter set (lights/emitter_set.h): the
// densities a sample reports equal the ones light_pdf_le evaluates for the same ray; the directions follow them
// (χ²); the origins are uniform where they should be (χ² on a grid); and the mean flux weight equals each light's
// analytic flux (docs/verification.md): 4πI for a point light, I·π(1 − cos²θ_s) for a sharp Cycles 3.4 spot (its
// extra cos θ), πAL for a one-sided area light, 2πAL for a two-sided triangle, E·πR² for the sun and 4πL·πR² for
// a constant world through the scene's bounding disk.
//
// Tolerances: a flux mean of N = 400,000 weights is within 5 estimated standard errors (false alarm 6e-7 per
// check; a light whose weight is constant, a point light, has σ = 0 and is held to float rounding, 1e-6); χ² tests
// at a family-wise 1e-3 over this file (Šidák).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "chi2.h"
#include "core/rng.h"
#include "lights/emitter_set.h"
#include "lights/light_emission.h"

namespace candela::test {
namespace {

constexpr int k_chi2_tests = 12;
const double k_alpha = sidak_alpha(1e-3, k_chi2_tests);

const SceneSphere k_bounds{Vec3(0.5f, -1.f, 2.f), 3.f};

PointLight point(float radius = 0.f) {
    PointLight l;
    l.position = Vec3(0.2f, 0.3f, -0.4f);
    l.intensity = Color(2.f, 1.f, 0.5f);
    l.radius = radius;
    return l;
}

PointLight spot(float radius, float blend) {
    PointLight l = point(radius);
    l.spot.direction = normalize(Vec3(0.3f, -1.f, 0.2f));
    l.spot.cos_half = std::cos(0.6f);
    l.spot.smooth = (1.f - l.spot.cos_half) * blend;
    l.spot.cycles34_cosine = true;
    return l;
}

AreaLight area(bool ellipse) {
    AreaLight l;
    l.center = Vec3(0.f, 1.f, 0.f);
    l.u = Vec3(1.2f, 0.f, 0.f);
    l.v = Vec3(0.f, 0.f, 0.7f);
    l.normal = Vec3(0.f, -1.f, 0.f);
    l.radiance = Color(3.f);
    l.ellipse = ellipse;
    l.area = ellipse ? 0.25f * k_pi * 1.2f * 0.7f : 1.2f * 0.7f;
    return l;
}

TriangleLight triangle() {
    TriangleLight t;
    t.p0 = Vec3(0.f, 0.f, 0.f);
    t.p1 = Vec3(1.f, 0.2f, 0.f);
    t.p2 = Vec3(0.1f, 1.f, 0.3f);
    const Vec3 c = cross(t.p1 - t.p0, t.p2 - t.p0);
    t.area = 0.5f * length(c);
    t.normal = normalize(c);
    t.radiance = Color(1.5f);
    t.prepare();
    return t;
}

SunLight sun(float angle) {
    SunLight s;
    s.to_sun = normalize(Vec3(0.2f, 1.f, 0.4f));
    s.irradiance = Color(4.f);
    s.tan_half_angle = std::tan(0.5f * angle);
    return s;
}

struct Case {
    std::string name;
    Light light;
    double flux;  // luminance of the analytic flux
};

std::vector<Case> cases() {
    const double R2pi = k_pi * k_bounds.radius * k_bounds.radius;
    const double I = luminance(Color(2.f, 1.f, 0.5f));
    const double c = std::cos(0.6);
    return {
        {"point", point(), 4.0 * M_PI * I},
        {"point radius", point(0.25f), 4.0 * M_PI * I},
        {"spot", spot(0.f, 0.f), I * M_PI * (1.0 - c * c)},
        {"spot radius", spot(0.1f, 0.f), I * M_PI * (1.0 - c * c)},
        {"spot blend", spot(0.f, 0.4f), I * spot_solid_angle_integral(spot(0.f, 0.4f).spot)},
        {"area rectangle", area(false), M_PI * area(false).area * 3.0},
        {"area ellipse", area(true), M_PI * area(true).area * 3.0},
        {"triangle", triangle(), 2.0 * M_PI * triangle().area * 1.5},
        {"sun", sun(0.f), 4.0 * R2pi},
        {"sun soft", sun(0.1f), 4.0 * R2pi},
        {"world", WorldLight{Color(0.5f), k_bounds.radius, nullptr}, 4.0 * M_PI * 0.5 * R2pi},
    };
}

EmissionSample draw(const Light& l, Pcg32& rng) {
    const Vec2 a{rng.next_float(), rng.next_float()}, b{rng.next_float(), rng.next_float()};
    return light_sample_le(l, a, b, rng.next_float(), k_bounds);
}

TEST(LightEmission, SampledDensitiesEqualTheEvaluatedOnes) {
    for (const Case& c : cases()) {
        Pcg32 rng(3, 7);
        for (int i = 0; i < 2000; ++i) {
            const EmissionSample s = draw(c.light, rng);
            if (!s.valid()) continue;
            float pp = 0.f, pd = 0.f;
            light_pdf_le(c.light, s.p, s.n, s.d, k_bounds, &pp, &pd);
            ASSERT_NEAR(pp, s.pdf_pos, 1e-4f * s.pdf_pos) << c.name;
            ASSERT_NEAR(pd, s.pdf_dir, 2e-3f * s.pdf_dir + 1e-6f) << c.name;
            EXPECT_NEAR(length(s.d), 1.f, 1e-5f) << c.name;
        }
    }
}

TEST(LightEmission, TheMeanFluxWeightIsTheLightsFlux) {
    for (const Case& c : cases()) {
        Pcg32 rng(11, 5);
        const int n = 400000;
        double sum = 0.0, sum_sq = 0.0;
        for (int i = 0; i < n; ++i) {
            const EmissionSample s = draw(c.light, rng);
            const double w = s.valid() ? luminance(s.weight()) : 0.0;
            sum += w;
            sum_sq += w * w;
        }
        const double mean = sum / n, se = std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n);
        EXPECT_NEAR(mean, c.flux, 5.0 * se + 1e-6 * c.flux) << c.name;  // + float rounding where the weight is constant
        EXPECT_NEAR(light_emitted_power(c.light, k_bounds), c.flux, 2e-3 * c.flux) << c.name;
    }
}

// Directions: χ² of d against pdf_dir for lights whose direction density does not depend on the origin.
TEST(LightEmission, DirectionsFollowTheirDensity) {
    for (const char* name : {"point", "spot", "area rectangle", "triangle", "world", "sun soft"}) {
        for (const Case& c : cases()) {
            if (c.name != name) continue;
            const Vec3 p_fixed = std::holds_alternative<TriangleLight>(c.light) ? triangle().p0 : Vec3(0.f);
            Pcg32 rng(21, 1);
            auto sampler = [&](Vec2 u, float uc, Vec3* w) {
                const EmissionSample s =
                    light_sample_le(c.light, {rng.next_float(), rng.next_float()}, u, uc, k_bounds);
                if (!s.valid()) return false;
                *w = s.d;
                return true;
            };
            auto pdf = [&](const Vec3& w) {
                float pp = 0.f, pd = 0.f;
                // Area-like lights: the density of d is that of a cosine lobe on a side; a triangle's either side.
                if (const auto* t = std::get_if<TriangleLight>(&c.light)) {
                    light_pdf_le(c.light, p_fixed, dot(w, t->normal) >= 0.f ? t->normal : -t->normal, w, k_bounds, &pp,
                                 &pd);
                } else {
                    light_pdf_le(c.light, Vec3(0.f), Vec3(0.f), w, k_bounds, &pp, &pd);
                }
                return double(pd);
            };
            Chi2Config cfg;
            cfg.samples = 400000;
            const Chi2Result r = chi2_test(sampler, pdf, cfg);
            EXPECT_GT(r.p_value, k_alpha) << name << ": " << r.summary();
        }
    }
}

/// χ² of N points over B equiprobable cells (expected N/B each): the statistic and its survival probability.
double uniform_cells_p_value(const std::vector<int>& counts, int n) {
    const double e = double(n) / counts.size();
    double x2 = 0.0;
    for (int c : counts) x2 += (c - e) * (c - e) / e;
    return chi2_survival(x2, int(counts.size()) - 1);
}

// Origins: uniform on rectangles, ellipses, triangles and the distant lights' disks (χ² over equiprobable cells of
// each shape's own uniform parametrization).
TEST(LightEmission, OriginsAreUniformOnTheEmitter) {
    const int n = 200000, g = 10;
    auto run = [&](const Light& l, const std::function<Vec2(const EmissionSample&)>& to_unit_square) {
        std::vector<int> counts(g * g, 0);
        Pcg32 rng(5, 9);
        for (int i = 0; i < n; ++i) {
            const EmissionSample s = draw(l, rng);
            const Vec2 q = to_unit_square(s);
            ++counts[std::min(g - 1, int(q.y * g)) * g + std::min(g - 1, int(q.x * g))];
        }
        return uniform_cells_p_value(counts, n);
    };
    const AreaLight rect = area(false), ell = area(true);
    EXPECT_GT(run(rect,
                  [&](const EmissionSample& s) {
                      const Vec3 q = s.p - rect.center;
                      return Vec2{dot(q, rect.u) / length_squared(rect.u) + 0.5f,
                                  dot(q, rect.v) / length_squared(rect.v) + 0.5f};
                  }),
              k_alpha);
    auto disk = [](float x, float y) {  // a point of the unit disk → (r², φ/2π): uniform on the square
        return Vec2{std::min(x * x + y * y, 0.99999f), float((std::atan2(y, x) + M_PI) / (2.0 * M_PI))};
    };
    EXPECT_GT(run(ell,
                  [&](const EmissionSample& s) {
                      const Vec3 q = s.p - ell.center;
                      return disk(2.f * dot(q, ell.u) / length_squared(ell.u),
                                  2.f * dot(q, ell.v) / length_squared(ell.v));
                  }),
              k_alpha);
    const TriangleLight tri = triangle();
    EXPECT_GT(run(tri,
                  [&](const EmissionSample& s) {
                      // Uniform on a triangle: (1 − b0)² and b1/(b1 + b2) are independent and uniform.
                      const Vec2 b = tri.barycentrics(s.p);
                      const float b0 = 1.f - b.x - b.y;
                      return Vec2{(1.f - b0) * (1.f - b0), b.x + b.y > 0.f ? b.x / (b.x + b.y) : 0.5f};
                  }),
              k_alpha);
    const SunLight sn = sun(0.f);
    EXPECT_GT(run(sn,
                  [&](const EmissionSample& s) {
                      const Frame f(sn.to_sun);
                      const Vec3 q = (s.p - k_bounds.center) / k_bounds.radius;
                      return disk(dot(q, f.s), dot(q, f.t));
                  }),
              k_alpha);
}

// Every distant ray starts outside the bounding sphere and travels through it.
TEST(LightEmission, DistantRaysCrossTheBoundingSphere) {
    for (const Case& c : cases()) {
        if (!std::holds_alternative<SunLight>(c.light) && !std::holds_alternative<WorldLight>(c.light)) continue;
        Pcg32 rng(8, 8);
        for (int i = 0; i < 1000; ++i) {
            const EmissionSample s = draw(c.light, rng);
            ASSERT_TRUE(s.infinite);
            EXPECT_GE(length(s.p - k_bounds.center), k_bounds.radius * (1.f - 1e-5f)) << c.name;
            // The ray's closest approach to the centre is within the radius.
            const Vec3 to_c = k_bounds.center - s.p;
            const float t = dot(to_c, s.d);
            EXPECT_LE(length(s.p + s.d * t - k_bounds.center), k_bounds.radius * (1.f + 1e-5f)) << c.name;
        }
    }
}

/// A textured emitter bright only near its first corner (dark at the four points the light selection averages).
struct CornerEmission : EmissionSource {
    Color emission(uint32_t, const Vec3&, const Vec3&, float b1, float b2, const Vec3&) const override {
        return (1.f - b1 - b2) > 0.9f ? Color(100.f) : Color(0.f);
    }
};

TEST(EmitterSet, ChoosesByPowerIncludesAConstantWorldAndKeepsDarkTexturedEmitters) {
    LightSet set;
    set.add(point());
    set.add(area(false));
    TriangleLight textured = triangle();
    CornerEmission source;
    textured.source = &source;
    textured.radiance = Color(0.f);  // what the four-point average saw
    set.add(textured);
    set.set_background(Color(0.2f));
    set.finalize(k_bounds.radius);
    const EmitterSet e(set, k_bounds);
    ASSERT_EQ(e.size(), 4u);
    EXPECT_EQ(e.world(), 3);
    EXPECT_GT(e.pmf(2), 0.f);  // the textured triangle still emits
    double sum = 0.0;
    for (uint32_t i = 0; i < e.size(); ++i) sum += e.pmf(i);
    EXPECT_NEAR(sum, 1.0, 1e-6);
    // Proportional to the flux: point 4πI against the area light's πAL.
    EXPECT_NEAR(e.pmf(0) / e.pmf(1), 4.0 * M_PI * luminance(point().intensity) / (M_PI * area(false).area * 3.0), 1e-3);
    // Its emission is real: the emitted flux weight of the textured triangle has the analytic mean 2π·A·100·0.19 (the
    // corner region b0 > 0.9 holds 1 % of the area: (1 − 0.9)² of it).
    Pcg32 rng(2, 2);
    double sum_w = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        const EmissionSample s = draw(e[2], rng);
        sum_w += s.valid() ? luminance(s.weight()) : 0.0;
    }
    const double expected = 2.0 * M_PI * textured.area * 100.0 * 0.01;
    EXPECT_NEAR(sum_w / n, expected, 0.05 * expected);
}

}  // namespace
}  // namespace candela::test
