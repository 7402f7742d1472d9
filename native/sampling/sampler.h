// Pixel samplers: a closed family of value types behind std::variant. A sampler is positioned at
// (pixel, sample index) and then hands out sample dimensions in a fixed order (pixel filter, lens, then
// per bounce light selection, light position, BSDF direction, roulette), so every value depends only on
// (seed, pixel, sample index, dimension) — never on the thread or tile order.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"

namespace candela {

/// Independent uniform random samples ("RANDOM"): one PCG32 stream per (seed, pixel, sample index).
class IndependentSampler {
public:
    explicit IndependentSampler(uint64_t seed) : m_seed(seed) {}

    void start_pixel_sample(uint32_t px, uint32_t py, uint32_t sample_index) {
        const uint64_t pixel = (static_cast<uint64_t>(py) << 32) | px;
        m_rng.seed(hash_values(m_seed, pixel, sample_index), mix64(pixel ^ m_seed));
    }
    float get_1d() { return m_rng.next_float(); }
    Vec2 get_2d() {
        const float a = m_rng.next_float();
        return {a, m_rng.next_float()};
    }
    Vec2 get_pixel_2d() { return get_2d(); }

private:
    uint64_t m_seed;
    Pcg32 m_rng;
};

using Sampler = std::variant<IndependentSampler>;

/// Names accepted by make_sampler (the add-on's `sampler` enum identifiers).
std::vector<std::string> sampler_names();
Sampler make_sampler(const std::string& name, uint64_t seed, int samples_per_pixel);

inline void start_pixel_sample(Sampler& s, uint32_t px, uint32_t py, uint32_t index) {
    std::visit([&](auto& v) { v.start_pixel_sample(px, py, index); }, s);
}
inline float get_1d(Sampler& s) { return std::visit([](auto& v) { return v.get_1d(); }, s); }
inline Vec2 get_2d(Sampler& s) { return std::visit([](auto& v) { return v.get_2d(); }, s); }
inline Vec2 get_pixel_2d(Sampler& s) { return std::visit([](auto& v) { return v.get_pixel_2d(); }, s); }

}  // namespace candela
