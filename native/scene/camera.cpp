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
    const std::string type = params.get_enum("camera_type", "PERSP", {"PERSP", "ORTHO", "PANO"});
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
    // The viewport's zoom and pan of the viewplane (1 and 0 for a render).
    const float zoom = params.get<float>("view_zoom", 1.f);
    const float offset_x = params.get<float>("view_offset_x", 0.f), offset_y = params.get<float>("view_offset_y", 0.f);
    if (!(lens > 0.f) || !(sensor_width > 0.f) || !(sensor_height > 0.f) || !(ortho_scale > 0.f))
        throw InvalidParameter("camera lens, sensor size and orthographic scale must be positive");
    m_ortho = type == "ORTHO";
    // An orthographic 3D view starts its rays behind the view (Blender's clip_start = −clip_end/2 there).
    if (!(m_clip_start >= 0.f || (m_ortho && std::isfinite(m_clip_start))) || !(m_clip_end > m_clip_start))
        throw InvalidParameter("camera clip_end must be greater than clip_start >= 0");
    if (!(zoom > 0.f) || !std::isfinite(zoom) || !std::isfinite(offset_x) || !std::isfinite(offset_y))
        throw InvalidParameter("view_zoom must be positive and view_offset_x/y finite");
    read_panorama(params, type == "PANO", sensor_width, sensor_height, fit, pixel_aspect_x, pixel_aspect_y);

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
    m_left = -xaspect * zoom;
    m_right = xaspect * zoom;
    m_bottom = -yaspect * zoom;
    m_top = yaspect * zoom;
    // Shift is a fraction of the fitted dimension; the viewport's pan a fraction of the (unzoomed) viewplane.
    const float dx = 2.f * (aspect * shift_x + offset_x * xaspect * 2.f);
    const float dy = 2.f * (aspect * shift_y + offset_y * yaspect * 2.f);
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
            m_rigid =
                m_rigid && std::fabs(dot(m_to_world.column(i), m_to_world.column(j)) - (i == j ? 1.f : 0.f)) <= 1e-6f;

    // Depth of field (Blender's Camera > Depth of Field; Cycles' blender_camera_from_object). The keys are read
    // even when it is off, so they never count as unknown.
    const bool use_dof = params.get<bool>("use_dof", false);
    const float fstop = params.get<float>("aperture_fstop", 2.8f);
    const float ratio = params.get<float>("aperture_ratio", 1.f);
    const float focus = params.get<float>("focus_distance", 10.f);
    const int blades = params.get<int>("aperture_blades", 0);
    const float rotation = params.get<float>("aperture_rotation", 0.f);
    if (use_dof && m_pano == Panorama::None) {  // a panorama renders without depth of field
        if (!(fstop > 0.f) || !std::isfinite(fstop))
            throw InvalidParameter("camera aperture_fstop must be positive (got " + std::to_string(fstop) + ")");
        if (!(ratio > 0.f) || !std::isfinite(ratio))
            throw InvalidParameter("camera aperture_ratio must be positive (got " + std::to_string(ratio) + ")");
        if (!(focus >= 0.f) || !std::isfinite(focus))
            throw InvalidParameter("camera focus_distance must be a finite distance >= 0 (got " +
                                   std::to_string(focus) + ")");
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
    m_motion.translate(offset);
}

void Camera::set_motion(const std::vector<Affine>& steps) {
    m_motion = MotionTransform(steps);
    m_moving = m_motion.moves();
    if (m_moving) m_rigid = false;  // interpolated rotations are unit only up to rounding: normalise every ray
}

Vec2 Camera::world_to_raster(const Vec3& p) const {
    const Vec3 q = to_camera().point(p);  // camera space: looking down −Z
    float sx = q.x, sy = q.y;
    if (!m_ortho) {
        const float depth = std::fmax(-q.z, 1e-30f);
        sx = q.x / (depth * m_tan_half_fov);
        sy = q.y / (depth * m_tan_half_fov);
    }
    return {(sx - m_left) / m_raster_to_x, (sy - m_bottom) / m_raster_to_y};
}

Ray Camera::generate_ray(Vec2 raster, Vec2 u_lens) const {
    if (m_pano != Panorama::None) return generate_panoramic_ray(raster);
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
        // The fixed transform read in place (to_world() returns a copy, twice per ray otherwise).
        const auto place = [&](const Affine& xf) {
            ray.o = xf.translation();
            ray.d = xf.vector(d_cam) * (1.f / len);
        };
        if (m_moving)
            place(to_world());
        else
            place(m_to_world);
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
        ray.o = to_world().point(o_cam);
        ray.d = normalize(to_world().vector(d_cam));
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
        ray.o = to_world().point(o_cam);
        ray.d = normalize(to_world().vector(d_cam));
        // Clip distances are measured along the view axis (the rays start on the z = 0 plane).
        const float inv_cos = 1.f / -d_cam.z;
        ray.tmin = m_clip_start * inv_cos;
        ray.tmax = m_clip_end * inv_cos;
    }
    return ray;
}

void Camera::read_panorama(const Params& params, bool pano, float sensor_width, float sensor_height,
                           const std::string& fit, float pixel_aspect_x, float pixel_aspect_y) {
    // Read even for other cameras, so a stale key never counts as unknown.
    const std::string kind = params.get_enum("panorama_type", "FISHEYE_EQUISOLID",
                                             {"EQUIRECTANGULAR", "FISHEYE_EQUIDISTANT", "FISHEYE_EQUISOLID",
                                              "EQUIANGULAR_CUBEMAP_FACE", "MIRRORBALL", "FISHEYE_LENS_POLYNOMIAL"});
    const float lat_min = params.get<float>("latitude_min", -0.5f * k_pi),
                lat_max = params.get<float>("latitude_max", 0.5f * k_pi);
    const float lon_min = params.get<float>("longitude_min", -k_pi), lon_max = params.get<float>("longitude_max", k_pi);
    m_fisheye_fov = params.get<float>("fisheye_fov", k_pi);
    m_fisheye_lens = params.get<float>("fisheye_lens", 10.5f);
    const float box[4] = {params.get<float>("pano_left", 0.f), params.get<float>("pano_right", 1.f),
                          params.get<float>("pano_bottom", 0.f), params.get<float>("pano_top", 1.f)};
    if (!pano) return;
    if (kind == "EQUIRECTANGULAR")
        m_pano = Panorama::Equirectangular;
    else if (kind == "FISHEYE_EQUIDISTANT")
        m_pano = Panorama::FisheyeEquidistant;
    else if (kind == "FISHEYE_EQUISOLID")
        m_pano = Panorama::FisheyeEquisolid;
    else
        throw InvalidParameter("panoramic camera type " + kind +
                               " is not supported (Candela renders Equirectangular, "
                               "Fisheye Equidistant and Fisheye Equisolid)");
    for (float v : {lat_min, lat_max, lon_min, lon_max, box[0], box[1], box[2], box[3]})
        if (!std::isfinite(v))
            throw InvalidParameter("panoramic camera latitude, longitude and view box must be finite");
    if (!(lat_max > lat_min) || !(lon_max > lon_min))
        throw InvalidParameter(
            "panoramic camera: latitude_max must exceed latitude_min and longitude_max longitude_min");
    if (!(m_fisheye_fov > 0.f) || !(m_fisheye_fov <= 2.f * k_pi) || !(m_fisheye_lens > 0.f))
        throw InvalidParameter("fisheye camera: fisheye_fov must be in (0, 360°] and fisheye_lens positive");
    if (!(box[1] > box[0]) || !(box[3] > box[2])) throw InvalidParameter("panoramic camera: the view box is empty");
    for (int i = 0; i < 4; ++i) m_pano_box[i] = box[i];
    // Cycles' equirectangular range: φ = (lon_min − lon_max)·u − lon_min, θ = (lat_min − lat_max)·v − lat_min + π/2.
    m_pano_range[0] = lon_min - lon_max;
    m_pano_range[1] = -lon_min;
    m_pano_range[2] = lat_min - lat_max;
    m_pano_range[3] = -lat_min + 0.5f * k_pi;
    // Equisolid: the sensor's fitted side is the sensor size, the other follows the frame's aspect (Cycles).
    const float xr = m_width * pixel_aspect_x, yr = m_height * pixel_aspect_y;
    const bool horizontal = fit == "HORIZONTAL" || (fit == "AUTO" && xr > yr);
    const float sensor = fit == "VERTICAL" ? sensor_height : sensor_width;
    m_pano_sensor_w = horizontal ? sensor : sensor * xr / yr;
    m_pano_sensor_h = horizontal ? sensor * yr / xr : sensor;
}

Vec3 Camera::panorama_direction(float u, float v) const {
    // Cycles' panorama space: x forward, y left, z up.
    Vec3 p(0.f);
    if (m_pano == Panorama::Equirectangular) {
        const float phi = m_pano_range[0] * u + m_pano_range[1];
        const float theta = m_pano_range[2] * v + m_pano_range[3];
        const float st = std::sin(theta);
        p = Vec3(st * std::cos(phi), st * std::sin(phi), std::cos(theta));
    } else {
        float x, y, r, theta;
        if (m_pano == Panorama::FisheyeEquidistant) {
            // The unit circle inscribed in the frame; θ grows linearly with the radius up to fov/2.
            x = (u - 0.5f) * 2.f;
            y = (v - 0.5f) * 2.f;
            r = std::sqrt(x * x + y * y);
            if (r > 1.f) return Vec3(0.f);
            theta = r * 0.5f * m_fisheye_fov;
        } else {
            // Equisolid: on the sensor (mm), r = 2·lens·sin(θ/2), up to the field of view.
            x = (u - 0.5f) * m_pano_sensor_w;
            y = (v - 0.5f) * m_pano_sensor_h;
            r = std::sqrt(x * x + y * y);
            if (r > 2.f * m_fisheye_lens * std::sin(0.25f * m_fisheye_fov)) return Vec3(0.f);
            theta = 2.f * std::asin(std::min(r / (2.f * m_fisheye_lens), 1.f));
        }
        // (cos φ, sin φ) = (x, y)/r: the direction's azimuth around the axis is the image point's.
        const float cphi = r > 0.f ? x / r : 1.f, sphi = r > 0.f ? y / r : 0.f;
        const float st = std::sin(theta);
        p = Vec3(std::cos(theta), -cphi * st, sphi * st);
    }
    // Panorama (x forward, y left, z up) → Blender camera space (−z forward, x right, y up).
    return Vec3(-p.y, p.z, -p.x);
}

Ray Camera::generate_panoramic_ray(Vec2 raster) const {
    const float u = m_pano_box[0] + (m_pano_box[1] - m_pano_box[0]) * raster.x / float(m_width);
    const float v = m_pano_box[2] + (m_pano_box[3] - m_pano_box[2]) * raster.y / float(m_height);
    const Vec3 d_cam = panorama_direction(u, v);
    Ray ray;
    ray.type = k_ray_camera;
    ray.o = to_world().translation();
    if (!(dot(d_cam, d_cam) > 0.f)) {  // outside the image circle: an empty ray
        ray.d = forward();
        ray.tmin = ray.tmax = 0.f;
        return ray;
    }
    ray.d = normalize(to_world().vector(d_cam));
    // Clip distances along the ray (Cycles starts panoramic rays at the near clip distance).
    ray.tmin = m_clip_start;
    ray.tmax = m_clip_end;
    return ray;
}

}  // namespace candela
