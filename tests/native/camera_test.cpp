// Camera conventions of Cycles 3.4 (docs/conventions.md §4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "scene/camera.h"

namespace candela {
namespace {

Params camera_params(int w, int h) {
    Params p;
    p.set("width", int64_t(w));
    p.set("height", int64_t(h));
    return p;
}

TEST(Camera, CentreRayLooksDownMinusZ) {
    const Camera cam(camera_params(64, 48), Affine());
    const Ray r = cam.generate_ray({32.f, 24.f});
    EXPECT_NEAR(r.d.x, 0.f, 1e-6f);
    EXPECT_NEAR(r.d.y, 0.f, 1e-6f);
    EXPECT_NEAR(r.d.z, -1.f, 1e-6f);
}

TEST(Camera, HorizontalFitSpansSensorWidth) {
    // AUTO fit of a landscape frame: the 36 mm sensor spans the width; lens 50 → tan(half fov) = 18/50.
    const Camera cam(camera_params(64, 48), Affine());
    const Ray r = cam.generate_ray({64.f, 24.f});
    EXPECT_NEAR(r.d.x / -r.d.z, 18.f / 50.f, 1e-5f);
    const Ray top = cam.generate_ray({32.f, 48.f});  // y is up: raster row 48 is the top edge
    EXPECT_NEAR(top.d.y / -top.d.z, 18.f / 50.f * 48.f / 64.f, 1e-5f);
}

TEST(Camera, VerticalFitSpansSensorHeight) {
    Params p = camera_params(48, 64);
    p.set("sensor_fit", std::string("VERTICAL"));
    p.set("sensor_height", 24.0);
    const Camera cam(p, Affine());
    const Ray r = cam.generate_ray({24.f, 64.f});
    EXPECT_NEAR(r.d.y / -r.d.z, 12.f / 50.f, 1e-5f);
}

TEST(Camera, ShiftMovesTheViewplaneByAFractionOfTheFittedSize) {
    Params p = camera_params(64, 48);
    p.set("shift_x", 0.5);
    const Camera cam(p, Affine());
    const Ray r = cam.generate_ray({32.f, 24.f});  // the centre now looks at the old right edge
    EXPECT_NEAR(r.d.x / -r.d.z, 18.f / 50.f, 1e-5f);
}

TEST(Camera, OrthographicSpansOrthoScale) {
    Params p = camera_params(64, 32);
    p.set("camera_type", std::string("ORTHO"));
    p.set("ortho_scale", 4.0);
    const Camera cam(p, Affine());
    const Ray left = cam.generate_ray({0.f, 16.f}), right = cam.generate_ray({64.f, 16.f});
    EXPECT_NEAR(right.o.x - left.o.x, 4.f, 1e-5f);
    const Ray top = cam.generate_ray({32.f, 32.f});
    EXPECT_NEAR(top.o.y, 1.f, 1e-5f);
    EXPECT_NEAR(left.d.z, -1.f, 1e-6f);
}

TEST(Camera, ClipDistancesAreAlongTheViewAxis) {
    Params p = camera_params(64, 48);
    p.set("clip_start", 2.0);
    p.set("clip_end", 10.0);
    const Camera cam(p, Affine());
    const Ray r = cam.generate_ray({64.f, 24.f});
    EXPECT_NEAR(r.tmin * -r.d.z, 2.f, 1e-5f);
    EXPECT_NEAR(r.tmax * -r.d.z, 10.f, 1e-4f);
}

TEST(Camera, RejectsEmptyResolution) { EXPECT_THROW(Camera(camera_params(0, 10), Affine()), InvalidParameter); }

// ---- the 3D viewport's zoom and pan (Cycles' blender_camera_from_view) ----------------------------------------

TEST(Camera, ViewZoomScalesTheViewplane) {
    Params p = camera_params(64, 48);
    p.set("view_zoom", 2.0);
    const Camera cam(p, Affine());
    const Ray r = cam.generate_ray({64.f, 24.f});
    EXPECT_NEAR(r.d.x / -r.d.z, 2.f * 18.f / 50.f, 1e-5f);
}

TEST(Camera, ViewOffsetPansByAFractionOfTheViewplane) {
    // offset 0.25 moves the viewplane by 2·(0.25·xaspect·2) = xaspect: the centre sees the old right edge.
    Params p = camera_params(64, 48);
    p.set("view_offset_x", 0.25);
    const Camera cam(p, Affine());
    const Ray r = cam.generate_ray({32.f, 24.f});
    EXPECT_NEAR(r.d.x / -r.d.z, 18.f / 50.f, 1e-5f);
    EXPECT_NEAR(r.d.y, 0.f, 1e-6f);
}

TEST(Camera, OrthographicViewStartsBehindTheView) {
    Params p = camera_params(64, 32);
    p.set("camera_type", std::string("ORTHO"));
    p.set("clip_start", -50.0);
    p.set("clip_end", 100.0);
    const Camera cam(p, Affine());
    const Ray r = cam.generate_ray({32.f, 16.f});
    EXPECT_NEAR(r.o.z, 50.f, 1e-4f);
    EXPECT_NEAR(r.tmax, 150.f, 1e-3f);
    Params persp = camera_params(64, 32);
    persp.set("clip_start", -1.0);
    EXPECT_THROW(Camera(persp, Affine()), InvalidParameter);  // only an orthographic view may
}

// ---- panoramic cameras (Cycles 3.4 kernel/camera/projection.h) ----------------------------------------------

Params pano_params(int w, int h, const char* kind) {
    Params p = camera_params(w, h);
    p.set("camera_type", std::string("PANO"));
    p.set("panorama_type", std::string(kind));
    return p;
}

/// Angle in radians between unit vectors.
float angle_between(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(dot(a, b), -1.f, 1.f)); }

TEST(Camera, EquirectangularCoversTheSphere) {
    const Camera cam(pano_params(64, 32, "EQUIRECTANGULAR"), Affine());
    EXPECT_TRUE(cam.is_panoramic());
    // Centre: straight ahead (−z); three quarters across: 90° to the right (+x); top row: up; bottom: down;
    // the left and right edges: behind.
    EXPECT_LT(angle_between(cam.generate_ray({32.f, 16.f}).d, Vec3(0.f, 0.f, -1.f)), 1e-5f);
    EXPECT_LT(angle_between(cam.generate_ray({48.f, 16.f}).d, Vec3(1.f, 0.f, 0.f)), 1e-5f);
    EXPECT_LT(angle_between(cam.generate_ray({16.f, 16.f}).d, Vec3(-1.f, 0.f, 0.f)), 1e-5f);
    EXPECT_LT(angle_between(cam.generate_ray({32.f, 32.f}).d, Vec3(0.f, 1.f, 0.f)), 1e-3f);
    EXPECT_LT(angle_between(cam.generate_ray({32.f, 0.f}).d, Vec3(0.f, -1.f, 0.f)), 1e-3f);
    EXPECT_LT(angle_between(cam.generate_ray({0.f, 16.f}).d, Vec3(0.f, 0.f, 1.f)), 1e-5f);
    // A row at latitude 45° up: the fraction (lat − lat_min) / (lat_max − lat_min) = 0.75 of the height.
    const Ray r = cam.generate_ray({32.f, 24.f});
    EXPECT_NEAR(std::asin(r.d.y), 0.25f * k_pi, 1e-5f);
}

TEST(Camera, EquirectangularHonoursTheLatitudeAndLongitudeRange) {
    Params p = pano_params(40, 20, "EQUIRECTANGULAR");
    p.set("longitude_min", -0.5 * 3.14159265358979);
    p.set("longitude_max", 0.5 * 3.14159265358979);
    p.set("latitude_min", -0.25 * 3.14159265358979);
    p.set("latitude_max", 0.25 * 3.14159265358979);
    const Camera cam(p, Affine());
    EXPECT_LT(angle_between(cam.generate_ray({40.f, 10.f}).d, Vec3(1.f, 0.f, 0.f)), 1e-5f);  // right edge: +90°
    EXPECT_NEAR(std::asin(cam.generate_ray({20.f, 20.f}).d.y), 0.25f * k_pi, 1e-5f);         // top: +45°
}

TEST(Camera, FisheyeEquidistantAngleGrowsLinearlyWithRadius) {
    Params p = pano_params(64, 64, "FISHEYE_EQUIDISTANT");
    p.set("fisheye_fov", 3.14159265358979);  // 180°
    const Camera cam(p, Affine());
    for (float f : {0.f, 0.25f, 0.5f, 0.9f}) {
        // A point at radius f of the inscribed circle, to the right and then upward: θ = f · 90°.
        const Ray right = cam.generate_ray({32.f + 32.f * f, 32.f});
        EXPECT_NEAR(angle_between(right.d, Vec3(0.f, 0.f, -1.f)), f * 0.5f * k_pi, 1e-4f);
        EXPECT_GE(right.d.x, 0.f);
        const Ray up = cam.generate_ray({32.f, 32.f + 32.f * f});
        EXPECT_NEAR(angle_between(up.d, Vec3(0.f, 0.f, -1.f)), f * 0.5f * k_pi, 1e-4f);
        EXPECT_GE(up.d.y, 0.f);
    }
    const Ray corner = cam.generate_ray({1.f, 1.f});  // outside the circle: an empty ray
    EXPECT_FALSE(corner.tmax > corner.tmin);
}

TEST(Camera, FisheyeEquisolidFollowsTheLensFormula) {
    // r = 2·f·sin(θ/2) on the sensor: θ = 60° at r = f. A 36 mm wide sensor on a 64x48 frame (horizontal fit).
    Params p = pano_params(64, 48, "FISHEYE_EQUISOLID");
    p.set("fisheye_lens", 10.5);
    p.set("fisheye_fov", 3.14159265358979);
    const Camera cam(p, Affine());
    const float x = 64.f * (0.5f + 10.5f / 36.f);
    const Ray r = cam.generate_ray({x, 24.f});
    EXPECT_NEAR(angle_between(r.d, Vec3(0.f, 0.f, -1.f)), k_pi / 3.f, 1e-4f);
    // The fitted sensor height is 36·48/64 = 27 mm: the same radius upward gives the same angle.
    const Ray up = cam.generate_ray({32.f, 48.f * (0.5f + 10.5f / 27.f)});
    EXPECT_NEAR(angle_between(up.d, Vec3(0.f, 0.f, -1.f)), k_pi / 3.f, 1e-4f);
    // Beyond the field of view (r > 2·f·sin(fov/4) = 14.85 mm): empty.
    const Ray out = cam.generate_ray({64.f * (0.5f + 15.5f / 36.f), 24.f});
    EXPECT_FALSE(out.tmax > out.tmin);
}

TEST(Camera, PanoramaFollowsTheCameraTransform) {
    // Rotated 90° about x, the camera looks along +y (a Blender camera with rotation (90°, 0, 0)).
    Affine xf;
    xf.m[1][1] = 0.f;
    xf.m[1][2] = -1.f;
    xf.m[2][1] = 1.f;
    xf.m[2][2] = 0.f;
    const Camera cam(pano_params(64, 32, "EQUIRECTANGULAR"), xf);
    EXPECT_LT(angle_between(cam.generate_ray({32.f, 16.f}).d, Vec3(0.f, 1.f, 0.f)), 1e-5f);
}

TEST(Camera, PanoramaViewBoxMapsTheFrameToPartOfThePanorama) {
    Params p = pano_params(64, 32, "EQUIRECTANGULAR");
    p.set("pano_left", 0.5);  // the viewport shows the right half of the panorama
    p.set("pano_right", 1.0);
    const Camera cam(p, Affine());
    EXPECT_LT(angle_between(cam.generate_ray({0.f, 16.f}).d, Vec3(0.f, 0.f, -1.f)), 1e-5f);
    EXPECT_LT(angle_between(cam.generate_ray({32.f, 16.f}).d, Vec3(1.f, 0.f, 0.f)), 1e-5f);
}

TEST(Camera, RefusesUnsupportedPanoramas) {
    EXPECT_THROW(Camera(pano_params(16, 16, "MIRRORBALL"), Affine()), InvalidParameter);
    Params p = pano_params(16, 16, "FISHEYE_EQUIDISTANT");
    p.set("fisheye_fov", 0.0);
    EXPECT_THROW(Camera(p, Affine()), InvalidParameter);
}

}  // namespace
}  // namespace candela
