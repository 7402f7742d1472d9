// One irradiance cache record (Ward, Rubinstein & Clear 1988; gradients: Ward & Heckbert 1992): the irradiance E_i
// arriving at x_i over the hemisphere around n_i from indirect light (every light path except the emission next-event
// estimation finds directly), the harmonic mean distance R_i of the surfaces the gather rays hit (the scale over
// which E can change: it sets how far the record is trusted), and the first-order change of E with a rotation of
// the normal (∇_r) and a translation of the point (∇_t), one gradient per colour channel, in world space.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

struct IcRecord {
    Vec3 p;             // x_i, world (camera-relative)
    Vec3 n;             // n_i, unit: the shading frame's normal on the side the gather looked at
    Color E{0.f};       // irradiance from indirect light [W/m²]
    float R = 0.f;      // harmonic mean hit distance, after the spacing clamps and neighbour clamping
    float R_min = 0.f;  // the smallest R the minimum spacing allows here (neighbour clamping keeps R ≥ it)
    Vec3 grad_r[3];     // ∂E_c/∂(rotation): E_c(n) ≈ E_c + (n_i × n)·grad_r[c]
    Vec3 grad_t[3];     // ∂E_c/∂x:          E_c(x) ≈ E_c + (x − x_i)·grad_t[c]
    int32_t pixel_x = -1, pixel_y = -1;  // the full-frame pixel whose camera path made the record (IC Records pass)
};

}  // namespace candela
