// What light sampling hands an integrator.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "core/vec.h"

namespace candela {

/// How area-like emitters (emissive triangles, rectangular area lights) are sampled — the add-on's
/// `light_pdf` option. AREA: a uniform point on the emitter, p_ω = d²/(A|cosθ_l|). SOLID_ANGLE: uniform in
/// the solid angle the emitter subtends (spherical triangle / rectangle), p_ω = 1/Ω, falling back to AREA
/// where that is not robust (docs/robustness-notes.md §2); the pdf evaluation mirrors the same branch.
enum class LightPdfMode : uint8_t { Area, SolidAngle };

/// "AREA" / "SOLID_ANGLE" (throws InvalidScene for anything else) and back.
LightPdfMode parse_light_pdf_mode(const std::string& name);
const char* light_pdf_mode_name(LightPdfMode mode);

/// The shading point a light is sampled from.
struct LightSampleContext {
    Vec3 p;  // position (world, camera-relative)
    Vec3 n;  // shading normal (may be zero for points in media)
};

struct LightSample {
    Color Li;               // incident radiance (or, for delta lights, intensity/d² folded in) along -wi
    Vec3 wi;                // unit direction from the shading point toward the light
    float dist = 0.f;       // distance to the sampled point (infinity for distant lights)
    float pdf = 0.f;        // solid-angle pdf of wi (1 for delta lights); 0 = no sample
    bool is_delta = false;  // never reached by BSDF sampling (delta, or NEE-only): weight 1, no MIS

    bool valid() const { return pdf > 0.f && !is_black(Li); }
};

/// Area-to-solid-angle conversion: p_ω = p_A · d² / |cos θ_light|.
inline float area_to_solid_angle(float pdf_area, float dist_sq, float cos_light) {
    return cos_light > 1e-7f ? pdf_area * dist_sq / cos_light : 0.f;
}

/// The light sample for point `p` (normal `n`) drawn uniformly from an emitter of area `area` with radiance
/// `radiance`, seen from `ref`. One-sided emitters shine toward +n only.
inline LightSample sample_from_area_point(const Vec3& ref, const Vec3& p, const Vec3& n, float area,
                                          const Color& radiance, bool two_sided) {
    LightSample s;
    const Vec3 w = p - ref;
    const float d2 = length_squared(w);
    if (!(d2 > 0.f)) return s;
    const float dn = dot(w, n);
    const float abs_dn = two_sided ? std::fabs(dn) : -dn;  // d·cos θ_l
    // p_ω = d²/(A·cos θ_l) = d³/(A·|w·n|): written so, its division needs only w·n and overlaps the square root
    // (the latency chain is then sqrt → multiply, not sqrt → divide → divide). The back of a one-sided emitter
    // or a grazing one (cos θ_l ≤ 1e-7, area_to_solid_angle's threshold) gives no sample.
    const float d = std::sqrt(d2);
    const float inv_area_dn = 1.f / (area * abs_dn);
    const float inv_d = 1.f / d;
    if (!(abs_dn > 1e-7f * d)) return s;
    const float pdf = d2 * (d * inv_area_dn);  // d·inv_area_dn = 1/(A·cos θ_l): no overflow before the product
    if (!(pdf > 0.f) || !std::isfinite(pdf)) return s;
    s.pdf = pdf;
    s.wi = w * inv_d;
    s.dist = d;
    s.Li = radiance;
    return s;
}

}  // namespace candela
