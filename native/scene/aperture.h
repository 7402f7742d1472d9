// The lens aperture of a depth-of-field camera as Cycles 3.4 models it (kernel/camera: camera_sample_aperture):
// a disk, or a regular polygon of `blades` corners on the unit circle (corners at rotation + (2k + 1)·π/blades,
// Cycles' orientation), sampled uniformly by area, then squeezed horizontally by 1/ratio (anamorphic bokeh) and
// scaled by the aperture radius. Blender: Camera > Depth of Field > Aperture (F-Stop, Blades, Rotation, Ratio).
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/vec.h"
#include "sampling/warp.h"

namespace candela {

struct Aperture {
    float radius = 0.f;     // scene units; 0 = pinhole
    int blades = 0;         // < 3: a disk
    float rotation = 0.f;   // radians
    float inv_ratio = 1.f;  // 1 / aperture_ratio

    bool is_pinhole() const { return !(radius > 0.f); }

    /// Area of the aperture in the lens plane (scene units²): πr²/ratio for a disk; for n blades, n triangles
    /// (centre and two corners 2π/n apart on the circle of radius r) of area ½·sin(2π/n)·r² each, /ratio; 0 pinhole.
    float area() const {
        if (is_pinhole()) return 0.f;
        const float unit = blades < 3 ? k_pi : 0.5f * float(blades) * std::sin(2.f * k_pi / float(blades));
        return unit * radius * radius * inv_ratio;
    }

    /// Whether the lens-plane point p (camera-space x, y) lies on the aperture, with a relative margin `tolerance`
    /// (points sample() produced pass for any tolerance above float rounding). The polygon's edge k has its outward
    /// normal at rotation + 2kπ/n (half-way between its corners) and lies cos(π/n) from the centre.
    bool contains(Vec2 p, float tolerance = 1e-4f) const {
        if (is_pinhole()) return false;
        const float qx = p.x / (inv_ratio * radius), qy = p.y / radius;  // back on the unit shape
        if (blades < 3) return qx * qx + qy * qy <= (1.f + tolerance) * (1.f + tolerance);
        const float n = float(blades), sector = 2.f * k_pi / n;
        const float k = std::nearbyint((std::atan2(qy, qx) - rotation) / sector);  // the edge facing q
        const float a = rotation + k * sector;
        return qx * std::cos(a) + qy * std::sin(a) <= std::cos(k_pi / n) * (1.f + tolerance);
    }

    /// A point on the aperture (camera-space x, y) from u uniform in [0, 1)²: uniform by area.
    Vec2 sample(Vec2 u) const {
        Vec2 p;
        if (blades < 3) {
            p = sample_uniform_disk_concentric(u);
        } else {
            // The polygon is `blades` congruent triangles (centre, corner k, corner k + 1): pick one uniformly
            // (equal areas) with the first coordinate, reuse its fraction for the point inside.
            const float n = float(blades);
            const float scaled = u.x * n;
            const float k = std::fmin(std::floor(scaled), n - 1.f);
            const Vec2 b = sample_uniform_triangle({std::fmin(scaled - k, k_one_minus_epsilon), u.y});
            const float a0 = rotation + (2.f * k - 1.f) * k_pi / n, a1 = a0 + 2.f * k_pi / n;
            // Barycentric b0 weighs corner a0, b1 corner a1, the rest the centre (the origin).
            p = {b.x * std::cos(a0) + b.y * std::cos(a1), b.x * std::sin(a0) + b.y * std::sin(a1)};
        }
        return {p.x * inv_ratio * radius, p.y * radius};
    }
};

}  // namespace candela
