#include "sampling/primary_sample_sampler.h"

#include <algorithm>

#include "sampling/erfinv.h"

namespace candela {

// Giles' approximation (sampling/erfinv.h, shared with the Beckmann distribution's sampling), without its Newton polish:
// relative error below 4e-7 on the central branch is plenty for a mutation. The clamp to ±0.99999 bounds the
// Gaussian step at ~3.1σ symmetrically, so the small-step proposal stays symmetric.
float erf_inv(float x) {
    x = std::clamp(x, -0.99999f, 0.99999f);
    return erfinv_giles_factor(x) * x;
}

}  // namespace candela
