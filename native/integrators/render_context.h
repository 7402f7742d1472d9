// What an integrator gets besides the scene and the film: the cancel flag, the thread count, the counters the
// session reports as progress and statistics, the current stage (a pre-pass such as "Tracing photons" with its
// own progress) and the log that reaches the user.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "core/message_log.h"
#include "core/parallel.h"
#include "film/aov_film.h"

namespace candela {

/// Why a render stopped (or that it has not).
enum class StopReason : int { Running = 0, Samples, TimeLimit, NoiseThreshold, Cancelled };
const char* stop_reason_name(StopReason r);

/// A named stage of the render and how far it is ("Tracing photons", 3.2 M of 10 M; or "Irradiance cache", 41 %
/// when `percent`: a stage whose total is a count of steps the user has no use for). No stage: the progressive
/// render itself, counted by RenderCounters::work_done in the integrator's work unit. The note is a short status
/// the integrator keeps up to date beside its progress ("1,234 records"), shown during and after its stages.
class StageProgress {
public:
    struct Snapshot {
        std::string name;  // empty: no stage
        int64_t done = 0, total = 0;
        bool percent = false;
        std::string note;  // empty: none
    };
    /// A stage that has ended, summed over its runs under one name (SPPM shoots photons every iteration; a moving
    /// scene builds a cache per shutter pass): the render statistics show where the time went. The progress
    /// snapshot cannot tell that: a stage shorter than the caller's polling interval is never seen in it.
    struct Finished {
        std::string name;
        int runs = 0;
        double seconds = 0.0;         // wall time of all runs
        int64_t done = 0, total = 0;  // the last run's progress when it ended
    };
    void begin(std::string name, int64_t total, bool percent = false) {
        std::lock_guard<std::mutex> lock(m_mutex);
        finish_locked();
        m_name = std::move(name);
        m_done = 0;
        m_total = total;
        m_percent = percent;
        m_started = std::chrono::steady_clock::now();
    }
    void set_done(int64_t done) { m_done.store(done, std::memory_order_relaxed); }
    void end() {
        std::lock_guard<std::mutex> lock(m_mutex);
        finish_locked();
    }
    void set_note(std::string note) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_note = std::move(note);
    }
    Snapshot snapshot() const {
        std::lock_guard<std::mutex> lock(m_mutex);
        return {m_name, m_done.load(std::memory_order_relaxed), m_total, m_percent, m_note};
    }
    /// The stages that ended, in the order they first began (one entry per name).
    std::vector<Finished> finished() const {
        std::lock_guard<std::mutex> lock(m_mutex);
        return m_finished;
    }

private:
    void finish_locked() {
        if (m_name.empty()) return;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_started).count();
        auto it =
            std::find_if(m_finished.begin(), m_finished.end(), [&](const Finished& f) { return f.name == m_name; });
        if (it == m_finished.end()) it = m_finished.insert(m_finished.end(), Finished{m_name});
        it->runs += 1;
        it->seconds += seconds;
        it->done = m_done.load(std::memory_order_relaxed);
        it->total = m_total;
        m_name.clear();
        m_done = 0;
        m_total = 0;
        m_percent = false;
    }

    mutable std::mutex m_mutex;
    std::string m_name;
    std::atomic<int64_t> m_done{0};
    int64_t m_total = 0;
    bool m_percent = false;
    std::string m_note;
    std::chrono::steady_clock::time_point m_started;
    std::vector<Finished> m_finished;
};

/// What the status line names as the method when it is not the integrator the user chose: AUTO's choice and its
/// one-line reason ("Auto: BDPT — caustic paths from small lights"). Empty: the chosen integrator's name.
class MethodNote {
public:
    void set(std::string text) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_text = std::move(text);
    }
    std::string get() const {
        std::lock_guard<std::mutex> lock(m_mutex);
        return m_text;
    }

private:
    mutable std::mutex m_mutex;
    std::string m_text;
};

struct RenderCounters {
    // Progress of the progressive render in the integrator's own unit (samples per pixel, light paths per
    // pixel, iterations, mutations per pixel: Integrator::budget()).
    std::atomic<int64_t> work_done{0};
    std::atomic<int64_t> work_total{0};
    std::atomic<uint64_t> paths{0};            // camera paths traced (or the integrator's paths: light paths, photons)
    std::atomic<uint64_t> rays{0};             // rays cast (camera, bounce and shadow rays)
    std::atomic<uint64_t> nan_samples{0};      // non-finite or negative samples dropped before the film
    std::atomic<double> relative_error{-1.0};  // estimated relative RMSE of the image; < 0 = not known (yet)
    // The integrator has no honest noise estimate (SPPM: sppm.h): the status shows "n/a", not "not known yet".
    std::atomic<bool> noise_unavailable{false};
    std::atomic<int> stop_reason{int(StopReason::Running)};
    StageProgress stage;
    MethodNote method;
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
    AovFilm* aovs = nullptr;         // data passes to write (camera-driven integrators), or none
    MessageLog* messages = nullptr;  // where log() and info() go (Session::take_log_entries), or nowhere

    /// A warning for the user's log (Blender's Info editor and status bar): the image may not be what they expect.
    void log(std::string message) const {
        if (messages) messages->add(LogLevel::Warning, std::move(message));
    }
    /// An info line: what the renderer did (its choices, what it skipped, cache sizes).
    void info(std::string message) const {
        if (messages) messages->add(LogLevel::Info, std::move(message));
    }
};

/// Per-thread statistics gathered by a tracer, folded into RenderCounters once per work item.
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
