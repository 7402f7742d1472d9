// Camera conventions of Cycles 3.4 (docs/conventions.md §4).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
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

}  // namespace
}  // namespace candela
