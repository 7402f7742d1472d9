#include "sampling/sampler.h"

#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "sampling/low_discrepancy.h"

namespace candela {

namespace {

/// Stratum s of n plus a jitter in [0, 1), as a value in [0, 1).
inline float stratum_value(uint32_t s, float jitter, uint32_t n) {
    return to_unit_float((double(s) + double(jitter)) / double(n));
}

}  // namespace

// ---- STRATIFIED ----

StratifiedSampler::StratifiedSampler(uint64_t seed, int samples_per_pixel) : SamplerBase(seed, samples_per_pixel) {
    const uint32_t n = m_spp;
    uint32_t root = uint32_t(std::sqrt(double(n)));
    while (uint64_t(root + 1) * (root + 1) <= n) ++root;
    while (uint64_t(root) * root > n) --root;
    // An exact factorisation nx·ny = N with a grid at most 2:1; otherwise the ⌊√N⌋ × ⌊N/⌊√N⌋⌋ grid.
    m_nx = root;
    m_ny = n / root;
    for (uint32_t nx = root; nx >= 1; --nx) {
        if (n % nx == 0) {
            if (n / nx <= 2 * nx) {
                m_nx = nx;
                m_ny = n / nx;
            }
            break;
        }
    }
}

float StratifiedSampler::sample_1d(uint32_t dim) const {
    if (m_index >= m_spp) return independent_1d(dim);
    const uint32_t s = permute_index(m_index, m_spp, dim_key(dim, 1));
    return stratum_value(s, independent_1d(dim), m_spp);
}

Vec2 StratifiedSampler::sample_2d(uint32_t dim) const {
    const uint32_t strata = m_nx * m_ny;
    if (m_index >= strata) return independent_2d(dim);
    const uint32_t s = permute_index(m_index, strata, dim_key(dim, 1));
    const Vec2 j = independent_2d(dim);
    return {stratum_value(s % m_nx, j.x, m_nx), stratum_value(s / m_nx, j.y, m_ny)};
}

// ---- NROOKS ----

float NRooksSampler::sample_1d(uint32_t dim) const {
    if (m_index >= m_spp) return independent_1d(dim);
    return stratum_value(permute_index(m_index, m_spp, dim_key(dim, 1)), independent_1d(dim), m_spp);
}

Vec2 NRooksSampler::sample_2d(uint32_t dim) const {
    if (m_index >= m_spp) return independent_2d(dim);
    const Vec2 j = independent_2d(dim);
    return {stratum_value(permute_index(m_index, m_spp, dim_key(dim, 1)), j.x, m_spp),
            stratum_value(permute_index(m_index, m_spp, dim_key(dim, 2)), j.y, m_spp)};
}

// ---- HALTON / HAMMERSLEY ----

namespace {

/// Owen-scrambled Φ_b(i) as a float in [0, 1).
inline float scrambled_radical_inverse(uint32_t base, uint32_t i, uint64_t key, uint32_t spp) {
    if (base == 2) return fixed_to_float(owen_scramble_base2(reverse_bits32(i), key));
    return to_unit_float(owen_radical_inverse(base, i, key, spp - 1));
}

}  // namespace

float HaltonSampler::sample_1d(uint32_t dim) const {
    if (dim >= k_max_radical_inverse_dims) return independent_1d(dim);
    return scrambled_radical_inverse(prime(int(dim)), m_index, dim_key(dim, 1), m_spp);
}

float HammersleySampler::sample_1d(uint32_t dim) const {
    if (m_index >= m_spp || dim >= k_max_radical_inverse_dims) return independent_1d(dim);
    if (dim == 0) {
        const uint32_t fixed = uint32_t((uint64_t(m_index) << 32) / m_spp);  // i/N as a 0.32 fraction
        return fixed_to_float(owen_scramble_base2(fixed, dim_key(0, 1)));
    }
    return scrambled_radical_inverse(prime(int(dim) - 1), m_index, dim_key(dim, 1), m_spp);
}

// ---- SOBOL (Burley 2020: shuffled, Owen-scrambled (0,2)-sequence per request) ----

// ---- registry ----

std::vector<std::string> sampler_names() { return {"RANDOM", "STRATIFIED", "NROOKS", "HALTON", "HAMMERSLEY", "SOBOL"}; }

Sampler make_sampler(const std::string& name, uint64_t seed, int samples_per_pixel) {
    if (name == "RANDOM") return IndependentSampler(seed, samples_per_pixel);
    if (name == "STRATIFIED") return StratifiedSampler(seed, samples_per_pixel);
    if (name == "NROOKS") return NRooksSampler(seed, samples_per_pixel);
    if (name == "HALTON") return HaltonSampler(seed, samples_per_pixel);
    if (name == "HAMMERSLEY") return HammersleySampler(seed, samples_per_pixel);
    if (name == "SOBOL") return SobolSampler(seed, samples_per_pixel);
    throw InvalidParameter("unknown sampler '" + name + "'");
}

}  // namespace candela
