// Scalar constants and helpers shared by every layer.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace candela {

inline constexpr float k_pi = 3.14159265358979323846f;
inline constexpr float k_inv_pi = 0.31830988618379067154f;
inline constexpr float k_inv_two_pi = 0.15915494309189533577f;
inline constexpr float k_inv_four_pi = 0.07957747154594766788f;
/// Largest float below 1: every canonical sample u must stay in [0, 1).
inline constexpr float k_one_minus_epsilon = 0x1.fffffep-1f;

inline float clamp(float v, float lo, float hi) { return std::min(std::max(v, lo), hi); }
inline float lerp(float t, float a, float b) { return a + t * (b - a); }
inline float safe_sqrt(float v) { return std::sqrt(std::max(v, 0.f)); }
inline float sqr(float v) { return v * v; }

inline uint32_t float_bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
inline float bits_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

}  // namespace candela
