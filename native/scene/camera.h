// Blender's camera as Cycles 3.4 builds it (intern/cycles/blender/camera.cpp, blender_camera_viewplane):
// perspective and orthographic projection with sensor fit, shift and clipping, in world space, and depth of field
// (Cycles' thin-lens model, kernel/camera: rays start on the aperture and pass through the point the pinhole ray
// meets on the plane of focus, a plane at focus_distance in front of the camera — of the near clip plane for an
// orthographic camera; the aperture radius is lens/(2·f-stop), lens in metres, or 1/(2·f-stop) orthographic).
// Raster coordinates are Blender's: x to the right, y up, (0, 0) the bottom-left corner of the full frame.
#pragma once

#include <cmath>

#include "core/params.h"
#include "core/transform.h"
#include "core/vec.h"
#include "scene/aperture.h"
#include "scene/ray_visibility.h"

namespace candela {

struct Ray {
    Vec3 o, d;
    float tmin = 0.f, tmax = 1e30f;
    uint8_t type = k_ray_all;  // RayType: which objects it can hit (scene/ray_visibility.h)
};

class Camera {
public:
    /// Reads the camera params (docs/architecture.md); camera_to_world has no scale.
    Camera(const Params& params, const Affine& camera_to_world);

    /// Primary camera ray through raster position (x, y) of the full frame; d is unit length. u_lens (uniform in
    /// [0, 1)², the sampler's Lens dimension) picks the point on the aperture; a pinhole camera ignores it.
    Ray generate_ray(Vec2 raster, Vec2 u_lens = {0.5f, 0.5f}) const;
    bool has_aperture() const { return !m_aperture.is_pinhole(); }
    const Aperture& aperture() const { return m_aperture; }
    float focus_distance() const { return m_focus_distance; }
    /// Unit view direction (the camera's −Z axis); depth = dot(p − position(), forward()) (Cycles' Z depth).
    Vec3 forward() const { return normalize(m_to_world.vector(Vec3(0.f, 0.f, -1.f))); }

    Vec3 position() const { return m_to_world.translation(); }
    /// The width of one pixel's footprint at `distance` from the camera (Cycles' compact ray differential of a
    /// camera ray: the pixel's size for an orthographic camera, distance × its angle at the image centre otherwise).
    float pixel_footprint(float distance) const {
        const float pixel = 0.5f * (std::fabs(m_raster_to_x) + std::fabs(m_raster_to_y));
        return m_ortho ? pixel : distance * pixel * m_tan_half_fov;
    }
    int full_width() const { return m_width; }
    int full_height() const { return m_height; }
    /// Moves the camera by `offset` (the scene is rendered in camera-world space).
    void translate(const Vec3& offset);
    /// Where point p (camera-world space) lies on the full frame's raster (pinhole projection, shift included; the
    /// inverse of generate_ray's mapping without aperture). A point behind a perspective camera maps far outside.
    Vec2 world_to_raster(const Vec3& p) const;

private:
    Affine m_to_world;
    bool m_ortho = false;
    int m_width = 0, m_height = 0;
    float m_left = -1, m_right = 1, m_bottom = -1, m_top = 1;  // viewplane
    float m_tan_half_fov = 1.f;                                 // perspective scale of the viewplane
    float m_clip_start = 0.1f, m_clip_end = 1000.f;
    Aperture m_aperture;
    float m_focus_distance = 10.f;
    float m_raster_to_x = 0.f, m_raster_to_y = 0.f;  // viewplane units per pixel
    bool m_rigid = false;  // the rotation is orthonormal: it keeps unit vectors unit (generate_ray normalises once)
};

}  // namespace candela
