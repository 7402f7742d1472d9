// Depth of field: Cycles 3.4's thin-lens camera (scene/camera.h, scene/aperture.h) against its analytic
// geometry. With the aperture point L (camera space, z = 0), the focus distance f and a pinhole ray of direction
// (t_x, t_y, −1), the ray runs from L through t·f on the plane of focus. Where it crosses depth z, its pinhole
// projection is t − L·(1/f − 1/z): every lens point shifts the pinhole image by L·(1/f − 1/z). Hence
//   - points on the plane of focus (z = f) stay sharp: every lens point reaches the same point;
//   - a point at depth z blurs into the aperture's shape scaled by (1/f − 1/z) — a disk of radius
//     R = a·|1/f − 1/z| in tan units, a·|1/f − 1/z|·lens·W/sensor pixels (a = lens·1e-3/(2·f-stop));
//   - the blur is a translation per lens point, so the image's total flux is unchanged and its second
//     moment grows by the aperture's: R²/2 for a disk, Var(render) = Var(pinhole) + R²/2.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scene/camera.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr int k_grid = 128;  // lens samples: the midpoints of a k_grid² grid (deterministic quadrature)

Params dof_params(int w, int h, float fstop, float focus) {
    Params p;
    p.set("width", int64_t(w));
    p.set("height", int64_t(h));
    p.set("use_dof", true);
    p.set("aperture_fstop", double(fstop));
    p.set("focus_distance", double(focus));
    return p;
}

Vec2 grid_u(int i, int j) { return {(i + 0.5f) / k_grid, (j + 0.5f) / k_grid}; }

/// Where the ray crosses the camera-space plane z = −depth.
Vec3 at_depth(const Ray& r, float depth) { return r.o + r.d * ((-depth - r.o.z) / r.d.z); }

TEST(Dof, ApertureRadiusIsCyclesLensOverTwoFStop) {
    const Camera persp(dof_params(64, 48, 2.f, 5.f), Affine());
    EXPECT_FLOAT_EQ(persp.aperture().radius, 50e-3f / 4.f);  // lens 50 mm
    Params p = dof_params(64, 48, 2.f, 5.f);
    p.set("camera_type", std::string("ORTHO"));
    const Camera ortho(p, Affine());
    EXPECT_FLOAT_EQ(ortho.aperture().radius, 1.f / 4.f);
    Params off = dof_params(64, 48, 2.f, 5.f);
    off.set("use_dof", false);
    EXPECT_FALSE(Camera(off, Affine()).has_aperture());
    Params bad = dof_params(64, 48, 0.f, 5.f);
    EXPECT_THROW(Camera(bad, Affine()), InvalidParameter);
}

TEST(Dof, PointsOnThePlaneOfFocusStaySharp) {
    const float focus = 3.f;
    const Camera cam(dof_params(64, 48, 0.1f, focus), Affine());  // a 25 cm aperture radius: very shallow
    for (Vec2 raster : {Vec2{32.f, 24.f}, Vec2{3.5f, 40.25f}, Vec2{60.f, 2.f}}) {
        const Vec3 sharp = at_depth(cam.generate_ray(raster, {0.5f, 0.5f}), focus);
        for (int i = 0; i < k_grid; i += 9)
            for (int j = 0; j < k_grid; j += 7) {
                const Ray r = cam.generate_ray(raster, grid_u(i, j));
                EXPECT_NEAR(length(at_depth(r, focus) - sharp), 0.f, 1e-5f * focus);
                EXPECT_NEAR(length(r.d), 1.f, 1e-5f);
            }
    }
}

/// Pixel offsets (pinhole projection at `depth` minus the raster position) of the rays through `raster` for
/// every lens sample of the grid.
std::vector<Vec2> blur_offsets(const Camera& cam, Vec2 raster, float depth, float px_per_tan) {
    const Ray centre = cam.generate_ray(raster, {0.5f, 0.5f});
    const Vec3 c = at_depth(centre, depth);
    std::vector<Vec2> out;
    for (int i = 0; i < k_grid; ++i)
        for (int j = 0; j < k_grid; ++j) {
            const Vec3 p = at_depth(cam.generate_ray(raster, grid_u(i, j)), depth);
            out.push_back({(p.x - c.x) / depth * px_per_tan, (p.y - c.y) / depth * px_per_tan});
        }
    return out;
}

TEST(Dof, OutOfFocusDepthsBlurToTheCircleOfConfusion) {
    const int w = 64;
    const float fstop = 0.1f, focus = 2.f, depth = 5.f;
    const Camera cam(dof_params(w, 48, fstop, focus), Affine());
    const float px_per_tan = 50.f * w / 36.f;  // horizontal fit: lens / sensor width per pixel column
    const float a = 50e-3f / (2.f * fstop);
    const float R = a * std::fabs(1.f / focus - 1.f / depth) * px_per_tan;  // 6.67 px
    const std::vector<Vec2> d = blur_offsets(cam, {20.f, 30.f}, depth, px_per_tan);
    double max_r = 0.0, mean_r2 = 0.0;
    for (const Vec2& v : d) {
        const double r2 = double(v.x) * v.x + double(v.y) * v.y;
        max_r = std::max(max_r, std::sqrt(r2));
        mean_r2 += r2 / d.size();
    }
    // The grid's outermost midpoints sit 1/k_grid inside the rim; the midpoint rule on the (area-preserving,
    // piecewise smooth) concentric map is accurate to O(1/k_grid) here, far below the 2 % allowed, while the
    // usual slips (diameter for radius: ×4 in r², a missing mm→m: ×10⁶) are far outside it.
    EXPECT_LE(max_r, R * (1.0 + 1e-4));
    EXPECT_GE(max_r, R * (1.0 - 2.0 / k_grid));
    EXPECT_NEAR(mean_r2, 0.5 * R * R, 0.02 * 0.5 * R * R);
}

TEST(Dof, BladesGiveARegularPolygon) {
    Aperture ap;
    ap.radius = 1.f;
    ap.blades = 6;
    ap.rotation = 0.3f;
    const float n = 6.f, apothem = std::cos(k_pi / n);
    double mean_r2 = 0.0;
    std::vector<float> support_vertex(6, -1.f), support_edge(6, -1.f);
    for (int i = 0; i < k_grid; ++i)
        for (int j = 0; j < k_grid; ++j) {
            const Vec2 p = ap.sample(grid_u(i, j));
            mean_r2 += (double(p.x) * p.x + double(p.y) * p.y) / (k_grid * k_grid);
            for (int k = 0; k < 6; ++k) {
                const float av = ap.rotation + (2.f * k + 1.f) * k_pi / n;  // corner k (Cycles' orientation)
                const float ae = ap.rotation + 2.f * k * k_pi / n;          // middle of edge k
                support_vertex[k] = std::max(support_vertex[k], p.x * std::cos(av) + p.y * std::sin(av));
                support_edge[k] = std::max(support_edge[k], p.x * std::cos(ae) + p.y * std::sin(ae));
            }
        }
    for (int k = 0; k < 6; ++k) {
        EXPECT_LE(support_edge[k], apothem + 1e-5f) << "edge " << k;  // nothing outside the hexagon
        EXPECT_GE(support_edge[k], apothem * (1.f - 2.f / k_grid)) << "edge " << k;
        EXPECT_GE(support_vertex[k], 1.f - 4.f / k_grid) << "corner " << k;  // the corners are reached
    }
    // Uniform by area: a triangle (0, A, B) has ∫|x|²/area = (|A|² + |B|² + A·B)/6, so the polygon's mean r² is
    // (2 + cos(2π/n))/6 = 0.41667 for n = 6 (a disk: 0.5).
    EXPECT_NEAR(mean_r2, (2.0 + std::cos(2.0 * k_pi / n)) / 6.0, 0.01 * 0.41667);
}

TEST(Dof, RatioSqueezesTheApertureHorizontally) {
    Aperture ap;
    ap.radius = 2.f;
    ap.inv_ratio = 1.f / 2.f;  // aperture_ratio 2
    float max_x = 0.f, max_y = 0.f;
    for (int i = 0; i < k_grid; ++i)
        for (int j = 0; j < k_grid; ++j) {
            const Vec2 p = ap.sample(grid_u(i, j));
            max_x = std::max(max_x, std::fabs(p.x));
            max_y = std::max(max_y, std::fabs(p.y));
        }
    EXPECT_NEAR(max_x, 1.f, 0.02f);
    EXPECT_NEAR(max_y, 2.f, 0.04f);
}

TEST(Dof, OrthographicRaysMeetFocusDistanceBeyondTheNearClip) {
    Params p = dof_params(64, 32, 0.5f, 2.f);  // aperture radius 1/(2·0.5) = 1
    p.set("camera_type", std::string("ORTHO"));
    p.set("clip_start", 0.5);
    const Camera cam(p, Affine());
    const Ray pin = cam.generate_ray({10.f, 20.f}, {0.5f, 0.5f});
    const Vec3 focus_point = at_depth(pin, 2.5f);
    for (int i = 0; i < k_grid; i += 11)
        for (int j = 0; j < k_grid; j += 13) {
            const Ray r = cam.generate_ray({10.f, 20.f}, grid_u(i, j));
            EXPECT_NEAR(length(at_depth(r, 2.5f) - focus_point), 0.f, 1e-5f);
            EXPECT_NEAR(r.o.z, -0.5f, 1e-6f);
        }
}

/// Flux and second moment (about the frame centre, in pixels²) of a render's luminance, and the standard error
/// of the moment by the delta method from the per-pixel standard errors (the Noise pass).
struct Moments {
    double flux = 0.0, flux_se = 0.0, r2 = 0.0, r2_se = 0.0;
};

Moments image_moments(const std::vector<float>& rgba, const std::vector<float>& noise, int w, int h) {
    Moments m;
    double var_flux = 0.0;
    std::vector<double> lum(size_t(w) * h), rr(lum.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            lum[i] = luminance(Color(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]));
            const double dx = x + 0.5 - 0.5 * w, dy = y + 0.5 - 0.5 * h;
            rr[i] = dx * dx + dy * dy;
            m.flux += lum[i];
            m.r2 += rr[i] * lum[i];
            var_flux += double(noise[i]) * noise[i];
        }
    m.r2 /= m.flux;
    // M = Σ r²·I / Σ I ⇒ δM = Σ (r² − M)·δI / Σ I (pixels independent).
    double var_r2 = 0.0;
    for (size_t i = 0; i < lum.size(); ++i) var_r2 += (rr[i] - m.r2) * (rr[i] - m.r2) * double(noise[i]) * noise[i];
    m.r2_se = std::sqrt(var_r2) / m.flux;
    m.flux_se = std::sqrt(var_flux);
    return m;
}

Moments render_point_emitter(bool dof) {
    // A small emissive square on the optical axis, 5 m away; nothing else, black world, box filter.
    MeshBuilder b;
    const uint32_t lamp = b.add_material(Color(0.f), Color(1.f));
    b.add_instance(b.add_quad_z(-0.05f, 0.05f, -0.05f, 0.05f, -5.f, lamp));
    Params p = basic_params(48, 48, 1024, 0);
    p.set("use_dof", dof);
    p.set("aperture_fstop", 0.05);
    p.set("focus_distance", 2.0);
    Session s(b.arrays(), std::move(p));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    int ch = 0;
    return image_moments(s.get_pass("Combined", &ch), s.get_pass("Noise", &ch), 48, 48);
}

TEST(Dof, RenderedBokehHasTheCircleOfConfusionsSecondMoment) {
    const Moments sharp = render_point_emitter(false), blurred = render_point_emitter(true);
    // Square 48×48 frame, sensor 36 mm spans the width: lens·W/sensor pixels per tan unit.
    const double px_per_tan = 50.0 * 48 / 36.0;
    const double R = (50e-3 / (2 * 0.05)) * std::fabs(1.0 / 2.0 - 1.0 / 5.0) * px_per_tan;  // 10 px
    const double expected = sharp.r2 + 0.5 * R * R;
    // Tolerances: 4 standard errors of each estimate (Sobol strata make the per-pixel errors an overestimate).
    EXPECT_NEAR(blurred.flux, sharp.flux, 4.0 * std::hypot(blurred.flux_se, sharp.flux_se));
    EXPECT_NEAR(blurred.r2, expected, 4.0 * std::hypot(blurred.r2_se, sharp.r2_se)) << "R = " << R << " px";
}

}  // namespace
}  // namespace candela::test
