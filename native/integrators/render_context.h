// What an integrator gets besides the scene and the film: the cancel flag, the thread count and the
// counters the session reports as progress and statistics.
#pragma once

#include <atomic>
#include <cstdint>

#include "core/parallel.h"
#include "film/aov_film.h"

namespace candela {

/// Why a render stopped (or that it has not).
enum class StopReason : int { Running = 0, Samples, TimeLimit, NoiseThreshold, Cancelled };
const char* stop_reason_name(StopReason r);

struct RenderCounters {
    std::atomic<int> samples_done{0};   // samples per pixel completed over the whole film
    std::atomic<int> samples_total{0};
    std::atomic<uint64_t> paths{0};     // camera paths traced
    std::atomic<uint64_t> rays{0};      // rays cast (camera, bounce and shadow rays)
    std::atomic<uint64_t> nan_samples{0};  // non-finite or negative samples dropped before the film
    std::atomic<double> relative_error{-1.0};  // estimated relative RMSE of the image; < 0 = not known yet
    std::atomic<int> stop_reason{int(StopReason::Running)};
};

inline const char* stop_reason_name(StopReason r) {
    switch (r) {
        case StopReason::Running: return "";
        case StopReason::Samples: return "samples";
        case StopReason::TimeLimit: return "time limit";
        case StopReason::NoiseThreshold: return "noise threshold";
        default: return "cancelled";
    }
}

struct RenderContext {
    const CancelToken& cancel;
    RenderCounters& counters;
    int threads = 0;
    AovFilm* aovs = nullptr;  // data passes to write (camera-driven integrators), or none
};

/// Per-thread statistics gathered by a tracer, folded into RenderCounters once per tile.
struct PathStats {
    uint64_t rays = 0;
    uint64_t paths = 0;
    uint64_t nan_samples = 0;

    void flush(RenderCounters& c) const {
        c.rays.fetch_add(rays, std::memory_order_relaxed);
        c.paths.fetch_add(paths, std::memory_order_relaxed);
        c.nan_samples.fetch_add(nan_samples, std::memory_order_relaxed);
    }
};

}  // namespace candela
