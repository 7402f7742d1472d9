// The shutter time of the path a thread is tracing (motion blur, docs/light_paths.md "Motion blur"): a value in
// [0, 1] over the shutter interval at which every query of that path sees the scene — Embree's ray time for
// moving instances, the camera's and objects' transforms for shading and camera connections. An integrator
// that renders motion blur draws one time per path (or per photon pass) and opens a ShutterScope around its
// tracing; outside any scope the time is the shutter's middle, so an integrator that does not draw times renders
// everything there. Per thread, so parallel paths never see each other's time; deterministic since the time is
// drawn from the path's sampler state.
#pragma once

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

}  // namespace candela
