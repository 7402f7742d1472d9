// Changes Cycles 3.4 makes to a shading point's closures before it scatters, as functions of a BSDF (the rules of
// when they apply live with the integrators: integrators/common/light_paths.h):
//
//   blur (Filter Glossy)     every microfacet lobe's α raised to at least the given α (Cycles' bsdf_blur: GGX and
//                            Beckmann reflection, glass and refraction, the Principled specular and clearcoat);
//                            a delta mirror or smooth glass becomes a rough one.
//   caustics filter          Cycles' closure rules with Caustics Reflective or Refractive off: glossy reflection
//                            lobes (Glossy, the Principled specular, clearcoat) are dropped when reflective is off,
//                            refraction-only lobes when refractive is off, and a glass lobe (both at once) keeps
//                            the half that stays on, as Cycles builds glass from two closures weighted by the
//                            Fresnel factor F at the shading normal: reflection with weight F (no Fresnel inside),
//                            refraction with weight 1 − F (refraction only).
//   transparency             the summed weight of the Transparent lobes (what a shadow ray lets through, Cycles'
//                            closure_transparent_extinction).
#pragma once

#include "bsdf/bsdf.h"

namespace candela {

/// The BSDF with every microfacet lobe's roughness raised to at least alpha (α, not the UI roughness).
Bsdf blur_bsdf(const Bsdf& b, float alpha);
/// True if blur_bsdf can change b (it has a microfacet or clearcoat lobe).
bool has_microfacet_lobe(const Bsdf& b);

/// The lobes that stay at a vertex reached by a diffuse ray with the given Caustics switches; cos_o is the cosine
/// of the outgoing direction with the shading normal (the Fresnel factor a glass lobe is split by).
Bsdf caustics_filter(const Bsdf& b, float cos_o, bool reflective, bool refractive);
/// True if caustics_filter(b, …, reflective, refractive) differs from b.
bool caustics_filter_changes(const Bsdf& b, bool reflective, bool refractive);

/// Σ weights of the Transparent lobes: the fraction of light passing straight through.
Color transparency(const Bsdf& b);

}  // namespace candela
