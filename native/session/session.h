// A render session: validates the scene arrays and params up front (so bad input fails at once, with a
// message), then builds the scene and renders on a worker thread while the caller polls progress,
// reads the partial image and may cancel. Exceptions from the worker are captured and reported through
// error(); nothing escapes a thread.
#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/message_log.h"
#include "core/params.h"
#include "film/aov_film.h"
#include "film/film.h"
#include "input/scene_arrays.h"
#include "integrators/integrator.h"
#include "session/memory_estimate.h"

namespace candela {

enum class SessionPhase { Idle, Building, Rendering, Done, Cancelled, Failed };
const char* phase_name(SessionPhase p);

struct SessionProgress {
    SessionPhase phase = SessionPhase::Idle;
    int64_t work_done = 0, work_total = 0;  // in the integrator's unit (WorkBudget)
    std::string unit = "sample";
    StageProgress::Snapshot stage;  // a named stage with its own progress (a pre-pass), or none
    std::string method;             // the method the status names when not the chosen integrator (AUTO's choice)
    double fraction = 0.0;
    double elapsed_s = 0.0;          // since start()
    double relative_error = -1.0;    // estimated relative RMSE of the image (< 0: not known yet)
    bool noise_unavailable = false;  // the integrator has no honest noise estimate: "n/a" (relative_error stays < 0)
    StopReason stop_reason = StopReason::Running;
};

struct SessionStats {
    double build_seconds = 0.0, render_seconds = 0.0;
    double samples_per_second = 0.0;  // pixel samples per second of render time
    uint64_t paths = 0, rays = 0, nan_samples = 0;
    SceneStats scene;
    std::vector<StageProgress::Finished> stages;  // the render's stages that ended (pre-passes), with their times
};

class Session {
public:
    Session(SceneArrays arrays, Params params);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    /// The memory a session with these arrays and params would allocate, and what is available (the
    /// constructor refuses a render that does not fit). `arrays` must be valid.
    static MemoryEstimate estimate_memory(const SceneArrays& arrays, const Params& params);

    void start();
    /// Waits up to timeout_s; true once the worker finished (done, cancelled or failed).
    bool wait(double timeout_s);
    void cancel();
    void join();

    SessionProgress progress() const;
    SessionStats stats() const;
    std::optional<std::string> error() const;
    std::vector<std::string> take_log();
    /// The same lines with their levels (the add-on shows warnings and info lines differently).
    std::vector<LogEntry> take_log_entries();
    /// Adds a warning for take_log() (the boundary reports what it ignored).
    void add_log(std::string message);

    int width() const { return m_film->width(); }
    int height() const { return m_film->height(); }
    /// Pass names get_pass understands and their channel counts (it returns a data pass only when the `passes`
    /// param asked for it).
    static std::vector<std::pair<std::string, int>> pass_names();
    /// BDPT's strategy-image passes for strategy depths 0..max_depth (3 channels each; integrators/bdpt/strategy_images.h).
    static std::vector<std::string> strategy_pass_names(int max_depth);
    /// A pass as float32 rows bottom to top, or empty if the name is unknown.
    std::vector<float> get_pass(const std::string& name, int* channels) const;

private:
    void run();

    std::unique_ptr<SceneArrays> m_arrays;  // released once the scene is built
    Params m_params;
    std::unique_ptr<Film> m_film;
    std::unique_ptr<AovFilm> m_aovs;  // the data passes asked for by the `passes` param
    std::unique_ptr<Integrator> m_integrator;
    CancelToken m_cancel;
    RenderCounters m_counters;
    int m_threads = 0;
    float m_exposure = 1.f;  // Film > Exposure (film_exposure)

    std::thread m_worker;
    mutable std::mutex m_mutex;
    std::condition_variable m_finished_cv;
    bool m_started = false, m_finished = false;
    SessionPhase m_phase = SessionPhase::Idle;
    std::optional<std::string> m_error;
    MessageLog m_log;
    std::string m_unit;
    SessionStats m_stats;
    std::chrono::steady_clock::time_point m_start_time, m_render_start;
};

}  // namespace candela
