// Lambertian reflection: f = 1/π (the colour is the closure weight), sampled by the cosine-weighted
// hemisphere (pdf = cos θ/π), so the sample weight f·cos/pdf is exactly 1. Reciprocal, and the same in
// both transport directions.
#pragma once

#include "bsdf/bsdf_sample.h"
#include "core/math.h"
#include "sampling/warp.h"

namespace candela {

struct LambertBsdf {
    Color f(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z > 0.f) ? Color(k_inv_pi) : Color(0.f);
    }
    float pdf(const Vec3& wo, const Vec3& wi, TransportMode = TransportMode::Radiance) const {
        return (wo.z > 0.f && wi.z > 0.f) ? cosine_hemisphere_pdf(wi.z) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u, float = 0.f, TransportMode = TransportMode::Radiance) const {
        BsdfSample s;
        if (wo.z <= 0.f) return s;
        s.wi = sample_cosine_hemisphere(u);
        if (s.wi.z <= 1e-7f) return s;  // u on the disk's rim: a grazing direction with pdf ≈ 0
        s.pdf = cosine_hemisphere_pdf(s.wi.z);
        s.f = Color(k_inv_pi);
        s.flags = k_bsdf_reflection | k_bsdf_diffuse;
        return s;
    }
    float albedo(const Vec3&) const { return 1.f; }
    uint32_t flags() const { return k_bsdf_reflection | k_bsdf_diffuse; }
};

}  // namespace candela
