// Lambertian reflection: f = ρ/π, sampled by the cosine-weighted hemisphere (pdf = cos θ/π), so the
// sample weight f·cos/pdf is exactly ρ. Reciprocal, and the same in both transport directions.
#pragma once

#include "bsdf/bsdf_sample.h"
#include "core/math.h"
#include "sampling/warp.h"

namespace candela {

struct LambertBsdf {
    Color albedo;

    Color f(const Vec3& wo, const Vec3& wi) const {
        return (wo.z > 0.f && wi.z > 0.f) ? albedo * k_inv_pi : Color(0.f);
    }
    float pdf(const Vec3& wo, const Vec3& wi) const {
        return (wo.z > 0.f && wi.z > 0.f) ? cosine_hemisphere_pdf(wi.z) : 0.f;
    }
    BsdfSample sample(const Vec3& wo, Vec2 u) const {
        BsdfSample s;
        if (wo.z <= 0.f) return s;
        s.wi = sample_cosine_hemisphere(u);
        if (s.wi.z <= 1e-7f) return s;  // u on the disk's rim: a grazing direction with pdf ≈ 0
        s.pdf = cosine_hemisphere_pdf(s.wi.z);
        s.f = albedo * k_inv_pi;
        return s;
    }
};

}  // namespace candela
