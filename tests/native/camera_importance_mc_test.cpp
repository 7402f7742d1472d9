// Camera importance by Monte Carlo (scene/camera_importance.cpp):
//   - K's definition: a uniform camera ray (raster uniform over the full frame, u_lens uniform) hits a small disk of
//     area a with probability E_lens[K·|cos θ_ref|]·a (random disks across the frustum, the frame's edges and the clip
//     planes, hit counts against a quadrature of K over each disk);
//   - ∫ K·|cos θ| dA over a surface that covers the frame is 1: every uniform camera ray hits it;
//   - pdf_dir is the density of generate_ray's directions (χ² of a histogram on the tangent plane).
// Tolerances: each comparison is a z-score against a σ estimated here (binomial counts plus the quadrature's own
// variance), |z| ≤ 4.5: a two-sided false-alarm rate of 6.8e-6 each, ≈ 1e-3 over the 144 disks and 16 plane
// integrals; the 5 χ² tests use p ≥ 2e-4 each (Šidák: 1e-3 together). Seeds are fixed, so a pass is reproducible.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "camera_cases.h"
#include "chi2.h"
#include "core/rng.h"
#include "sampling/warp.h"
#include "scene/camera.h"

namespace candela::test {
namespace {

constexpr double k_z_max = 4.5;

/// An orthonormal frame around the unit n.
void frame_of(const Vec3& n, Vec3* e1, Vec3* e2) {
    const Vec3 a = std::fabs(n.x) > 0.5f ? Vec3(0.f, 1.f, 0.f) : Vec3(1.f, 0.f, 0.f);
    *e1 = normalize(cross(a, n));
    *e2 = cross(n, *e1);
}

struct Disk {
    Vec3 c, n, e1, e2;
    float r = 0.f;
};

bool ray_hits_disk(const Ray& ray, const Disk& k) {
    const float dn = dot(ray.d, k.n);
    if (dn == 0.f) return false;
    const float t = dot(k.c - ray.o, k.n) / dn;
    if (!(t >= ray.tmin && t <= ray.tmax)) return false;
    const Vec3 q = ray.o + ray.d * t - k.c;
    return dot(q, q) <= k.r * k.r;
}

/// ∫_disk E_lens[K·|cos θ_ref|] dA by jittered quadrature over the disk (64 × 64 strata in (r², φ)) with an
/// independent lens sample per point; *variance gets the estimate's variance (as if independent: conservative).
double expected_hit_probability(const Camera& cam, const Disk& k, Pcg32& rng, double* variance) {
    constexpr int m = 64;
    double sum = 0.0, sum2 = 0.0;
    const double area = k_pi * double(k.r) * k.r;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            const float rr = k.r * std::sqrt((i + rng.next_float()) / m);
            const float phi = 2.f * k_pi * (j + rng.next_float()) / m;
            const Vec3 x = k.c + k.e1 * (rr * std::cos(phi)) + k.e2 * (rr * std::sin(phi));
            CameraConnection con;
            double v = 0.0;
            if (cam.connect(x, rand2(rng), &con)) v = area * con.importance * std::fabs(dot(k.n, con.wi));
            sum += v;
            sum2 += v * v;
        }
    const double n = double(m) * m, mean = sum / n;
    *variance = std::max(sum2 / n - mean * mean, 0.0) / n;
    return mean;
}

TEST(CameraImportance, HitProbabilityOfSmallDisksIsTheImportance) {
    const std::vector<std::string> models = {"perspective", "wide_shifted_aspect",
                                             "thin_lens",   "thin_lens_blades_ratio",
                                             "ortho_dof",   "ortho_dof_blades_ratio"};
    for (const CameraCase& c : connectable_cases()) {
        if (std::find(models.begin(), models.end(), c.name) == models.end()) continue;
        const Camera cam(c.params, c.to_world);
        const float w = float(cam.full_width()), h = float(cam.full_height());
        Pcg32 rng(17, 5);
        // 24 disks with random normals, centred anywhere from 5 % outside the frame and 10 % in front of the near
        // clip plane to 3 % beyond the far one: some straddle an edge or a clip plane.
        std::vector<Disk> disks(24);
        for (Disk& k : disks) {
            const Vec2 raster{(rng.next_float() * 1.1f - 0.05f) * w, (rng.next_float() * 1.1f - 0.05f) * h};
            const float depth = 0.9f + 5.3f * rng.next_float();
            k.c = point_at_depth(cam, raster, rand2(rng), depth);
            k.n = sample_uniform_sphere(rand2(rng));
            frame_of(k.n, &k.e1, &k.e2);
            k.r = cam.orthographic() ? 0.06f : 0.02f * depth;
        }
        constexpr int n_rays = 4000000;
        std::vector<int64_t> hits(disks.size(), 0);
        for (int i = 0; i < n_rays; ++i) {
            const Vec2 raster{rng.next_float() * w, rng.next_float() * h};
            const Ray ray = cam.generate_ray(raster, rand2(rng));
            for (size_t k = 0; k < disks.size(); ++k) hits[k] += ray_hits_disk(ray, disks[k]);
        }
        int seen = 0;
        for (size_t k = 0; k < disks.size(); ++k) {
            double var_q;
            const double p = expected_hit_probability(cam, disks[k], rng, &var_q);
            const double expected = p * n_rays;
            const double sigma = std::sqrt(std::max(expected * (1.0 - p), 1.0) + var_q * double(n_rays) * n_rays);
            const double z = (double(hits[k]) - expected) / sigma;
            EXPECT_LE(std::fabs(z), k_z_max)
                << c.name << " disk " << k << ": " << hits[k] << " hits, expected " << expected << " ± " << sigma;
            seen += expected > 300.0;
            if (std::getenv("CANDELA_TEST_VERBOSE"))
                std::printf("%s disk %zu: hits %lld expected %.1f sigma %.1f z %.2f\n", c.name.c_str(), k,
                            (long long)hits[k], expected, sigma, z);
        }
        EXPECT_GE(seen, 12) << c.name << ": too few disks in view to test anything";
    }
}

TEST(CameraImportance, ImportanceIntegratesToOneOverASurfaceCoveringTheFrame) {
    for (const CameraCase& c : connectable_cases()) {
        const Camera cam(c.params, c.to_world);
        const float w = float(cam.full_width()), h = float(cam.full_height());
        for (float tilt : {0.f, 0.3f}) {
            // A plane at depth 3 facing the camera, tilted about the camera's x axis by `tilt` radians.
            const Vec3 fwd = cam.forward();
            const Vec3 right = normalize(c.to_world.column(0)), up = normalize(c.to_world.column(1));
            const Vec3 n = fwd * std::cos(tilt) + up * std::sin(tilt);
            const Vec3 centre = point_at_depth(cam, {0.5f * w, 0.5f * h}, {0.5f, 0.5f}, 3.f);
            const Vec3 e1 = right, e2 = cross(n, e1);
            // The rectangle of the plane every camera ray hits (corner rays with many lens samples), enlarged 20 %.
            Pcg32 rng(23, 9);
            float lo1 = 1e30f, hi1 = -1e30f, lo2 = 1e30f, hi2 = -1e30f;
            auto plane_hit = [&](const Ray& r, float* t) {
                *t = dot(centre - r.o, n) / dot(r.d, n);
                return r.o + r.d * *t - centre;
            };
            for (int i = 0; i < 20000; ++i) {
                const Vec2 raster{float(i % 2) * w, float((i / 2) % 2) * h};
                float t;
                const Vec3 q = plane_hit(cam.generate_ray(raster, rand2(rng)), &t);
                lo1 = std::min(lo1, dot(q, e1));
                hi1 = std::max(hi1, dot(q, e1));
                lo2 = std::min(lo2, dot(q, e2));
                hi2 = std::max(hi2, dot(q, e2));
            }
            const float m1 = 0.2f * (hi1 - lo1), m2 = 0.2f * (hi2 - lo2);
            lo1 -= m1, hi1 += m1, lo2 -= m2, hi2 += m2;
            // Precondition: every uniform camera ray hits the rectangle inside its clip range.
            for (int i = 0; i < 20000; ++i) {
                const Ray r = cam.generate_ray({rng.next_float() * w, rng.next_float() * h}, rand2(rng));
                float t;
                const Vec3 q = plane_hit(r, &t);
                ASSERT_TRUE(t >= r.tmin && t <= r.tmax && dot(q, e1) >= lo1 && dot(q, e1) <= hi1 && dot(q, e2) >= lo2 &&
                            dot(q, e2) <= hi2)
                    << c.name;
            }
            // So ∫ K·|cos θ| dA over the rectangle, a probability, is 1: estimate it with uniform points.
            const double area = double(hi1 - lo1) * (hi2 - lo2);
            constexpr int n_points = 400000;
            double sum = 0.0, sum2 = 0.0;
            for (int i = 0; i < n_points; ++i) {
                const Vec3 x =
                    centre + e1 * (lo1 + (hi1 - lo1) * rng.next_float()) + e2 * (lo2 + (hi2 - lo2) * rng.next_float());
                CameraConnection con;
                if (!cam.connect(x, rand2(rng), &con)) continue;
                const double v = area * con.importance * std::fabs(dot(n, con.wi));
                sum += v;
                sum2 += v * v;
            }
            const double mean = sum / n_points, sigma = std::sqrt((sum2 / n_points - mean * mean) / n_points);
            EXPECT_LE(std::fabs(mean - 1.0), k_z_max * sigma)
                << c.name << " tilt " << tilt << ": " << mean << " ± " << sigma;
            EXPECT_LT(sigma, 0.01) << c.name;  // resolves a 5 % error
        }
    }
}

/// χ² of generate_ray's camera-space directions on the tangent plane (x/−z, y/−z) over the box [lo, hi] in
/// 16 × 16 cells, against pdf_we's pdf_dir integrated over each cell (dω = cos³θ·dA on the tangent plane; 64 × 64
/// midpoints per cell). `ray_for(t)` is the ray whose density pdf_we gives for tangent t; `sample` draws one
/// direction as generate_ray does. Directions outside the box fail the test: the box holds the support.
double direction_chi2_p(const Camera& cam, Vec2 lo, Vec2 hi, const std::function<Ray(Vec2)>& ray_for,
                        const std::function<Vec3(Pcg32&)>& sample, std::string* report) {
    constexpr int cells = 16, sub = 64, n = 1000000;
    std::vector<double> observed(cells * cells, 0.0), expected(cells * cells, 0.0);
    const double cw = (hi.x - lo.x) / cells, ch = (hi.y - lo.y) / cells;
    Pcg32 rng(31, 4);
    int outside = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 d = sample(rng);
        const double tx = d.x / -d.z, ty = d.y / -d.z;
        const int cx = int(std::floor((tx - lo.x) / cw)), cy = int(std::floor((ty - lo.y) / ch));
        if (!(d.z < 0.f) || cx < 0 || cx >= cells || cy < 0 || cy >= cells) {
            ++outside;
            continue;
        }
        observed[cy * cells + cx] += 1.0;
    }
    double total = 0.0;
    for (int cy = 0; cy < cells; ++cy)
        for (int cx = 0; cx < cells; ++cx) {
            double mass = 0.0;
            for (int j = 0; j < sub; ++j)
                for (int i = 0; i < sub; ++i) {
                    const Vec2 t{float(lo.x + cw * (cx + (i + 0.5) / sub)), float(lo.y + ch * (cy + (j + 0.5) / sub))};
                    float pdf_pos, pdf_dir;
                    cam.pdf_we(ray_for(t), &pdf_pos, &pdf_dir);
                    const double cos_theta = 1.0 / std::sqrt(1.0 + double(t.x) * t.x + double(t.y) * t.y);
                    mass += pdf_dir * cos_theta * cos_theta * cos_theta;
                }
            expected[cy * cells + cx] = mass * cw * ch / (sub * sub) * n;
            total += mass * cw * ch / (sub * sub);
        }
    double stat = 0.0, pooled_o = 0.0, pooled_e = 0.0;
    int dof = -1;
    bool impossible = outside > 0;
    for (size_t k = 0; k < observed.size(); ++k) {
        if (expected[k] <= 0.0) {
            impossible |= observed[k] > 0.0;
        } else if (expected[k] < 5.0) {
            pooled_o += observed[k];
            pooled_e += expected[k];
        } else {
            stat += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
            ++dof;
        }
    }
    if (pooled_e > 0.0) {
        stat += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        ++dof;
    }
    *report = "chi2 " + std::to_string(stat) + " dof " + std::to_string(dof) + ", pdf integral " +
              std::to_string(total) + ", outside the box " + std::to_string(outside);
    return impossible ? 0.0 : chi2_survival(stat, dof);
}

TEST(CameraImportance, PdfDirIsTheDensityOfGeneratedDirections) {
    const double alpha = sidak_alpha(1e-3, 5);
    const std::vector<CameraCase> cases = camera_cases();
    // Perspective: pdf_dir is the density given the lens point (raster uniform), so the lens sample is held fixed;
    // the support, the frame seen from that lens point, is the box of the corner rays' tangents.
    struct Persp {
        std::string name;
        Vec2 u_lens;
    };
    for (const Persp& pc : {Persp{"wide_shifted_aspect", {0.5f, 0.5f}}, Persp{"thin_lens", {0.9f, 0.2f}},
                            Persp{"thin_lens_blades_ratio", {0.13f, 0.77f}}}) {
        const Camera cam(case_named(cases, pc.name).params, Affine());
        const float w = float(cam.full_width()), h = float(cam.full_height());
        const Ray r00 = cam.generate_ray({0.f, 0.f}, pc.u_lens), r11 = cam.generate_ray({w, h}, pc.u_lens);
        const Vec2 lo{r00.d.x / -r00.d.z, r00.d.y / -r00.d.z}, hi{r11.d.x / -r11.d.z, r11.d.y / -r11.d.z};
        const Vec3 lens = r00.o;
        std::string report;
        const double p = direction_chi2_p(
            cam, lo, hi,
            [&](Vec2 t) {
                Ray r;
                r.o = lens;
                r.d = normalize(Vec3(t.x, t.y, -1.f));
                return r;
            },
            [&](Pcg32& rng) {
                return cam.generate_ray({rng.next_float() * w, rng.next_float() * h}, pc.u_lens).d;
            },
            &report);
        EXPECT_GE(p, alpha) << pc.name << ": " << report;
    }
    // Orthographic with depth of field: the direction comes from the lens offset alone (tangent −l/f), raster and
    // lens both uniform; the box bounds the squeezed aperture, 2 % larger.
    for (const std::string name : {"ortho_dof", "ortho_dof_blades_ratio"}) {
        const Camera cam(case_named(cases, name).params, Affine());
        const float w = float(cam.full_width()), h = float(cam.full_height());
        const float f = cam.focus_distance(), r = cam.aperture().radius;
        const Vec2 hi{1.02f * r * cam.aperture().inv_ratio / f, 1.02f * r / f}, lo{-hi.x, -hi.y};
        const Ray centre = cam.generate_ray({0.5f * w, 0.5f * h}, {0.3f, 0.6f});
        const Vec3 focus_point = centre.o + centre.d * (f / -centre.d.z);
        std::string report;
        const double p = direction_chi2_p(
            cam, lo, hi,
            [&](Vec2 t) {
                Ray ray;
                ray.d = normalize(Vec3(t.x, t.y, -1.f));
                ray.o = focus_point - ray.d * (f / -ray.d.z);
                return ray;
            },
            [&](Pcg32& rng) {
                const Vec2 raster{rng.next_float() * w, rng.next_float() * h};
                return cam.generate_ray(raster, rand2(rng)).d;
            },
            &report);
        EXPECT_GE(p, alpha) << name << ": " << report;
    }
}

}  // namespace
}  // namespace candela::test
