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
//
// Camera importance (scene/camera_importance.cpp): the camera seen from the scene, for light-rooted strategies
// (light tracing, bidirectional path tracing): connections from a world point to the lens, the raster position of
// a camera ray, its position and direction densities, and the importance K of a connection.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/motion_transform.h"
#include "core/params.h"
#include "core/transform.h"
#include "core/vec.h"
#include "scene/aperture.h"
#include "scene/ray_visibility.h"
#include "scene/shutter_time.h"

namespace candela {

struct Ray {
    Vec3 o, d;
    float tmin = 0.f, tmax = 1e30f;
    uint8_t type = k_ray_all;  // RayType: which objects it can hit (scene/ray_visibility.h)
};

/// A connection from a world point to the camera, for light-rooted strategies.
struct CameraConnection {
    Vec3 wi;           // unit direction from the reference point toward lens_point
    float dist = 0.f;  // distance from the reference point to lens_point
    Vec3 lens_point;   // where the camera ray through the reference point starts (on the aperture; on the
                       // clip_start plane for orthographic)
    Vec2 raster;       // the full-frame raster position that camera ray has
    /// K: for a camera ray of generate_ray with raster uniform over the full frame and u_lens uniform,
    /// E_lens[K·|cos θ_ref|]·a is the probability that it hits a small disk of area a at the reference point whose
    /// normal makes the angle θ_ref with wi. Perspective (pinhole or thin lens): 1/(A_img·cos³θ·dist²), θ between
    /// the ray and the view axis, A_img = image_plane_area(); orthographic with depth of field: 1/(A_view·cos θ).
    float importance = 0.f;
    float pdf_pos = 1.f;  // area density of lens_point under generate_ray's lens sampling (1 and delta_pos for a
                          // pinhole; orthographic with depth of field: 1/A_view on the clip_start plane)
    float pdf_dir =
        0.f;  // solid-angle density of the ray direction under generate_ray with raster uniform over the full frame
    bool delta_pos = false;
};

class Camera {
public:
    /// What an integrator that needs a connection to the camera reports for a camera that has none
    /// (not_connectable_message()).
    static constexpr const char* k_not_connectable_message =
        "the orthographic camera without depth of field has no light-tracing strategy: use PATH or enable depth of "
        "field";

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
    Vec3 forward() const { return normalize(to_world().vector(Vec3(0.f, 0.f, -1.f))); }

    Vec3 position() const { return to_world().translation(); }
    /// Camera motion over the shutter (motion blur): camera_to_world sampled at evenly spaced shutter times (in
    /// the space the constructor's was; translate() moves them too). Every query then uses the camera at the
    /// thread's shutter_time() (scene/shutter_time.h): rays, connections, raster positions.
    void set_motion(const std::vector<Affine>& steps);
    bool moves() const { return m_moving; }
    /// Camera → world at the thread's shutter time (the fixed transform when the camera does not move).
    Affine to_world() const { return m_moving ? m_motion.at(shutter_time()) : m_to_world; }
    Affine to_camera() const { return m_moving ? to_world().inverse() : m_to_camera; }
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

    // ---- Importance (scene/camera_importance.cpp) ----------------------------------------------------------
    bool orthographic() const { return m_ortho; }
    /// False for a pinhole orthographic camera (its rays have one direction, a delta, so no strategy that connects
    /// a scene point to the camera, or hits the camera, can reach it) and for a panoramic camera (connect,
    /// raster_of and pdf_we invert the viewplane projection, which a panorama does not have: its t = 1 strategies
    /// are not implemented).
    bool connectable() const { return !is_panoramic() && (!m_ortho || has_aperture()); }
    /// "" if connectable(), else what the integrator reports, naming the camera type: k_not_connectable_message for
    /// the orthographic pinhole, panoramic_not_connectable_message for a panorama.
    std::string not_connectable_message() const;
    /// The camera a light-rooted strategy cannot reach, for messages: "the orthographic camera without depth of
    /// field" or "the panoramic camera (Fisheye Equisolid)"; "" if connectable().
    std::string not_connectable_kind() const;
    /// The message for a panoramic camera of panorama_type `type` (EQUIRECTANGULAR, FISHEYE_EQUIDISTANT, ...), so
    /// an integrator can refuse it from its params before the scene is built ("integrator X: " + this).
    static std::string panoramic_not_connectable_message(const std::string& type);
    /// The panorama's panorama_type ("FISHEYE_EQUISOLID"); "" if not panoramic.
    std::string panorama_type_name() const;
    /// Blender's label of a panorama_type ("FISHEYE_EQUISOLID" → "Fisheye Equisolid").
    static std::string panorama_label(const std::string& type);
    /// A pinhole perspective camera: every ray starts at position() (CameraConnection::delta_pos).
    bool delta_position() const { return !m_ortho && !has_aperture(); }
    /// Samples the lens point with u_lens (the same warp generate_ray uses) and returns the connection to world
    /// point `ref`; false if ref is behind the camera, outside the frame, or outside [clip_start, clip_end] along
    /// the view axis (exactly the points a generate_ray ray could reach before tmax), or the camera is not
    /// connectable.
    /// `margin` (pixels) widens the frame: filter importance sampling sends the camera rays of border pixels up to
    /// half the filter's support beyond it, so connections there must count too (the film keeps their weights
    /// for the pixels inside).
    bool connect(const Vec3& ref, Vec2 u_lens, CameraConnection* out, float margin = 0.f) const;
    /// The raster position of a ray generate_ray could produce (its origin on the lens / clip plane, or anywhere
    /// on the same line; its direction): false outside the frame or if it does not point forward.
    bool raster_of(const Ray& camera_ray, Vec2* raster, float margin = 0.f) const;
    /// pdf_pos and pdf_dir (as in CameraConnection) of a camera ray: pdf_dir is 0 outside the frame, and both
    /// are 0 where the ray does not leave the aperture (its support: Aperture::contains).
    void pdf_we(const Ray& camera_ray, float* pdf_pos, float* pdf_dir, float margin = 0.f) const;
    /// Perspective: area of the viewplane rectangle at z = −1 (tan_half_fov included); orthographic: the
    /// viewplane's area in world units.
    float image_plane_area() const;
    /// Aperture::area(): πr²/ratio for a disk, (n/2)·sin(2π/n)·r²/ratio for n blades; 0 for a pinhole.
    float lens_area() const { return m_aperture.area(); }

private:
    Ray generate_panoramic_ray(Vec2 raster) const;
    void read_panorama(const Params& params, bool pano, float sensor_width, float sensor_height, const std::string& fit,
                       float pixel_aspect_x, float pixel_aspect_y);
    /// The raster position of viewplane point (sx, sy); false outside the full frame [0, W] × [0, H].
    bool viewplane_to_raster(float sx, float sy, Vec2* raster, float margin = 0.f) const;
    /// The camera-space ray of a world ray, with its origin moved along it onto the lens plane (z = 0,
    /// perspective) or the clip_start plane (orthographic), and its direction unit length; false if it does
    /// not point forward (d.z < 0).
    bool to_lens_plane(const Ray& ray, Vec3* o_cam, Vec3* d_cam) const;

    Affine m_to_world;
    Affine m_to_camera;        // m_to_world's inverse
    MotionTransform m_motion;  // camera motion (set_motion), used when m_moving
    bool m_moving = false;
    bool m_ortho = false;
    Panorama m_pano = Panorama::None;
    float m_pano_range[4] = {0.f, 0.f, 0.f, 0.f};  // equirectangular: φ = r0·u + r1, θ = r2·v + r3
    float m_fisheye_fov = 3.14159265f, m_fisheye_lens = 10.5f;
    float m_pano_sensor_w = 36.f, m_pano_sensor_h = 24.f;  // equisolid: the sensor after sensor fit (mm)
    float m_pano_box[4] = {0.f, 1.f, 0.f, 1.f};            // frame fraction of raster 0 and W (x), 0 and H (y)
    int m_width = 0, m_height = 0;
    float m_left = -1, m_right = 1, m_bottom = -1, m_top = 1;  // viewplane
    float m_tan_half_fov = 1.f;                                // perspective scale of the viewplane
    float m_clip_start = 0.1f, m_clip_end = 1000.f;
    Aperture m_aperture;
    float m_focus_distance = 10.f;
    float m_raster_to_x = 0.f, m_raster_to_y = 0.f;  // viewplane units per pixel
    bool m_rigid = false;  // the rotation is orthonormal: it keeps unit vectors unit (generate_ray normalises once)
};

}  // namespace candela
