// Blender's camera as Cycles 3.4 builds it (intern/cycles/blender/camera.cpp, blender_camera_viewplane):
// perspective and orthographic projection with sensor fit, shift and clipping, in world space.
// Raster coordinates are Blender's: x to the right, y up, (0, 0) the bottom-left corner of the full frame.
#pragma once

#include "core/params.h"
#include "core/transform.h"
#include "core/vec.h"

namespace candela {

struct Ray {
    Vec3 o, d;
    float tmin = 0.f, tmax = 1e30f;
};

class Camera {
public:
    /// Reads the camera params (docs/architecture.md); camera_to_world has no scale.
    Camera(const Params& params, const Affine& camera_to_world);

    /// Primary ray through raster position (x, y) of the full frame; d is unit length.
    Ray generate_ray(Vec2 raster) const;

    Vec3 position() const { return m_to_world.translation(); }
    int full_width() const { return m_width; }
    int full_height() const { return m_height; }
    /// Moves the camera by `offset` (the scene is rendered in camera-world space).
    void translate(const Vec3& offset);

private:
    Affine m_to_world;
    bool m_ortho = false;
    int m_width = 0, m_height = 0;
    float m_left = -1, m_right = 1, m_bottom = -1, m_top = 1;  // viewplane
    float m_tan_half_fov = 1.f;                                 // perspective scale of the viewplane
    float m_clip_start = 0.1f, m_clip_end = 1000.f;
};

}  // namespace candela
