// Camera importance: the camera as light-rooted strategies see it (Veach's thesis §4.5 and ch. 10; pbrt-v3
// §16.1.1 derives the perspective case). Everything is the exact inverse of generate_ray (camera.cpp), so a
// connection found here is a ray generate_ray makes for the connection's raster position and lens sample.
//
// Camera space: the camera looks down −Z; raster (x, y) maps to the viewplane point
// (sx, sy) = (left + x·raster_to_x, bottom + y·raster_to_y).
//
// Perspective (pinhole, or thin lens with the lens point L on z = 0 and the plane of focus z = −f). The pinhole
// ray of (sx, sy) has direction (sx·T, sy·T, −1), T = tan_half_fov; the thin-lens ray leaves L toward that
// direction's point f·(sx·T, sy·T, −1) on the plane of focus (a pinhole is L = 0 and any f). So a world point p at
// depth z = −p.z is reached from L by the ray of the raster whose focus point is L + (p − L)·f/z.
//   Direction density. For a fixed L, raster uniform over the frame puts the focus point uniformly on a rectangle
//   of area A_img·f² (A_img = image_plane_area(): the frame at z = −1). A direction at angle θ from the axis meets
//   that plane at distance f/cos θ and obliquity cos θ, so dω = cos θ·dA/(f/cos θ)² and
//       pdf_dir = (f/cos θ)²/(cos θ·A_img·f²) = 1/(A_img·cos³θ)      (independent of L and f).
//   Importance. A disk of area a at distance d whose normal makes θ_ref with the ray subtends a·|cos θ_ref|/d²,
//   so for this L the ray hits it with probability pdf_dir·a·|cos θ_ref|/d², and averaged over the lens samples
//   connect() draws with generate_ray's own warp:
//       K = 1/(A_img·cos³θ·d²)                                       (the lens density cancels: pdf_pos = 1/lens_area).
// Orthographic with depth of field. A ray starts at s + l on the clip_start plane (s the viewplane point, l the
// lens offset) and runs along (−l, −f) to s on the plane of focus, f further on. Its direction depends on l alone:
// the direction's tangent (−l/f) is uniform over the aperture scaled by 1/f, of area lens_area/f², so
//       pdf_dir = f²/(lens_area·cos³θ),  pdf_pos = 1/A_view
// (for a given direction the origins are uniform over the frame shifted by l: the joint density of origin and
// direction is exactly the product inside that shifted frame; pdf_pos ignores the shift, the lens blur at the
// frame's edge). For a fixed l the ray hits a disk if its origin falls in the disk's shadow along the direction on
// the clip plane, of area a·|cos θ_ref|/cos θ, so
//       K = 1/(A_view·cos θ).
// With K, a light tracer's splat value at the connection's raster position is β·f·|cos θ_ref|·K, the film counting
// (light paths)/(W·H) samples per pixel (film/film.h, "Splats"): the whole image sums to the probability of the
// camera seeing the point, 1 for a surface that covers the frame (tests/native/camera_importance_test.cpp).
//
// Clipping is along the view axis, as generate_ray's tmin and tmax: a point is reachable iff its depth (from the
// lens plane, perspective; from the camera's plane z = 0 for orthographic, whose rays start at clip_start) lies in
// [clip_start, clip_end].
#include <cctype>
#include <cmath>
#include <string>

#include "scene/camera.h"

namespace candela {

std::string Camera::panorama_label(const std::string& type) {
    std::string label;
    bool word_start = true;
    for (char c : type) {
        if (c == '_') {
            label += ' ';
            word_start = true;
        } else {
            label += word_start ? c : char(std::tolower(static_cast<unsigned char>(c)));
            word_start = false;
        }
    }
    return label;
}

std::string Camera::panoramic_not_connectable_message(const std::string& type) {
    return "the panoramic camera (" + panorama_label(type) +
           ") is not supported: light-tracing connections (t = 1) go to a perspective or orthographic lens (they "
           "invert its viewplane projection, which a panorama does not have); use PATH for panoramas";
}

std::string Camera::panorama_type_name() const {
    switch (m_pano) {
    case Panorama::Equirectangular: return "EQUIRECTANGULAR";
    case Panorama::FisheyeEquidistant: return "FISHEYE_EQUIDISTANT";
    case Panorama::FisheyeEquisolid: return "FISHEYE_EQUISOLID";
    default: return std::string();
    }
}

std::string Camera::not_connectable_kind() const {
    if (connectable()) return std::string();
    if (!is_panoramic()) return "the orthographic camera without depth of field";
    return "the panoramic camera (" + panorama_label(panorama_type_name()) + ")";
}

std::string Camera::not_connectable_message() const {
    if (connectable()) return std::string();
    if (!is_panoramic()) return k_not_connectable_message;
    return panoramic_not_connectable_message(panorama_type_name());
}

float Camera::image_plane_area() const {
    const float a = (m_right - m_left) * (m_top - m_bottom);
    return m_ortho ? a : a * m_tan_half_fov * m_tan_half_fov;
}

bool Camera::viewplane_to_raster(float sx, float sy, Vec2* raster, float margin) const {
    const float x = (sx - m_left) / m_raster_to_x, y = (sy - m_bottom) / m_raster_to_y;
    if (!(x >= -margin && x <= float(m_width) + margin && y >= -margin && y <= float(m_height) + margin))
        return false;  // NaN fails too
    *raster = {x, y};
    return true;
}

bool Camera::to_lens_plane(const Ray& ray, Vec3* o_cam, Vec3* d_cam) const {
    Vec3 d = to_camera().vector(ray.d);
    const float len = length(d);
    if (!(len > 0.f)) return false;
    d = d / len;
    if (!(d.z < 0.f)) return false;
    const Vec3 o = to_camera().point(ray.o);
    const float plane = m_ortho ? -m_clip_start : 0.f;
    *o_cam = o + d * ((plane - o.z) / d.z);
    o_cam->z = plane;
    *d_cam = d;
    return true;
}

bool Camera::raster_of(const Ray& camera_ray, Vec2* raster, float margin) const {
    if (is_panoramic()) return false;  // no viewplane to invert (connectable() is false)
    Vec3 o, d;
    if (!to_lens_plane(camera_ray, &o, &d)) return false;
    // The ray's point on the plane of focus (f ahead of the lens or clip plane) is the pinhole ray's point there.
    // Without an aperture any plane will do: a perspective ray is its own pinhole ray (f = 1), an orthographic
    // one starts at its viewplane point (f = 0).
    const bool dof = has_aperture();
    const float f = dof ? m_focus_distance : (m_ortho ? 0.f : 1.f);
    const float s = f / -d.z;
    const float fx = o.x + d.x * s, fy = o.y + d.y * s;
    if (m_ortho) return viewplane_to_raster(fx, fy, raster, margin);
    const float to_view = 1.f / (f * m_tan_half_fov);
    return viewplane_to_raster(fx * to_view, fy * to_view, raster, margin);
}

void Camera::pdf_we(const Ray& camera_ray, float* pdf_pos, float* pdf_dir, float margin) const {
    *pdf_pos = 0.f;
    *pdf_dir = 0.f;
    Vec3 o, d;
    Vec2 raster;
    const bool dof = has_aperture();
    if (is_panoramic()) {
        // Rays start at the camera's position (a delta, as a pinhole's); the direction density of the projection
        // is not implemented: 0, and connectable() is false so no strategy needs it.
        *pdf_pos = 1.f;
        return;
    }
    if (m_ortho) {
        *pdf_pos = 1.f / image_plane_area();
        // A pinhole orthographic camera's direction is a delta: no density (connectable() is false).
        if (!dof || !to_lens_plane(camera_ray, &o, &d) || !raster_of(camera_ray, &raster, margin)) return;
        // The lens offset that gives this direction: l = −f·(d.x, d.y)/(−d.z).
        const float s = m_focus_distance / -d.z;
        if (!m_aperture.contains({-d.x * s, -d.y * s})) return;
        const float cos_theta = -d.z;
        *pdf_dir = m_focus_distance * m_focus_distance / (lens_area() * cos_theta * cos_theta * cos_theta);
        return;
    }
    *pdf_pos = dof ? 1.f / lens_area() : 1.f;
    if (!to_lens_plane(camera_ray, &o, &d)) return;
    if (dof && !m_aperture.contains({o.x, o.y})) {
        *pdf_pos = 0.f;
        return;
    }
    if (!raster_of(camera_ray, &raster, margin)) return;
    const float cos_theta = -d.z;
    *pdf_dir = 1.f / (image_plane_area() * cos_theta * cos_theta * cos_theta);
}

bool Camera::connect(const Vec3& ref, Vec2 u_lens, CameraConnection* out, float margin) const {
    if (!connectable()) return false;
    const Vec3 p = to_camera().point(ref);
    const float depth = -p.z;
    if (!(depth > 0.f && depth >= m_clip_start && depth <= m_clip_end)) return false;
    const bool dof = has_aperture();
    const Vec2 lens = dof ? m_aperture.sample(u_lens) : Vec2{0.f, 0.f};
    CameraConnection c;
    if (!m_ortho) {
        // The ray from L through p meets the plane of focus at L + (p − L)·f/depth = f·(sx·T, sy·T, −1).
        const Vec3 L(lens.x, lens.y, 0.f);
        const float f = dof ? m_focus_distance : 1.f;
        const float s = f / depth, to_view = 1.f / (f * m_tan_half_fov);
        if (!viewplane_to_raster((L.x + (p.x - L.x) * s) * to_view, (L.y + (p.y - L.y) * s) * to_view, &c.raster,
                                 margin))
            return false;
        const Vec3 to_lens = L - p;
        const float d_cam = length(to_lens);
        const float cos_theta = depth / d_cam;
        c.lens_point = to_world().point(L);
        c.wi = normalize(to_world().vector(to_lens));
        c.dist = length(c.lens_point - ref);
        const float cos3 = cos_theta * cos_theta * cos_theta;
        c.pdf_dir = 1.f / (image_plane_area() * cos3);
        c.importance = c.pdf_dir / (c.dist * c.dist);
        c.pdf_pos = dof ? 1.f / lens_area() : 1.f;
        c.delta_pos = !dof;
    } else {
        // The ray of lens offset l runs along (−l, −f) from s + l on the clip plane; p lies t = (depth − clip_start)/f
        // of that vector along it, so s = p − (1 − t)·l and the origin is p + t·l.
        const float f = m_focus_distance;
        const float t = (depth - m_clip_start) / f;
        if (!viewplane_to_raster(p.x - (1.f - t) * lens.x, p.y - (1.f - t) * lens.y, &c.raster, margin)) return false;
        const Vec3 back(lens.x, lens.y, f);  // toward the origin
        const float back_len = length(back);
        const float cos_theta = f / back_len;
        c.lens_point = to_world().point(Vec3(p.x + t * lens.x, p.y + t * lens.y, -m_clip_start));
        c.wi = normalize(to_world().vector(back));
        c.dist = length(c.lens_point - ref);
        const float a_view = image_plane_area();
        c.importance = 1.f / (a_view * cos_theta);
        c.pdf_pos = 1.f / a_view;
        c.pdf_dir = f * f / (lens_area() * cos_theta * cos_theta * cos_theta);
        c.delta_pos = false;
    }
    *out = c;
    return true;
}

}  // namespace candela
