// The type of a continuation ray, for object ray visibility (scene/ray_visibility.h), as Cycles' path_state_next
// assigns it: any transmission makes a TRANSMISSION ray, a reflection a DIFFUSE or a GLOSSY one (mirror-like
// reflection counts as glossy), and a transparent pass-through (a Transparent BSDF's straight continuation) keeps the
// type of the ray it continues — a camera ray through a transparent surface is still a camera ray.
#pragma once

#include <cstdint>

#include "bsdf/bsdf_sample.h"
#include "scene/ray_visibility.h"

namespace candela {

inline uint8_t continuation_ray_type(const BsdfSample& s, uint8_t previous) {
    if (s.is_transmission()) return s.is_transparent() ? previous : uint8_t(k_ray_transmission);
    return (s.flags & k_bsdf_diffuse) ? uint8_t(k_ray_diffuse) : uint8_t(k_ray_glossy);
}

}  // namespace candela
