// Multiple importance sampling weights (Veach 1997, ch. 9): the balance heuristic w_a = p_a / Σ p (eq. 9.12) and
// the power heuristic with β = 2, w_a = p_a² / Σ p² (eq. 9.13). Densities are in the same measure and already
// scaled by their strategies' sample counts (n_a p_a). Every integrator weighs two strategies with mis_weight.
#pragma once

#include <cmath>

namespace candela {

enum class MisHeuristic { Balance, Power };

/// MIS weight of strategy a against strategy b; a delta (infinite) density a weighs 1.
inline __attribute__((always_inline)) float mis_weight(MisHeuristic h, float a, float b) {
    if (std::isinf(a)) return 1.f;
    if (h == MisHeuristic::Power) {
        a *= a;
        b *= b;
    }
    const float sum = a + b;
    return sum > 0.f && std::isfinite(sum) ? a / sum : 0.f;
}

}  // namespace candela
