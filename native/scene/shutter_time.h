// The shutter time of the path a thread is tracing (motion blur, docs/light_paths.md "Motion blur"): a value in
// [0, 1] over the shutter interval at which every query of that path sees the scene — Embree's ray time for
// moving instances, the camera's and objects' transforms for shading and camera connections. An integrator
// that renders motion blur draws one time per path (or per photon pass) and opens a ShutterScope around its
// tracing; outside any scope the time is the shutter's middle, so an integrator that does not draw times renders
// everything there. Per thread, so parallel paths never see each other's time; deterministic since the time is
// drawn from the path's sampler state.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/rng.h"

namespace candela {

inline constexpr float k_shutter_middle = 0.5f;

namespace detail {
inline thread_local float t_shutter_time = k_shutter_middle;
}

/// The current thread's shutter time.
inline float shutter_time() { return detail::t_shutter_time; }

/// Sets the thread's shutter time for the scope's lifetime (nests: the previous time comes back).
class ShutterScope {
public:
    explicit ShutterScope(float time) : m_previous(detail::t_shutter_time) { detail::t_shutter_time = time; }
    ~ShutterScope() { detail::t_shutter_time = m_previous; }
    ShutterScope(const ShutterScope&) = delete;
    ShutterScope& operator=(const ShutterScope&) = delete;

private:
    float m_previous;
};

/// A path's shutter time from a 64-bit key of its sampler state (Sampler's sample_stream_key, a function of the
/// seed, pixel and sample index): uniform in [0, 1), independent of every sampler dimension (none is taken, so
/// images without motion are unchanged), the same for any thread count.
inline float shutter_time_of(uint64_t key) { return float(mix64(key ^ 0x73687574746572ULL) >> 40) * 0x1p-24f; }

/// The shutter time of pass `pass` of `passes` that each see the scene at one time (the cache integrators' shutter
/// passes: PHOTON, IRRADIANCE_CACHE), for a render keyed by `key`. Stratified: pass j has stratum σ(j) = j·g mod n
/// of the n equal parts of the shutter and a uniform jitter in it from a hash of (key, j), so the n passes hold one
/// time in each part and their average is an unbiased, stratified estimate of the time average. g is the integer
/// coprime to n nearest n/φ (φ the golden ratio): σ is then a permutation, and its first j strata are spread over
/// the shutter like the golden-ratio sequence j/φ mod 1, whose every prefix is close to evenly spaced (the three-gap
/// theorem: its gaps take at most three lengths). Every prefix of j ≥ 2 passes leaves no gap over 4/j of the
/// shutter between its strata (checked for n up to 300 and some larger n; the jitter adds at most 2/n), so a render
/// stopped early (time limit, cancel) or watched while it renders has seen the whole shutter, not its first part.
inline float stratified_shutter_time(uint64_t key, uint64_t pass, uint64_t passes) {
    if (passes <= 1) return shutter_time_of(hash_combine(key, pass));
    const uint64_t n = passes, guess = uint64_t(double(n) * 0.6180339887498949 + 0.5);
    auto gcd = [](uint64_t a, uint64_t b) {
        while (b) {
            const uint64_t r = a % b;
            a = b;
            b = r;
        }
        return a;
    };
    uint64_t g = 1;
    for (uint64_t d = 0; d < n; ++d) {  // nearest first: guess, guess + 1, guess − 1, … (1 is coprime to any n)
        if (guess + d < n && gcd(guess + d, n) == 1) {
            g = guess + d;
            break;
        }
        if (d <= guess && guess - d > 0 && gcd(guess - d, n) == 1) {
            g = guess - d;
            break;
        }
    }
    const uint64_t stratum = (pass % n) * g % n;  // pass < 2^24 (the samples' limit) and g < n: no overflow
    const double jitter = double(shutter_time_of(hash_combine(key, pass)));
    return float(std::min((double(stratum) + jitter) / double(n), double(0x1.fffffep-1f)));
}

}  // namespace candela
