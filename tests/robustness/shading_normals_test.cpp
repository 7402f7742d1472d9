// Shading normals that disagree with the geometry (low-poly smooth-shaded spheres, cylinders and boxes) and
// grazing directions: shading follows the smooth-shading formula wherever the facet and its shading normals
// agree, goes dark only in the terminator band where they cannot agree, never creates energy (white furnace),
// never lets light through a closed surface, and never produces NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/math.h"
#include "hard_scenes.h"
#include "scene/scene.h"
#include "session/session.h"

namespace candela::test {
namespace {

Params params(int w, int h, int spp, int bounces, bool transparent = false) {
    Params p = basic_params(w, h, spp, bounces);
    p.set("film_transparent", transparent);
    return p;
}

void add_sun(ShadedBuilder& b, Vec3 to_sun, float irradiance) {
    std::vector<float> row(20, 0.f);
    const Vec3 dir = -normalize(to_sun);  // where the sun shines
    row[0] = row[1] = row[2] = irradiance;
    row[6] = dir.x;
    row[7] = dir.y;
    row[8] = dir.z;
    b.add_light(2, row);
}

// Largest angle between a triangle's geometric normal and its corners' shading normals: δ.
float max_normal_disagreement(const ShadedBuilder& b) {
    float delta = 0.f;
    for (size_t t = 0; t < b.triangles.size() / 3; ++t) {
        if (!b.smooth[t]) continue;
        Vec3 v[3];
        for (int k = 0; k < 3; ++k) {
            const float* p = &b.positions[3 * b.triangles[3 * t + k]];
            v[k] = Vec3(p[0], p[1], p[2]);
        }
        const Vec3 ng = normalize(cross(v[1] - v[0], v[2] - v[0]));
        if (!is_finite(ng)) continue;
        for (int k = 0; k < 3; ++k) {
            const float* n = &b.normals[9 * t + 3 * k];
            delta = std::max(delta, std::acos(clamp(std::fabs(dot(ng, Vec3(n[0], n[1], n[2]))), 0.f, 1.f)));
        }
    }
    return delta;
}

// A low-poly smooth-shaded object lit by a sun from the side (direct light only, albedo a, irradiance E). At
// every hit the path tracer shades with the shading normal ns (the facet normal ng where ns faces away from
// the viewer) and lights only if the light is above both ns's and ng's horizon (else light would leak). So,
// probing 9 points of each pixel's footprint (corners, edge midpoints, centre) through the scene's own camera and intersector:
//  - all probes lit by both normals: the pixel is a·E/π·cos(ns, l) averaged over the footprint, so it must lie
//    within [0.9·min, 1.1·max] of the probes' values (±6σ; the 10 % covers the footprint between probes);
//  - all probes facing away from the light by ns: exactly black (nothing leaks to the dark side);
//  - otherwise a probe is in the terminator band (ng·l ≤ 0 < ns·l): dark is allowed there, and "beyond reason"
//    would be a band whose smooth shading is brighter than a·E/π·sin δ: with δ the largest angle between a
//    facet's normal and its corners' shading normals, ng·l ≤ 0 forces ns·l ≤ sin δ.
TEST(ShadingNormals, LowPolySmoothObjectsShadeSmoothlyOutsideTheTerminatorBand) {
    struct Shape {
        std::string name;
        int kind;  // 0 sphere, 1 cylinder
        int segments, rings;
        Vec3 to_sun;
    };
    const float albedo = 0.8f, irradiance = 3.f;
    for (const Shape& s :
         {Shape{"sphere 12x6", 0, 12, 6, Vec3(1.f, 0.3f, 0.2f)}, Shape{"sphere 8x4", 0, 8, 4, Vec3(1.f, -0.5f, 0.6f)},
          Shape{"cylinder 10", 1, 10, 0, Vec3(1.f, 0.2f, 0.5f)}}) {
        ShadedBuilder b;
        const uint32_t m = b.add_material(Color(albedo), Color(0.f));
        const uint32_t mesh = s.kind == 0 ? b.add_smooth_sphere(1.f, s.segments, s.rings, m)
                                          : b.add_smooth_cylinder(0.8f, -1.f, 1.f, s.segments, m);
        // Tilted so the facets meet the terminator at an angle; 4 units in front of the camera.
        const float c = std::cos(0.6f), sn = std::sin(0.6f);
        const float xf[16] = {1, 0, 0, 0, 0, c, -sn, 0, 0, sn, c, -4.f, 0, 0, 0, 1};
        b.add_instance(mesh, xf);
        add_sun(b, s.to_sun, irradiance);
        const float delta = max_normal_disagreement(b);
        const Params p = params(64, 48, 16, 0, true);
        const RenderResult r = render(b.arrays(), p);
        const Scene scene(b.arrays(), p, nullptr);
        const Vec3 l = normalize(s.to_sun);
        const float k = albedo * irradiance * k_inv_pi;
        size_t lit = 0, dark = 0, band = 0, wrong = 0;
        float band_max = 0.f;
        for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x) {
                const size_t i = size_t(y) * r.width + x;
                float lo = 1e30f, hi = 0.f;
                int n_lit = 0, n_dark = 0, n_probe = 0;
                bool missed = false;
                for (int py = 0; py < 3 && !missed; ++py)
                    for (int px = 0; px < 3; ++px) {
                        const Ray ray = scene.camera().generate_ray(Vec2{x + 0.5f * px, y + 0.5f * py});
                        SurfaceHit h;
                        if (!scene.intersect(ray, &h)) {
                            missed = true;
                            break;
                        }
                        const Vec3 wo = -ray.d;
                        const float side = dot(wo, h.ng) < 0.f ? -1.f : 1.f;
                        const Vec3 ng = h.ng * side, ns = h.ns * side;
                        const Vec3 n = dot(wo, ns) > 0.f ? ns : ng;
                        const float cs = dot(n, l), cg = dot(ng, l);
                        ++n_probe;
                        if (cs > 0.f && cg > 0.f) {
                            ++n_lit;
                            lo = std::min(lo, k * cs);
                            hi = std::max(hi, k * cs);
                        } else if (cs <= 0.f) {
                            ++n_dark;
                        } else {
                            band_max = std::max(band_max, cs);
                        }
                    }
                if (missed || r.rgba[4 * i + 3] != 1.f) continue;  // silhouette pixels
                const double v = pixel_luminance(r, i), sigma = 6.0 * r.noise[i] + 1e-5;
                if (n_lit == n_probe) {
                    ++lit;
                    wrong += !(v >= 0.9 * lo - sigma && v <= 1.1 * hi + sigma);
                } else if (n_dark == n_probe) {
                    ++dark;
                    wrong += v != 0.0;
                } else {
                    ++band;
                }
            }
        EXPECT_EQ(wrong, 0u) << s.name;
        EXPECT_GT(lit, 200u) << s.name;
        EXPECT_GT(dark, 100u) << s.name;
        EXPECT_LE(band_max, std::sin(delta) + 1e-4f) << s.name << ": δ = " << delta * 180.f / k_pi << "°";
        std::printf("  %-12s δ = %4.1f°: %zu lit, %zu dark, %zu terminator-band pixels (≤ sin δ = %.2f of full)\n",
                    s.name.c_str(), delta * 180.f / k_pi, lit, dark, band, std::sin(delta));
    }
}

// White furnace: closed low-poly smooth objects of albedo 1 (diffuse, and glossy GGX) under a uniform white
// world, plus a smooth-shaded ground seen at grazing angles. Every path's estimate is unbiased for a quantity
// ≤ 1 (a white, energy-conserving BSDF reflects at most what arrives, and rejected directions only lose), so
// every pixel must be ≤ 1 within 6σ, and the mean over the objects ≤ 1 within 4σ. Background pixels are 1.
TEST(ShadingNormals, WhiteFurnaceWithSmoothShadingCreatesNoEnergy) {
    for (const std::string closure : {"DIFFUSE", "GLOSSY"}) {
        ShadedBuilder b;
        const uint32_t m = b.add_material(Color(1.f), Color(0.f));
        if (closure == "GLOSSY")
            b.add_closure(m, "GLOSSY", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"roughness", 0.3f}});
        else
            b.add_closure(m, "DIFFUSE", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}});
        const float a[16] = {1, 0, 0, -1.2f, 0, 1, 0, 0, 0, 0, 1, -4.f, 0, 0, 0, 1};
        b.add_instance(b.add_smooth_sphere(0.9f, 8, 5, m), a);
        const float c[16] = {1, 0, 0, 1.1f, 0, 0, 1, 0, 0, -1, 0, -4.f, 0, 0, 0, 1};
        b.add_instance(b.add_smooth_cylinder(0.7f, -0.9f, 0.9f, 7, m), c);
        b.add_instance(b.add_box(Vec3(-0.4f, 0.5f, -3.4f), Vec3(0.4f, 1.1f, -2.6f), m, true));
        // Ground just below the camera, its shading normals tilted ±35° (a coarse "smooth" terrain).
        const uint32_t ground = b.add_quad(Vec3(-50.f, -0.02f, 5.f), Vec3(100.f, 0, 0), Vec3(0, 0, -100.f), m);
        for (int t = 0; t < 2; ++t)
            for (int k = 0; k < 3; ++k) {
                const float tilt = (k == 1) ? 0.6f : -0.6f;
                float* n = &b.normals[9 * (b.mesh_tri_start[ground] + t) + 3 * k];
                n[0] = std::sin(tilt);
                n[1] = std::cos(tilt);
                n[2] = 0.f;
                b.smooth[b.mesh_tri_start[ground] + t] = 1;
            }
        b.add_instance(ground);
        b.world_color = {1.f, 1.f, 1.f};
        Params p = params(64, 48, 32, 64);
        Session s(b.arrays(), p);
        s.start();
        s.join();
        int ch = 0;
        const auto rgba = s.get_pass("Combined", &ch);
        const auto noise = s.get_pass("Noise", &ch);
        size_t over = 0;
        double sum = 0.0, var = 0.0;
        for (size_t i = 0; i < noise.size(); ++i) {
            const double v = 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2];
            ASSERT_TRUE(std::isfinite(v));
            over += v > 1.0 + 6.0 * noise[i] + 1e-5;
            sum += v;
            var += double(noise[i]) * noise[i];
        }
        const double mean = sum / noise.size(), se = std::sqrt(var) / noise.size();
        EXPECT_EQ(over, 0u) << closure;
        EXPECT_LE(mean, 1.0 + 4.0 * se + 1e-6) << closure;
        EXPECT_EQ(s.stats().nan_samples, 0u) << closure;
        std::printf("  furnace %-7s mean %.4f ± %.4f\n", closure.c_str(), mean, se);
    }
}

// The camera inside a closed low-poly smooth-shaded box (shading normals 54.7° off the faces) or sphere, every
// kind of light outside, and a white world: nothing may get in. Each pixel must be exactly 0. The same scene
// without the enclosure is bright (the test can fail).
TEST(ShadingNormals, NoLightLeaksIntoAClosedSmoothShadedEnclosure) {
    for (int enclosure = 0; enclosure < 2; ++enclosure)
        for (const std::string closure : {"DIFFUSE", "GLOSSY"})
            for (int with_walls = 1; with_walls >= 0; --with_walls) {
                ShadedBuilder b;
                const uint32_t m = b.add_material(Color(0.8f), Color(0.f));
                b.add_closure(m, closure,
                              {{"color_r", 0.8f}, {"color_g", 0.8f}, {"color_b", 0.8f}, {"roughness", 0.2f}});
                if (with_walls) {
                    const uint32_t mesh =
                        enclosure == 0 ? b.add_box(Vec3(-1.f), Vec3(1.f), m, true) : b.add_smooth_sphere(1.f, 8, 4, m);
                    b.add_instance(mesh);
                }
                // A floor inside: lit through the walls' gaps if there were any.
                b.add_instance(b.add_quad(Vec3(-0.8f, -0.5f, 0.5f), Vec3(1.6f, 0, 0), Vec3(0, 0, -1.3f), m));
                b.add_point_light(Vec3(0.3f, 1.6f, -0.2f), Color(300.f));
                b.add_point_light(Vec3(-1.05f, 0.f, 0.f), Color(100.f), 0.02f);  // just outside a wall
                add_sun(b, Vec3(0.3f, 1.f, 0.4f), 5.f);
                b.add_area_light(Vec3(0.f, 0.f, -1.3f), Vec3(1.f, 0, 0), Vec3(0, 1.f, 0), Vec3(0, 0, 1.f),
                                 Color(200.f));
                b.world_color = {1.f, 1.f, 1.f};
                const RenderResult r = render(b.arrays(), params(32, 24, 16, 8));
                const std::string what = std::string(enclosure ? "sphere" : "box") + ", " + closure;
                if (with_walls) {
                    size_t lit = 0;
                    for (size_t i = 0; i < r.rgba.size(); ++i) lit += i % 4 != 3 && r.rgba[i] != 0.f;
                    EXPECT_EQ(lit, 0u) << what << ": light got into the enclosure";
                    EXPECT_EQ(r.mean_rgb, 0.0) << what;
                } else {
                    EXPECT_GT(r.mean_rgb, 0.05) << what << " without walls";
                }
            }
}

}  // namespace
}  // namespace candela::test
