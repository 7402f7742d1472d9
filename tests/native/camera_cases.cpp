#include "camera_cases.h"

#include <stdexcept>

#include "test_helpers.h"

namespace candela::test {

namespace {

Params base_params(int w, int h) {
    Params p;
    p.set("width", int64_t(w));
    p.set("height", int64_t(h));
    p.set("clip_start", 1.0);
    p.set("clip_end", 6.0);
    return p;
}

Affine rotated_camera() {
    const std::vector<float> rows = look_at({1.5f, -2.f, 0.7f}, {-0.3f, 0.4f, 0.1f}, {0.f, 0.f, 1.f});
    return Affine::from_rows(rows.data());
}

}  // namespace

std::vector<CameraCase> camera_cases() {
    std::vector<CameraCase> cases;
    auto add = [&](const std::string& name, Params p) { cases.push_back({name, std::move(p), rotated_camera()}); };
    add("perspective", base_params(64, 48));
    {
        Params p = base_params(40, 56);
        p.set("lens", 18.0);  // wide: cos θ down to 0.55 at the corners
        p.set("shift_x", 0.15);
        p.set("shift_y", -0.2);
        p.set("pixel_aspect_x", 1.5);
        add("wide_shifted_aspect", p);
    }
    {
        Params p = base_params(48, 64);
        p.set("sensor_fit", std::string("VERTICAL"));
        p.set("shift_y", 0.1);
        add("vertical_fit_portrait", p);
    }
    {
        Params p = base_params(48, 64);
        p.set("sensor_fit", std::string("HORIZONTAL"));
        p.set("pixel_aspect_y", 1.3);
        add("horizontal_fit_portrait", p);
    }
    {
        Params p = base_params(64, 48);
        p.set("use_dof", true);
        p.set("aperture_fstop", 0.2);  // radius 0.125: a blur of up to 20 px
        p.set("focus_distance", 2.5);
        add("thin_lens", p);
    }
    {
        Params p = base_params(56, 40);
        p.set("lens", 24.0);
        p.set("use_dof", true);
        p.set("aperture_fstop", 0.12);
        p.set("focus_distance", 3.0);
        p.set("aperture_blades", int64_t(5));
        p.set("aperture_rotation", 0.4);
        p.set("aperture_ratio", 1.7);
        p.set("shift_x", -0.1);
        add("thin_lens_blades_ratio", p);
    }
    {
        Params p = base_params(64, 40);
        p.set("camera_type", std::string("ORTHO"));
        p.set("ortho_scale", 4.0);
        p.set("shift_x", 0.1);
        add("ortho", p);
    }
    {
        Params p = base_params(64, 48);
        p.set("camera_type", std::string("ORTHO"));
        p.set("ortho_scale", 4.0);
        p.set("use_dof", true);
        p.set("aperture_fstop", 1.0);  // radius 0.5
        p.set("focus_distance", 2.0);
        add("ortho_dof", p);
    }
    {
        Params p = base_params(48, 60);
        p.set("camera_type", std::string("ORTHO"));
        p.set("ortho_scale", 3.0);
        p.set("sensor_fit", std::string("HORIZONTAL"));
        p.set("use_dof", true);
        p.set("aperture_fstop", 0.8);
        p.set("focus_distance", 1.5);
        p.set("aperture_blades", int64_t(6));
        p.set("aperture_rotation", 0.2);
        p.set("aperture_ratio", 0.6);
        p.set("shift_y", 0.15);
        add("ortho_dof_blades_ratio", p);
    }
    return cases;
}

std::vector<CameraCase> connectable_cases() {
    std::vector<CameraCase> out;
    for (CameraCase& c : camera_cases())
        if (c.name != "ortho") out.push_back(std::move(c));
    return out;
}

Vec3 point_at_depth(const Camera& cam, Vec2 raster, Vec2 u, float depth) {
    const Ray r = cam.generate_ray(raster, u);
    const Vec3 fwd = cam.forward();
    const float t = (depth - dot(r.o - cam.position(), fwd)) / dot(r.d, fwd);
    return r.o + r.d * t;
}

const CameraCase& case_named(const std::vector<CameraCase>& cases, const std::string& name) {
    for (const CameraCase& c : cases)
        if (c.name == name) return c;
    throw std::runtime_error("no camera case " + name);
}

}  // namespace candela::test
