// The pieces of a light path every light-rooted walk shares (LIGHT's light tracer, the photon tracers of PHOTON and
// SPPM): the emitted ray with its flux weight, the ray leaving a vertex, and Russian roulette on a light path.
//
// A light path starts at an emitter chosen ∝ power (lights/emitter_set.h) with the flux weight
//     β₀ = Le·|cos θ|/(p_pos·p_dir·P(emitter))      (lights/light_emission.h),
// whose expectation is the scene's total flux. Its throughput is a flux, not a number ≤ 1, so roulette compares
// the throughput with the first vertex's (THROUGHPUT, SQRT_THROUGHPUT) or uses the vertex's own sample weight
// f·|cos|/p (ALBEDO: Jensen's rule for photons, which keeps every surviving photon's power near its parent's).
#pragma once

#include <cstdint>
#include <limits>

#include "core/math.h"
#include "integrators/common/roulette.h"
#include "lights/emitter_set.h"
#include "scene/camera.h"
#include "scene/ray_offset.h"
#include "scene/ray_visibility.h"
#include "scene/surface_hit.h"

namespace candela {

struct LightPathStart {
    Ray ray;
    EmissionSample emission;  // what the emitter sampled (point, direction, densities)
    Color beta{0.f};          // the flux weight β₀
    uint32_t emitter = 0;     // the emitter's index in the EmitterSet
    bool valid = false;
};

/// The emitted ray of u_select (the emitter), u_pos (its origin), u_dir (its direction) and u_side (a triangle's
/// side), as EmitterSet::sample_le draws it.
inline LightPathStart start_light_path(const EmitterSet& emitters, float u_select, Vec2 u_pos, Vec2 u_dir,
                                       float u_side) {
    LightPathStart out;
    float pmf = 0.f;
    const EmissionSample es = emitters.sample_le(u_select, u_pos, u_dir, u_side, &out.emitter, &pmf);
    out.emission = es;
    if (!es.valid() || !(pmf > 0.f)) return out;
    out.beta = es.weight() / pmf;
    if (!is_finite(out.beta)) return out;
    out.ray = Ray{(es.delta_pos || es.infinite) ? es.p : offset_ray_origin(es.p, es.n), es.d, 0.f,
                  std::numeric_limits<float>::infinity(), k_ray_all};
    out.valid = true;
    return out;
}

/// The ray leaving `hit` along unit w, from the origin offset to the side w leaves by.
inline Ray ray_leaving(const SurfaceHit& hit, const Vec3& w) {
    const float cos_g = dot(w, hit.ng);
    return Ray{offset_ray_origin(hit.p, cos_g > 0.f ? hit.ng : -hit.ng), w, 0.f, std::numeric_limits<float>::infinity(),
               k_ray_all};
}

/// A light path's survival probability after a scattering with sample weight `weight` (f·|cos|/p), its throughput
/// `relative` to the first vertex's (Π η² undone).
inline float light_path_survival(RouletteMode mode, const Color& weight, const Color& relative) {
    return mode == RouletteMode::Albedo           ? min_num(1.f, max_component(weight))
           : mode == RouletteMode::SqrtThroughput ? arrival_survival(relative, 1.f)
                                                  : min_num(1.f, max_component(relative));
}

}  // namespace candela
