#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace candela {

Camera::Camera(const Params& params, const Affine& camera_to_world)
    : m_to_world(camera_to_world), m_to_camera(camera_to_world.inverse()) {
    m_width = params.require<int>("width");
    m_height = params.require<int>("height");
    if (m_width <= 0 || m_height <= 0)
        throw InvalidParameter("resolution " + std::to_string(m_width) + "x" + std::to_string(m_height) +
                               " is empty: width and height must be at least 1 pixel");
    const std::string type = params.get_enum("camera_type", "PERSP", {"PERSP", "ORTHO"});
    const std::string fit = params.get_enum("sensor_fit", "AUTO", {"AUTO", "HORIZONTAL", "VERTICAL"});
    const float sensor_width = params.get<float>("sensor_width", 36.f);
    const float sensor_height = params.get<float>("sensor_height", 24.f);
    const float lens = params.get<float>("lens", 50.f);
    const float ortho_scale = params.get<float>("ortho_scale", 6.f);
    const float shift_x = params.get<float>("shift_x", 0.f), shift_y = params.get<float>("shift_y", 0.f);
    const float pixel_aspect_x = params.get<float>("pixel_aspect_x", 1.f);
    const float pixel_aspect_y = params.get<float>("pixel_aspect_y", 1.f);
    m_clip_start = params.get<float>("clip_start", 0.1f);
    m_clip_end = params.get<float>("clip_end", 1000.f);
    if (!(lens > 0.f) || !(sensor_width > 0.f) || !(sensor_height > 0.f) || !(ortho_scale > 0.f))
        throw InvalidParameter("camera lens, sensor size and orthographic scale must be positive");
    if (!(m_clip_start >= 0.f) || !(m_clip_end > m_clip_start))
        throw InvalidParameter("camera clip_end must be greater than clip_start >= 0");
    m_ortho = type == "ORTHO";

    const float xratio = m_width * pixel_aspect_x, yratio = m_height * pixel_aspect_y;
    bool horizontal = fit == "HORIZONTAL";
    float sensor = fit == "VERTICAL" ? sensor_height : sensor_width;
    if (fit == "AUTO") horizontal = xratio > yratio;
    float aspect, xaspect, yaspect;
    if (horizontal) {
        aspect = xratio / yratio;
        xaspect = aspect;
        yaspect = 1.f;
    } else {
        aspect = yratio / xratio;
        xaspect = 1.f;
        yaspect = aspect;
    }
    if (m_ortho) {
        // The viewplane spans ortho_scale along the fitted dimension.
        xaspect = xaspect * ortho_scale / (aspect * 2.f);
        yaspect = yaspect * ortho_scale / (aspect * 2.f);
        aspect = ortho_scale / 2.f;
    }
    m_left = -xaspect;
    m_right = xaspect;
    m_bottom = -yaspect;
    m_top = yaspect;
    const float dx = 2.f * aspect * shift_x, dy = 2.f * aspect * shift_y;
    m_left += dx;
    m_right += dx;
    m_bottom += dy;
    m_top += dy;
    // fov spans the viewplane's ±1 axis: 2·atan(0.5·sensor/lens/aspect).
    m_tan_half_fov = (0.5f * sensor / lens) / (m_ortho ? 1.f : aspect);
    m_raster_to_x = (m_right - m_left) / float(m_width);
    m_raster_to_y = (m_top - m_bottom) / float(m_height);
    // A rotation whose columns are orthonormal to 1e-6 keeps |R·d| = |d| to about that: then a perspective ray
    // direction is normalised once, in camera space, instead of again after the rotation.
    m_rigid = true;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m_rigid = m_rigid && std::fabs(dot(m_to_world.column(i), m_to_world.column(j)) - (i == j ? 1.f : 0.f)) <= 1e-6f;

    // Depth of field (Blender's Camera > Depth of Field; Cycles' blender_camera_from_object). The keys are read
    // even when it is off, so they never count as unknown.
    const bool use_dof = params.get<bool>("use_dof", false);
    const float fstop = params.get<float>("aperture_fstop", 2.8f);
    const float ratio = params.get<float>("aperture_ratio", 1.f);
    const float focus = params.get<float>("focus_distance", 10.f);
    const int blades = params.get<int>("aperture_blades", 0);
    const float rotation = params.get<float>("aperture_rotation", 0.f);
    if (use_dof) {
        if (!(fstop > 0.f) || !std::isfinite(fstop))
            throw InvalidParameter("camera aperture_fstop must be positive (got " + std::to_string(fstop) + ")");
        if (!(ratio > 0.f) || !std::isfinite(ratio))
            throw InvalidParameter("camera aperture_ratio must be positive (got " + std::to_string(ratio) + ")");
        if (!(focus >= 0.f) || !std::isfinite(focus))
            throw InvalidParameter("camera focus_distance must be a finite distance >= 0 (got " + std::to_string(focus) + ")");
        if (blades < 0) throw InvalidParameter("camera aperture_blades must not be negative");
        if (!std::isfinite(rotation)) throw InvalidParameter("camera aperture_rotation must be finite");
        m_focus_distance = std::max(focus, 1e-5f);  // Cycles' floor
        // The lens is in millimetres, the scene in metres (Cycles assumes 1 unit = 1 m here).
        m_aperture.radius = m_ortho ? 1.f / (2.f * fstop) : (lens * 1e-3f) / (2.f * fstop);
        m_aperture.blades = blades;
        m_aperture.rotation = rotation;
        m_aperture.inv_ratio = 1.f / ratio;
    }
}

void Camera::translate(const Vec3& offset) {
    for (int r = 0; r < 3; ++r) m_to_world.m[r][3] += offset[r];
    m_to_camera = m_to_world.inverse();
}

Vec2 Camera::world_to_raster(const Vec3& p) const {
    const Vec3 q = m_to_camera.point(p);  // camera space: looking down −Z
    float sx = q.x, sy = q.y;
    if (!m_ortho) {
        const float depth = std::fmax(-q.z, 1e-30f);
        sx = q.x / (depth * m_tan_half_fov);
        sy = q.y / (depth * m_tan_half_fov);
    }
    return {(sx - m_left) / m_raster_to_x, (sy - m_bottom) / m_raster_to_y};
}

Ray Camera::generate_ray(Vec2 raster, Vec2 u_lens) const {
    const float sx = m_left + raster.x * m_raster_to_x;
    const float sy = m_bottom + raster.y * m_raster_to_y;
    const bool dof = !m_aperture.is_pinhole();
    if (!dof && !m_ortho && m_rigid) {
        // The common case, a rigid pinhole camera: d = R·d_cam/|d_cam|, and the clip distances along the view
        // axis become distances along d through 1/cos = |d_cam| (d_cam.z = −1).
        const Vec3 d_cam(sx * m_tan_half_fov, sy * m_tan_half_fov, -1.f);
        const float len = length(d_cam);
        Ray ray;
        ray.type = k_ray_camera;
        ray.o = m_to_world.translation();
        ray.d = m_to_world.vector(d_cam) * (1.f / len);
        ray.tmin = m_clip_start * len;
        ray.tmax = m_clip_end * len;
        return ray;
    }
    const Vec2 lens = dof ? m_aperture.sample(u_lens) : Vec2{0.f, 0.f};
    Ray ray;
    ray.type = k_ray_camera;
    if (m_ortho) {
        // Blender's orthographic camera starts rays on the clip_start plane; with depth of field they leave from
        // the aperture around that point and meet again focus_distance further on.
        const Vec3 o_cam(sx + lens.x, sy + lens.y, -m_clip_start);
        const Vec3 d_cam = dof ? normalize(Vec3(-lens.x, -lens.y, -m_focus_distance)) : Vec3(0.f, 0.f, -1.f);
        ray.o = m_to_world.point(o_cam);
        ray.d = normalize(m_to_world.vector(d_cam));
        ray.tmin = 0.f;
        ray.tmax = (m_clip_end - m_clip_start) / -d_cam.z;
    } else {
        Vec3 d_cam(sx * m_tan_half_fov, sy * m_tan_half_fov, -1.f);
        Vec3 o_cam(0.f);
        if (dof) {
            // The pinhole ray meets the plane of focus (z = −focus_distance) at d_cam·focus_distance.
            o_cam = Vec3(lens.x, lens.y, 0.f);
            d_cam = d_cam * m_focus_distance - o_cam;
        }
        d_cam = normalize(d_cam);
        ray.o = m_to_world.point(o_cam);
        ray.d = normalize(m_to_world.vector(d_cam));
        // Clip distances are measured along the view axis (the rays start on the z = 0 plane).
        const float inv_cos = 1.f / -d_cam.z;
        ray.tmin = m_clip_start * inv_cos;
        ray.tmax = m_clip_end * inv_cos;
    }
    return ray;
}

}  // namespace candela
