// Camera importance (scene/camera_importance.cpp) as the exact inverse of generate_ray: raster_of(generate_ray(raster,
// u)) = raster for every projection, sensor fit, shift, pixel aspect and lens, whatever the border; a connection is
// the generate_ray ray through the reference point (origin lens_point, direction −wi) with the densities pdf_we
// gives that ray; clip planes bound connections; the orthographic pinhole connects to nothing; the image-plane and
// lens areas, and the aperture's support. The statistical checks are in camera_importance_mc_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camera_cases.h"
#include "core/rng.h"
#include "scene/camera.h"

namespace candela::test {
namespace {

constexpr double k_z_max = 4.5;  // ApertureContainsExactlyWhatItSamples: two-sided false-alarm rate 6.8e-6

TEST(CameraImportance, RasterOfInvertsGenerateRay) {
    for (const CameraCase& c : camera_cases()) {
        const Camera cam(c.params, c.to_world);
        Pcg32 rng(7, 1);
        const float w = float(cam.full_width()), h = float(cam.full_height());
        double worst = 0.0;
        for (int i = 0; i < 4000; ++i) {
            const Vec2 raster{rng.next_float() * w, rng.next_float() * h};
            const Vec2 u = rand2(rng);
            Ray ray = cam.generate_ray(raster, u);
            Vec2 back;
            ASSERT_TRUE(cam.raster_of(ray, &back)) << c.name << " raster " << raster.x << ", " << raster.y;
            worst = std::max({worst, double(std::fabs(back.x - raster.x)), double(std::fabs(back.y - raster.y))});
            // The origin may be anywhere on the ray's line.
            ray.o = ray.o + ray.d * 0.73f;
            ASSERT_TRUE(cam.raster_of(ray, &back));
            worst = std::max({worst, double(std::fabs(back.x - raster.x)), double(std::fabs(back.y - raster.y))});
        }
        // Float rounding of coordinates of ~10² pixels is ~1e-5 pixel; a modelling slip (a shift, a fit, the
        // aspect, the lens) moves rasters by a good fraction of the frame.
        EXPECT_LT(worst, 1e-3) << c.name;
        // Outside the frame, or pointing backwards: no raster.
        Vec2 back;
        EXPECT_FALSE(cam.raster_of(cam.generate_ray({-0.5f, 0.5f * h}), &back)) << c.name;
        EXPECT_FALSE(cam.raster_of(cam.generate_ray({0.5f * w, h + 0.5f}), &back)) << c.name;
        Ray rev = cam.generate_ray({0.5f * w, 0.5f * h});
        rev.d = -rev.d;
        EXPECT_FALSE(cam.raster_of(rev, &back)) << c.name;
    }
}

TEST(CameraImportance, RasterOfIsIndependentOfTheBorder) {
    for (const CameraCase& c : camera_cases()) {
        Params cropped = c.params;
        cropped.set("crop_x0", int64_t(5));
        cropped.set("crop_y0", int64_t(7));
        cropped.set("crop_x1", int64_t(20));
        cropped.set("crop_y1", int64_t(30));
        const Camera full(c.params, c.to_world), border(cropped, c.to_world);
        Pcg32 rng(3, 3);
        for (int i = 0; i < 200; ++i) {
            const Vec2 raster{rng.next_float() * full.full_width(), rng.next_float() * full.full_height()};
            const Vec2 u = rand2(rng);
            const Ray a = full.generate_ray(raster, u), b = border.generate_ray(raster, u);
            Vec2 ra, rb;
            ASSERT_TRUE(full.raster_of(a, &ra));
            ASSERT_TRUE(border.raster_of(b, &rb));
            EXPECT_EQ(ra.x, rb.x) << c.name;
            EXPECT_EQ(ra.y, rb.y) << c.name;
        }
    }
}

TEST(CameraImportance, ConnectionIsTheGeneratedRayThroughTheReferencePoint) {
    for (const CameraCase& c : connectable_cases()) {
        const Camera cam(c.params, c.to_world);
        Pcg32 rng(11, 2);
        const float w = float(cam.full_width()), h = float(cam.full_height());
        int found = 0, missed = 0;
        for (int i = 0; i < 4000; ++i) {
            const Vec2 raster{(rng.next_float() * 1.4f - 0.2f) * w, (rng.next_float() * 1.4f - 0.2f) * h};
            const float depth = 0.5f + 7.f * rng.next_float();  // clip range [1, 6]
            const Vec3 ref = point_at_depth(cam, raster, rand2(rng), depth);
            const Vec2 u = rand2(rng);
            CameraConnection con;
            if (!cam.connect(ref, u, &con)) {
                ++missed;
                continue;
            }
            ++found;
            EXPECT_GE(depth, 1.f - 1e-4f) << c.name;
            EXPECT_LE(depth, 6.f + 1e-4f) << c.name;
            EXPECT_TRUE(con.raster.x >= 0.f && con.raster.x <= w && con.raster.y >= 0.f && con.raster.y <= h);
            const Ray ray = cam.generate_ray(con.raster, u);
            const float tol = 2e-5f * (1.f + con.dist);
            ASSERT_LT(length(ray.o - con.lens_point), tol) << c.name;
            ASSERT_LT(length(ray.d + con.wi), 2e-5f) << c.name;
            ASSERT_NEAR(length(con.lens_point - ref), con.dist, tol) << c.name;
            ASSERT_LT(length(ray.o + ray.d * con.dist - ref), tol) << c.name;
            EXPECT_GE(con.dist, ray.tmin * (1.f - 1e-4f) - 1e-5f) << c.name;
            EXPECT_LE(con.dist, ray.tmax * (1.f + 1e-4f)) << c.name;
            // pdf_we of that ray gives the connection's densities (BDPT's MIS uses both).
            float pdf_pos, pdf_dir;
            cam.pdf_we(ray, &pdf_pos, &pdf_dir);
            EXPECT_NEAR(pdf_pos, con.pdf_pos, 1e-4f * con.pdf_pos) << c.name;
            EXPECT_NEAR(pdf_dir, con.pdf_dir, 1e-3f * con.pdf_dir) << c.name;
            EXPECT_EQ(con.delta_pos, cam.delta_position()) << c.name;
            EXPECT_GT(con.importance, 0.f);
        }
        EXPECT_GT(found, 1000) << c.name;
        EXPECT_GT(missed, 500) << c.name;
    }
}

TEST(CameraImportance, ClipPlanesBoundConnections) {
    for (const CameraCase& c : connectable_cases()) {
        const Camera cam(c.params, c.to_world);  // clip range [1, 6]
        const Vec2 centre{0.5f * cam.full_width(), 0.5f * cam.full_height()};
        // Points on the ray of the frame's centre for lens sample u: in the frame for that lens point.
        for (Vec2 u : {Vec2{0.5f, 0.5f}, Vec2{0.1f, 0.8f}, Vec2{0.95f, 0.3f}}) {
            auto at = [&](float depth) { return point_at_depth(cam, centre, u, depth); };
            CameraConnection con;
            EXPECT_FALSE(cam.connect(at(0.98f), u, &con)) << c.name << ": nearer than clip_start";
            EXPECT_TRUE(cam.connect(at(1.02f), u, &con)) << c.name;
            EXPECT_TRUE(cam.connect(at(5.98f), u, &con)) << c.name;
            EXPECT_FALSE(cam.connect(at(6.02f), u, &con)) << c.name << ": beyond clip_end";
            EXPECT_FALSE(cam.connect(at(-2.f), u, &con)) << c.name << ": behind the camera";
        }
    }
}

TEST(CameraImportance, OrthographicPinholeIsNotConnectable) {
    const std::vector<CameraCase> cases = camera_cases();
    const Camera ortho(case_named(cases, "ortho").params, Affine());
    EXPECT_FALSE(ortho.connectable());
    CameraConnection con;
    EXPECT_FALSE(ortho.connect({0.f, 0.f, -3.f}, {0.5f, 0.5f}, &con));
    EXPECT_NE(ortho.not_connectable_message().find("use PATH or enable depth of field"), std::string::npos);
    float pdf_pos, pdf_dir;
    ortho.pdf_we(ortho.generate_ray({10.f, 10.f}), &pdf_pos, &pdf_dir);
    EXPECT_EQ(pdf_dir, 0.f);  // a delta direction has no density
    for (const char* name : {"perspective", "thin_lens", "ortho_dof"}) {
        const Camera cam(case_named(cases, name).params, Affine());
        EXPECT_TRUE(cam.connectable()) << name;
        EXPECT_TRUE(cam.not_connectable_message().empty()) << name;
        EXPECT_TRUE(cam.connect({0.f, 0.f, -3.f}, {0.5f, 0.5f}, &con)) << name;
    }
}

TEST(CameraImportance, ImagePlaneAndLensAreas) {
    // 36 mm sensor, 50 mm lens, 64 × 48: the frame at z = −1 is 0.72 × 0.54.
    const std::vector<CameraCase> cases = camera_cases();
    EXPECT_NEAR(Camera(case_named(cases, "perspective").params, Affine()).image_plane_area(), 0.72f * 0.54f, 1e-6f);
    EXPECT_NEAR(Camera(case_named(cases, "ortho").params, Affine()).image_plane_area(), 4.f * 2.5f, 1e-5f);
    EXPECT_EQ(Camera(case_named(cases, "perspective").params, Affine()).lens_area(), 0.f);
    // Disk: πr²/ratio; polygon: its corners' shoelace area.
    Aperture disk;
    disk.radius = 0.3f;
    disk.inv_ratio = 1.f / 1.7f;
    EXPECT_NEAR(disk.area(), k_pi * 0.09f / 1.7f, 1e-6f);
    for (int blades : {3, 5, 6, 9}) {
        Aperture poly = disk;
        poly.blades = blades;
        poly.rotation = 0.4f;
        double shoelace = 0.0;
        for (int k = 0; k < blades; ++k) {
            const double a0 = poly.rotation + (2.0 * k + 1.0) * M_PI / blades, a1 = a0 + 2.0 * M_PI / blades;
            const double x0 = poly.radius * poly.inv_ratio * std::cos(a0), y0 = poly.radius * std::sin(a0);
            const double x1 = poly.radius * poly.inv_ratio * std::cos(a1), y1 = poly.radius * std::sin(a1);
            shoelace += 0.5 * (x0 * y1 - x1 * y0);
        }
        EXPECT_NEAR(poly.area(), shoelace, 1e-6 * shoelace) << blades;
    }
}

TEST(CameraImportance, ApertureContainsExactlyWhatItSamples) {
    // Every sample is inside; and the fraction of a bounding box inside is area()/box (binomial σ, z ≤ 4.5).
    for (int blades : {0, 3, 5, 6}) {
        Aperture ap;
        ap.radius = 0.4f;
        ap.blades = blades;
        ap.rotation = 0.25f;
        ap.inv_ratio = 1.f / 0.6f;
        Pcg32 rng(5, uint64_t(blades));
        for (int i = 0; i < 100000; ++i) ASSERT_TRUE(ap.contains(ap.sample(rand2(rng)))) << blades;
        const float bx = ap.radius * ap.inv_ratio, by = ap.radius;
        constexpr int n = 400000;
        int inside = 0;
        for (int i = 0; i < n; ++i)
            inside += ap.contains({(2.f * rng.next_float() - 1.f) * bx, (2.f * rng.next_float() - 1.f) * by});
        const double p = ap.area() / (4.0 * bx * by);
        EXPECT_LE(std::fabs(inside - n * p), k_z_max * std::sqrt(n * p * (1.0 - p))) << blades;
    }
}

}  // namespace
}  // namespace candela::test
