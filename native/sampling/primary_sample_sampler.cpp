#include "sampling/primary_sample_sampler.h"

#include <algorithm>

namespace candela {

// Giles, "Approximating the erfinv function" (GPU Computing Gems, 2010), single precision: two polynomials in
// w = −ln(1 − x²), relative error below 4e-7 on the central branch. Written out rather than taken from a library
// (Boost.Math has erf_inv) because it is the one function needed and Boost is not otherwise a dependency. The clamp
// to ±0.99999 bounds the Gaussian step at ~3.1σ symmetrically, so the small-step proposal stays symmetric.
float erf_inv(float x) {
    x = std::clamp(x, -0.99999f, 0.99999f);
    float w = -std::log((1.f - x) * (1.f + x)), p;
    if (w < 5.f) {
        w -= 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = std::sqrt(w) - 3.f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    return p * x;
}

}  // namespace candela
