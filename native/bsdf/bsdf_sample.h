// The result of sampling a BSDF.
#pragma once

#include "core/vec.h"

namespace candela {

struct BsdfSample {
    Color f;              // BSDF value for (wo, wi), without the cosine
    Vec3 wi;              // sampled incident direction, local frame
    float pdf = 0.f;      // solid-angle density of wi; 0 means "no sample"
    bool is_delta = false;

    bool valid() const { return pdf > 0.f; }
};

}  // namespace candela
