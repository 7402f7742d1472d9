// Blender's camera as Cycles 3.4 builds it (intern/cycles/blender/camera.cpp, blender_camera_viewplane):
// perspective and orthographic projection with sensor fit, shift and clipping, in world space, and depth of field
// (Cycles' thin-lens model, kernel/camera: rays start on the aperture and pass through the point the pinhole ray
// meets on the plane of focus, a plane at focus_distance in front of the camera — of the near clip plane for an
// orthographic camera; the aperture radius is lens/(2·f-stop), lens in metres, or 1/(2·f-stop) orthographic).
// Raster coordinates are Blender's: x to the right, y up, (0, 0) the bottom-left corner of the full frame.
//
// Panoramic cameras (camera_type PANO; Cycles 3.4 kernel/camera/projection.h): equirectangular (a latitude /
// longitude range), fisheye equidistant (the angle from the axis grows linearly with the radius: θ = r·fov/2 on
// the unit circle inscribed in the frame) and fisheye equisolid (r = 2·lens·sin(θ/2) on the sensor, up to the
// field of view). Cycles' panorama space looks down +x with +z up; it is turned into Blender's camera space (−z
// forward, +y up) so the same camera_to_world applies. Rays outside a fisheye's image circle carry nothing
// (tmax = tmin = 0: integrators return black for them, as Cycles does).
//
// The 3D viewport (Cycles' blender_camera_from_view) adds a zoom of the viewplane and an offset of it
// (view_zoom, view_offset_x/y: camera view zoom and pan), lets an orthographic view start rays behind the view
// (clip_start < 0) and, in the camera view of a panoramic camera, maps the frame to the part of the panorama the
// viewport shows (pano_left/right/bottom/top, fractions of the camera frame).
#pragma once

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
    /// Panoramic projection (no viewplane): integrators that connect vertices to the camera must refuse it or
    /// project through panorama_direction's inverse.
    bool is_panoramic() const { return m_pano != Panorama::None; }
    enum class Panorama { None, Equirectangular, FisheyeEquidistant, FisheyeEquisolid };
    Panorama panorama() const { return m_pano; }
    /// Camera-space direction (Blender's: −z forward) of the panorama at frame fractions (u, v) ∈ [0, 1]²; the
    /// zero vector outside a fisheye's image circle.
    Vec3 panorama_direction(float u, float v) const;
    const Aperture& aperture() const { return m_aperture; }
    float focus_distance() const { return m_focus_distance; }
    /// Unit view direction (the camera's −Z axis); depth = dot(p − position(), forward()) (Cycles' Z depth).
    Vec3 forward() const { return normalize(m_to_world.vector(Vec3(0.f, 0.f, -1.f))); }

    Vec3 position() const { return m_to_world.translation(); }
    int full_width() const { return m_width; }
    int full_height() const { return m_height; }
    /// Moves the camera by `offset` (the scene is rendered in camera-world space).
    void translate(const Vec3& offset);

private:
    Ray generate_panoramic_ray(Vec2 raster) const;
    void read_panorama(const Params& params, bool pano, float sensor_width, float sensor_height, const std::string& fit,
                       float pixel_aspect_x, float pixel_aspect_y);

    Affine m_to_world;
    bool m_ortho = false;
    Panorama m_pano = Panorama::None;
    float m_pano_range[4] = {0.f, 0.f, 0.f, 0.f};   // equirectangular: φ = r0·u + r1, θ = r2·v + r3
    float m_fisheye_fov = 3.14159265f, m_fisheye_lens = 10.5f;
    float m_pano_sensor_w = 36.f, m_pano_sensor_h = 24.f;   // equisolid: the sensor after sensor fit (mm)
    float m_pano_box[4] = {0.f, 1.f, 0.f, 1.f};     // frame fraction of raster 0 and W (x), 0 and H (y)
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
