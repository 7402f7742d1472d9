// Russian roulette (Arvo & Kirk 1990): a path continues with probability q and carries β/q if it does, so
// E[1{u < q}/q] = 1 and the estimate stays unbiased for the sum truncated at max_bounces. The survival
// probabilities every integrator uses:
//   THROUGHPUT       q = min(1, max β'·b·Πη²) for the continuation ray's throughput β' (b branches),
//   ALBEDO           q = min(1, max albedo(wo)) of the surface,
//   SQRT_THROUGHPUT  Cycles 3.4's rule (path_state_continuation_probability): q = min(1, √(max β·Πη²)), decided on
//                    arrival at a vertex, before its shadow rays; the square root keeps dim paths alive longer.
// Πη² undoes the radiance scaling of refraction (1/η² per crossing), which is not a loss of energy.
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/vec.h"

namespace candela {

enum class RouletteMode { Off, Throughput, Albedo, SqrtThroughput };

/// SQRT_THROUGHPUT's survival on arrival with throughput beta.
inline __attribute__((always_inline)) float arrival_survival(const Color& beta, float eta_scale) {
    return min_num(1.f, std::sqrt(max_component(beta) * eta_scale));
}

/// THROUGHPUT's or ALBEDO's survival for a continuation ray of throughput `beta` (one of `branches`); `albedo()`
/// is evaluated only for ALBEDO.
template <class Albedo>
inline __attribute__((always_inline)) float continuation_survival(RouletteMode mode, const Color& beta, int branches,
                                                                  float eta_scale, Albedo&& albedo) {
    return mode == RouletteMode::Albedo ? min_num(1.f, max_component(albedo()))
                                        : min_num(1.f, max_component(beta) * float(branches) * eta_scale);
}

}  // namespace candela
