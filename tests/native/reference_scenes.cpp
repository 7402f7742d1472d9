#include "reference_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"
#include "lights/light.h"

namespace candela::test {

std::vector<float> translation(float x, float y, float z) { return {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1}; }

uint32_t add_parallelogram(MeshBuilder& b, Vec3 o, Vec3 u, Vec3 v, uint32_t material) {
    const uint32_t base = uint32_t(b.positions.size() / 3);
    for (const Vec3& p : {o, o + u, o + u + v, o + v}) b.positions.insert(b.positions.end(), {p.x, p.y, p.z});
    b.triangles.insert(b.triangles.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    b.tri_material.insert(b.tri_material.end(), {material, material});
    b.mesh_tri_start.push_back(uint32_t(b.triangles.size() / 3));
    return uint32_t(b.mesh_tri_start.size() - 2);
}

namespace {
std::vector<float> at(float x, float y, float z) { return translation(x, y, z); }
}  // namespace

SceneArrays lit_room(unsigned lights, bool specular) {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f, 0.55f, 0.5f), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    const uint32_t mirror = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(mirror, "GLOSSY", {{"color_r", 0.9f}, {"color_g", 0.9f}, {"color_b", 0.9f}, {"roughness", 0.f}});
    const uint32_t glossy = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glossy, "GLOSSY", {{"color_r", 0.8f}, {"color_g", 0.6f}, {"color_b", 0.4f}, {"roughness", 0.35f}});
    const uint32_t lamp = b.add_material(Color(0.f), Color(4.f));
    // Floor, back wall, left wall; the room is open to the right, the top and behind the camera (a dim world).
    b.add_instance(b.add_quad_z(-2.f, 2.f, -1.5f, 1.5f, -3.f, wall));
    const std::vector<float> floor = {1, 0, 0, 0, 0, 0, 1, -1.2f, 0, -1, 0, -1.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-2.f, 2.f, -1.5f, 1.5f, 0.f, wall), floor.data());
    const std::vector<float> left = {0, 0, 1, -1.8f, 0, 1, 0, 0, -1, 0, 0, -1.5f, 0, 0, 0, 1};
    b.add_instance(b.add_quad_z(-1.5f, 1.5f, -1.5f, 1.5f, 0.f, wall), left.data());
    const std::vector<float> g = at(0.5f, -0.8f, -1.8f), s = at(-0.8f, -0.85f, -2.2f);
    if (specular) b.add_instance(b.add_sphere(0.4f, 24, 12, glass), g.data());
    b.add_instance(b.add_sphere(0.35f, 24, 12, glossy), s.data());
    const std::vector<float> m = {0.7f, 0, 0.7f, -1.3f, 0, 1, 0, 0.3f, -0.7f, 0, 0.7f, -2.5f, 0, 0, 0, 1};
    if (specular) b.add_instance(b.add_quad_z(-0.4f, 0.4f, -0.4f, 0.4f, 0.f, mirror), m.data());
    if (lights & 1) b.add_point_light(Vec3(0.6f, 0.7f, -1.6f), Color(6.f));
    if (lights & 2) b.add_point_light(Vec3(-0.5f, 0.8f, -1.4f), Color(6.f), 0.15f);
    if (lights & 4) {
        std::vector<float> spot(light_columns().size(), 0.f);
        for (int c = 0; c < 3; ++c) spot[c] = 25.f;
        spot[3] = 0.3f, spot[4] = 1.2f, spot[5] = -1.5f;
        const Vec3 d = normalize(Vec3(0.1f, -1.f, -0.2f));
        spot[6] = d.x, spot[7] = d.y, spot[8] = d.z;
        spot[16] = 1.f, spot[17] = 0.2f;
        b.add_light(1, spot);
    }
    if (lights & (8 | 16)) {
        std::vector<float> sun(light_columns().size(), 0.f);
        for (int c = 0; c < 3; ++c) sun[c] = 2.f;
        const Vec3 d = normalize(Vec3(-0.6f, -0.7f, -0.3f));
        sun[6] = d.x, sun[7] = d.y, sun[8] = d.z;
        sun[18] = (lights & 16) ? 0.2f : 0.f;
        b.add_light(2, sun);
    }
    if (lights & 32)
        b.add_area_light(Vec3(0.f, 1.2f, -1.8f), Vec3(0.7f, 0.f, 0.f), Vec3(0.f, 0.f, 0.5f), Vec3(0.f, -1.f, 0.f),
                         Color(12.f), true);
    if (lights & 64)
        b.add_area_light(Vec3(1.f, 0.3f, -2.9f), Vec3(0.5f, 0.f, 0.f), Vec3(0.f, 0.4f, 0.f), Vec3(0.f, 0.f, 1.f),
                         Color(10.f), false);
    if (lights & 128)
        b.add_instance(b.add_triangle(Vec3(-1.f, 1.f, -2.f), Vec3(-0.4f, 1.f, -2.f), Vec3(-0.7f, 1.f, -2.6f), lamp));
    if (lights & 256) b.world_color = {0.3f, 0.35f, 0.4f};
    return b.arrays();
}

SceneArrays cornell_box() {
    MeshBuilder b;
    const uint32_t white = b.add_material(Color(0.73f, 0.71f, 0.68f), Color(0.f));
    const uint32_t red = b.add_material(Color(0.63f, 0.065f, 0.05f), Color(0.f));
    const uint32_t green = b.add_material(Color(0.14f, 0.45f, 0.091f), Color(0.f));
    const uint32_t lamp = b.add_material(Color(0.f), Color(17.f, 12.f, 4.f));
    // The box spans x, y ∈ [−1, 1], z ∈ [−4, −2]; the camera at the origin sees it through its open side.
    const Vec3 X(2.f, 0.f, 0.f), Y(0.f, 2.f, 0.f), Z(0.f, 0.f, 2.f);
    b.add_instance(add_parallelogram(b, Vec3(-1.f, -1.f, -4.f), Z, X, white));  // floor, facing +y
    b.add_instance(add_parallelogram(b, Vec3(-1.f, 1.f, -4.f), X, Z, white));   // ceiling, facing −y
    b.add_instance(add_parallelogram(b, Vec3(-1.f, -1.f, -4.f), X, Y, white));  // back wall, facing +z
    b.add_instance(add_parallelogram(b, Vec3(-1.f, -1.f, -4.f), Y, Z, red));    // left wall, facing +x
    b.add_instance(add_parallelogram(b, Vec3(1.f, -1.f, -4.f), Z, Y, green));   // right wall, facing −x
    b.add_instance(add_parallelogram(b, Vec3(-0.25f, 0.98f, -3.25f), Vec3(0.5f, 0.f, 0.f), Vec3(0.f, 0.f, 0.5f), lamp));
    const float c = std::cos(0.3f), s = std::sin(0.3f);
    const std::vector<float> tall = {c, 0, s, -0.35f, 0, 1, 0, -0.4f, -s, 0, c, -3.3f, 0, 0, 0, 1};
    const std::vector<float> short_box = {c, 0, -s, 0.35f, 0, 1, 0, -0.7f, s, 0, c, -2.7f, 0, 0, 0, 1};
    b.add_instance(b.add_box(Vec3(0.3f, 0.6f, 0.3f), white), tall.data());
    b.add_instance(b.add_box(Vec3(0.3f, 0.3f, 0.3f), white), short_box.data());
    return b.arrays();
}

SceneArrays glass_caustic() {
    MeshBuilder b;
    const uint32_t floor = b.add_material(Color(0.7f, 0.7f, 0.65f), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    b.add_instance(add_parallelogram(b, Vec3(-2.f, -1.f, -5.f), Vec3(0.f, 0.f, 4.f), Vec3(4.f, 0.f, 0.f), floor));
    b.add_instance(add_parallelogram(b, Vec3(-2.f, -1.f, -5.f), Vec3(4.f, 0.f, 0.f), Vec3(0.f, 3.f, 0.f), floor));
    const std::vector<float> g = at(0.f, -0.5f, -3.f);
    b.add_instance(b.add_sphere(0.5f, 32, 16, glass), g.data());
    b.add_area_light(Vec3(0.3f, 1.2f, -3.2f), Vec3(0.3f, 0.f, 0.f), Vec3(0.f, 0.f, 0.3f), Vec3(0.f, -1.f, 0.f),
                     Color(30.f), /*disk=*/true);
    return b.arrays();
}

SceneArrays glass_slab() {
    MeshBuilder b;
    const uint32_t floor = b.add_material(Color(k_slab_albedo), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    b.add_instance(b.add_quad_z(-1.5f, 1.5f, -1.5f, 1.5f, -2.f, floor));
    const std::vector<float> at = translation(0.f, 0.f, 0.55f);
    b.add_instance(b.add_box(Vec3(1.6f, 1.6f, 0.05f), glass), at.data());
    std::vector<float> sun(light_columns().size(), 0.f);
    for (int c = 0; c < 3; ++c) sun[c] = 1.f;
    sun[8] = -1.f;  // direction (0, 0, −1)
    b.add_light(2, sun);
    return b.arrays();
}

double slab_expected() { return double(k_slab_albedo) * k_slab_transmittance / k_pi; }

SceneArrays smooth_lowpoly_sphere() {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    const uint32_t mesh = b.add_sphere(1.f, 8, 6, m);
    b.add_instance(mesh);
    b.add_point_light(Vec3(0.2f, 0.1f, 0.3f), Color(20.f));
    SceneArrays a = b.arrays();
    const size_t T = b.triangles.size() / 3;
    std::vector<float> normals;
    std::vector<uint8_t> smooth(T, 1);
    for (size_t t = 0; t < T; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = b.triangles[3 * t + k];
            const Vec3 p(b.positions[3 * v], b.positions[3 * v + 1], b.positions[3 * v + 2]);
            const Vec3 n = normalize(p);
            normals.insert(normals.end(), {n.x, n.y, n.z});
        }
    a.set("normals", ElemType::F32, {T, 3, 3}, normals.data());
    a.set("tri_smooth", ElemType::U8, {T}, smooth.data());
    return a;
}

/// Row-major 4×4 from Mitsuba's 3×4 toWorld rows.
namespace {
std::array<float, 16> rows(std::array<float, 12> m) {
    return {m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11], 0, 0, 0, 1};
}
}  // namespace

SceneArrays veach_scene(std::vector<float>* camera) {
    constexpr int k_plates = 4;
    MeshBuilder b;
    const float alphas[k_plates] = {0.01f, 0.05f, 0.1f, 0.25f};
    const std::array<float, 12> plate_rows[k_plates] = {
        {0.805757f, 0.0961775f, 0, 0.264069f, -0.673242f, 0.115108f, 0, 4.09801f, 0, 0, 4, 0},
        {0.972057f, 0.0567134f, 0, 3.06163f, -0.396994f, 0.138865f, 0, 2.71702f, 0, 0, 4, 0},
        {1.03191f, 0.0277252f, 0, 7.09981f, -0.194077f, 0.147415f, 0, 1.81891f, 0, 0, 4, 0},
        {1.04217f, 0.0182831f, 0, 10.6769f, -0.127982f, 0.148882f, 0, 1.23376f, 0, 0, 4, 0}};
    for (int i = 0; i < k_plates; ++i) {
        const uint32_t m = b.add_material(Color(0.f), Color(0.f));
        // Cycles' Glossy BSDF: α = roughness²; distribution 1 = Beckmann.
        b.add_closure(m, "GLOSSY",
                      {{"color_r", 0.3f},
                       {"color_g", 0.3f},
                       {"color_b", 0.3f},
                       {"roughness", std::sqrt(alphas[i])},
                       {"distribution", 1.f}});
        const auto t = rows(plate_rows[i]);
        b.add_instance(b.add_box(Vec3(1.f), m), t.data());
    }
    const uint32_t backdrop = b.add_material(Color(0.5f), Color(0.f));
    const auto floor = rows({9.9f, 0, 0, 4.9f, 0, -4.32743e-7f, 9.9f, 0, 0, -23.76f, -1.03858e-6f, 0});
    const auto wall = rows(
        {-4.32743e-7f, -4.32743e-7f, 9.9f, -5, -9.9f, 1.89158e-14f, -4.32743e-7f, 9.9f, 0, -23.76f, -1.03858e-6f, 0});
    b.add_instance(b.add_quad_z(-1.f, 1.f, -1.f, 1.f, 0.f, backdrop), floor.data());
    b.add_instance(b.add_quad_z(-1.f, 1.f, -1.f, 1.f, 0.f, backdrop), wall.data());
    const float radii[4] = {0.9f, 0.3f, 0.1f, 0.03333f}, z[4] = {-3.75f, -1.25f, 1.25f, 3.75f};
    for (int i = 0; i < 4; ++i) {
        const uint32_t lamp = b.add_material(Color(0.f), Color(7.59909f / (radii[i] * radii[i])));
        const auto at = rows({1, 0, 0, 0, 0, 1, 0, 6.5f, 0, 0, 1, z[i]});
        b.add_instance(b.add_sphere(radii[i], 32, 16, lamp), at.data());
    }
    // Mitsuba's camera at (28.2792, 3.5, 0) looking −x, +y up.
    *camera = look_at(Vec3(28.2792f, 3.5f, 0.f), Vec3(0.f, 3.5f, 0.f), Vec3(0.f, 1.f, 0.f));
    return b.arrays(camera->data());
}

Params veach_params(int w, int h) {
    Params p = basic_params(w, h, 1, 0);
    // fov 35° across x: lens = 18 mm / tan(17.5°) on a 36 mm sensor fitted horizontally.
    p.set("sensor_fit", std::string("HORIZONTAL"));
    p.set("sensor_width", 36.0);
    p.set("lens", 18.0 / std::tan(17.5 * k_pi / 180.0));
    p.set("clip_start", 0.01);
    return p;
}

namespace {

constexpr float k_plates_radiance = 10.f, k_receiver_albedo = 0.5f, k_plate_albedo = 0.8f, k_plate_height = 1.f;
const std::array<Vec3, 4> k_emitter = {Vec3(-1.5f, -0.5f, 0.f), Vec3(-0.5f, -0.5f, 0.f), Vec3(-0.5f, 0.5f, 0.f),
                                       Vec3(-1.5f, 0.5f, 0.f)};
constexpr float k_plate_x0 = -2.f, k_plate_x1 = 2.f, k_plate_y0 = -1.5f, k_plate_y1 = 1.5f;
constexpr float k_view_x0 = 0.75f, k_view_x1 = 1.25f, k_view_y0 = -0.25f, k_view_y1 = 0.25f;

/// n-point Gauss–Legendre nodes and weights on [a, b] (Newton on the Legendre recurrence).
void gauss_legendre(int n, double a, double b, std::vector<double>* x, std::vector<double>* w) {
    x->resize(n), w->resize(n);
    for (int i = 0; i < n; ++i) {
        double t = std::cos(k_pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = t;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
                p0 = p1, p1 = p2;
            }
            dp = n * (t * p1 - p0) / (t * t - 1.0);
            const double dt = p1 / dp;
            t -= dt;
            if (std::fabs(dt) < 1e-15) break;
        }
        (*x)[i] = 0.5 * (a + b) + 0.5 * (b - a) * t;
        (*w)[i] = (b - a) / ((1.0 - t * t) * dp * dp);
    }
}

}  // namespace

SceneArrays facing_plates() {
    MeshBuilder b;
    const uint32_t receiver = b.add_material(Color(k_receiver_albedo), Color(0.f));
    const uint32_t plate = b.add_material(Color(k_plate_albedo), Color(0.f));
    b.add_instance(b.add_quad_z(0.5f, 1.5f, -0.5f, 0.5f, 0.f, receiver));
    b.add_instance(b.add_quad_z(k_plate_x0, k_plate_x1, k_plate_y0, k_plate_y1, k_plate_height, plate));
    // Blender's area light: radiance = power / (4 · area), so power = 4 · 1 m² · L.
    b.add_area_light(Vec3(-1.f, 0.f, 0.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f), Vec3(0.f, 0.f, 1.f),
                     Color(4.f * k_plates_radiance), /*disk=*/false);
    const std::vector<float> camera = look_at(Vec3(1.f, 0.f, 0.5f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f));
    return b.arrays(camera.data());
}

Params facing_plates_params(int w, int h, int samples) {
    Params p = basic_params(w, h, samples, 1);
    p.set("camera_type", std::string("ORTHO"));
    p.set("ortho_scale", double(k_view_x1 - k_view_x0));
    p.set("pixel_filter", std::string("BOX"));
    p.set("filter_width", 1.0);
    p.set("clip_start", 0.01);
    // Depth of field focused on the receiver: every ray of a raster point still lands on the same point of R (so
    // the image is the area mean over the square), and light tracing has a lens to connect to.
    p.set("use_dof", true);
    p.set("focus_distance", 0.5);
    p.set("aperture_fstop", 2.0);
    return p;
}

double facing_plates_expected(int order) {
    std::vector<double> vx, vwx, vy, vwy, px, pwx, py, pwy;
    gauss_legendre(order, k_view_x0, k_view_x1, &vx, &vwx);
    gauss_legendre(order, k_view_y0, k_view_y1, &vy, &vwy);
    gauss_legendre(8 * order, k_plate_x0, k_plate_x1, &px, &pwx);
    gauss_legendre(6 * order, k_plate_y0, k_plate_y1, &py, &pwy);
    const std::vector<Vec3> emitter(k_emitter.begin(), k_emitter.end());
    // E_P at every plate node, once.
    std::vector<double> irradiance(px.size() * py.size());
    for (size_t i = 0; i < px.size(); ++i)
        for (size_t j = 0; j < py.size(); ++j)
            irradiance[i * py.size() + j] =
                k_plates_radiance *
                polygon_irradiance(emitter, Vec3(float(px[i]), float(py[j]), k_plate_height), Vec3(0.f, 0.f, -1.f));
    const double h = k_plate_height;
    double sum = 0.0, area = 0.0;
    for (size_t a = 0; a < vx.size(); ++a)
        for (size_t c = 0; c < vy.size(); ++c) {
            double L = 0.0;
            for (size_t i = 0; i < px.size(); ++i)
                for (size_t j = 0; j < py.size(); ++j) {
                    const double dx = px[i] - vx[a], dy = py[j] - vy[c], r2 = dx * dx + dy * dy + h * h;
                    L += pwx[i] * pwy[j] * (k_plate_albedo / k_pi) * irradiance[i * py.size() + j] * h * h / (r2 * r2);
                }
            L *= k_receiver_albedo / k_pi;
            sum += vwx[a] * vwy[c] * L;
            area += vwx[a] * vwy[c];
        }
    return sum / area;
}

double polygon_irradiance(const std::vector<Vec3>& poly, Vec3 x, Vec3 n) {
    double sum = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3 a = normalize(poly[i] - x), b = normalize(poly[(i + 1) % poly.size()] - x);
        const double beta = std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0));
        sum += beta * double(dot(n, normalize(cross(a, b))));
    }
    return 0.5 * std::fabs(sum);
}

}  // namespace candela::test
