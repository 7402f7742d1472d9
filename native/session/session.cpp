#include "session/session.h"

#include "integrators/bdpt/strategy_images.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "integrators/scene_skips.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace candela {

const char* phase_name(SessionPhase p) {
    switch (p) {
    case SessionPhase::Idle: return "idle";
    case SessionPhase::Building: return "building";
    case SessionPhase::Rendering: return "rendering";
    case SessionPhase::Done: return "done";
    case SessionPhase::Cancelled: return "cancelled";
    default: return "failed";
    }
}

namespace {

struct FilmWindow {
    int x0, y0, x1, y1;
    double pixels() const { return double(x1 - x0) * double(y1 - y0); }
};

/// The border window from the params (the full frame without one); throws if it is empty or outside the frame.
FilmWindow film_window(const Params& params) {
    const int width = params.require<int>("width"), height = params.require<int>("height");
    const FilmWindow w{params.get<int>("crop_x0", 0), params.get<int>("crop_y0", 0), params.get<int>("crop_x1", width),
                       params.get<int>("crop_y1", height)};
    if (w.x0 < 0 || w.y0 < 0 || w.x1 > width || w.y1 > height || w.x0 >= w.x1 || w.y0 >= w.y1)
        throw InvalidParameter("the border window [" + std::to_string(w.x0) + ", " + std::to_string(w.x1) + ") x [" +
                               std::to_string(w.y0) + ", " + std::to_string(w.y1) + ") is empty or outside the frame");
    return w;
}

}  // namespace

MemoryEstimate Session::estimate_memory(const SceneArrays& arrays, const Params& params) {
    return candela::estimate_memory(arrays, params, film_window(params).pixels());
}

Session::Session(SceneArrays arrays, Params params)
    : m_arrays(std::make_unique<SceneArrays>(std::move(arrays))), m_params(std::move(params)) {
    m_arrays->validate();
    // Everything that can be checked without building the BVH is checked here, on the caller's thread.
    Camera probe(m_params, Affine());  // validates the camera params
    const FilmWindow w = film_window(m_params);
    const int x0 = w.x0, y0 = w.y0, x1 = w.x1, y1 = w.y1;
    // Refuse renders that cannot fit in memory before allocating anything (the film here, the BVH on start()).
    const MemoryEstimate memory = estimate_memory(*m_arrays, m_params);
    if (!memory.fits()) {
        if (memory.film_bytes > memory.geometry_bytes)
            throw InvalidParameter("a " + std::to_string(x1 - x0) + "x" + std::to_string(y1 - y0) +
                                   " render: " + memory.refusal());
        throw InvalidScene(memory.refusal());
    }
    m_exposure = m_params.get<float>("film_exposure", 1.f);
    if (!(m_exposure >= 0.f) || !std::isfinite(m_exposure))
        throw InvalidParameter("film_exposure must be a finite factor >= 0 (got " + std::to_string(m_exposure) + ")");
    m_threads = resolve_thread_count(m_params.get<int>("threads", 0));
    m_film = std::make_unique<Film>(x1 - x0, y1 - y0, x0, y0, m_params.get<int>("tile_size", 32));
    m_aovs = std::make_unique<AovFilm>(*m_film, split_pass_list(m_params.get<std::string>("passes", "")));
    m_integrator = make_integrator(m_params);
    const WorkBudget budget = m_integrator->budget();
    m_counters.work_total = budget.total;
    m_unit = budget.unit;
    for (const auto& key : m_params.unused_keys())
        if (key != "threads") m_log.add("unknown render parameter '" + key + "' was ignored");
}

Session::~Session() {
    cancel();
    join();
}

void Session::start() {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_started) throw InvalidParameter("a session renders once: start() was already called");
    m_started = true;
    m_phase = SessionPhase::Building;
    m_start_time = std::chrono::steady_clock::now();
    m_worker = std::thread([this] { run(); });
}

void Session::run() {
    SessionPhase end_phase = SessionPhase::Done;
    std::optional<std::string> error;
    try {
        const auto t0 = std::chrono::steady_clock::now();
        const Scene scene(*m_arrays, m_params, &m_cancel);
        m_arrays.reset();  // the scene keeps what it needs
        const auto t1 = std::chrono::steady_clock::now();
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_stats.build_seconds = std::chrono::duration<double>(t1 - t0).count();
            m_stats.scene = scene.stats();
            m_phase = SessionPhase::Rendering;
            m_render_start = t1;
        }
        if (scene.lights().empty() && is_black(scene.lights().background()))
            m_log.add("the scene has no lights and a black world: the image is black");
        const std::string note = unhonoured_features_note(m_params.get<std::string>("integrator", "PATH"),
                                                          m_integrator->honoured_features(), scene);
        if (!note.empty()) m_log.add(note);
        // What the scene does not need (AUTO logs its chosen integrator's after it chose).
        const std::string integrator = m_params.get<std::string>("integrator", "PATH");
        if (integrator != "AUTO") {
            const std::string skipped = scene_skips_line(scene_skips(integrator, scene));
            if (!skipped.empty()) m_log.add(LogLevel::Info, skipped);
        }
        RenderContext ctx{m_cancel, m_counters, m_threads, m_aovs.get(), &m_log};
        m_integrator->render(scene, *m_film, ctx);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stats.render_seconds = seconds;
        if (m_cancel.cancelled()) end_phase = SessionPhase::Cancelled;
    } catch (const Cancelled&) {
        end_phase = SessionPhase::Cancelled;
    } catch (const std::exception& e) {
        end_phase = SessionPhase::Failed;
        error = e.what();
    } catch (...) {
        end_phase = SessionPhase::Failed;
        error = "unknown error in the render thread";
    }
    // A cancel before the integrator's driver ran (during the scene build, say) leaves no stop reason of its own.
    if (end_phase == SessionPhase::Cancelled && StopReason(m_counters.stop_reason.load()) == StopReason::Running)
        m_counters.stop_reason.store(decltype(m_counters.stop_reason.load())(StopReason::Cancelled));
    std::lock_guard<std::mutex> lock(m_mutex);
    m_phase = end_phase;
    m_error = error;
    m_stats.paths = m_counters.paths;
    m_stats.rays = m_counters.rays;
    m_stats.nan_samples = m_counters.nan_samples;
    if (m_stats.render_seconds > 0) m_stats.samples_per_second = double(m_stats.paths) / m_stats.render_seconds;
    if (m_stats.nan_samples)
        m_log.add(std::to_string(m_stats.nan_samples) + " non-finite or negative samples were dropped");
    m_finished = true;
    m_finished_cv.notify_all();
}

bool Session::wait(double timeout_s) {
    std::unique_lock<std::mutex> lock(m_mutex);
    if (!m_started) return true;
    return m_finished_cv.wait_for(lock, std::chrono::duration<double>(std::max(0.0, timeout_s)),
                                  [this] { return m_finished; });
}

void Session::cancel() { m_cancel.cancel(); }

void Session::join() {
    if (m_worker.joinable()) m_worker.join();
}

SessionProgress Session::progress() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    SessionProgress p;
    p.phase = m_phase;
    p.work_done = m_counters.work_done;
    p.work_total = m_counters.work_total;
    p.unit = m_unit;
    p.stage = m_counters.stage.snapshot();
    p.method = m_counters.method.get();
    p.fraction = p.work_total > 0 ? double(p.work_done) / double(p.work_total) : 0.0;
    p.relative_error = m_counters.relative_error;
    p.noise_unavailable = m_counters.noise_unavailable;
    p.stop_reason = StopReason(m_counters.stop_reason.load());
    if (m_phase == SessionPhase::Done) p.fraction = 1.0;
    if (m_started) p.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start_time).count();
    return p;
}

SessionStats Session::stats() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    SessionStats s = m_stats;
    s.stages = m_counters.stage.finished();
    if (!m_finished) {
        s.paths = m_counters.paths;
        s.rays = m_counters.rays;
        s.nan_samples = m_counters.nan_samples;
        if (m_phase == SessionPhase::Rendering) {
            s.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_render_start).count();
            if (s.render_seconds > 0) s.samples_per_second = double(s.paths) / s.render_seconds;
        }
    }
    return s;
}

std::optional<std::string> Session::error() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_error;
}

std::vector<std::string> Session::take_log() { return m_log.take(); }
std::vector<LogEntry> Session::take_log_entries() { return m_log.take_entries(); }

void Session::add_log(std::string message) { m_log.add(std::move(message)); }

std::vector<std::string> Session::strategy_pass_names(int max_depth) {
    std::vector<std::string> names;
    for (const StrategyId& id : StrategyImages::strategies(max_depth))
        for (bool unweighted : {false, true}) names.push_back(StrategyImages::name(id, unweighted));
    return names;
}

std::vector<std::pair<std::string, int>> Session::pass_names() {
    std::vector<std::pair<std::string, int>> names = {{"Combined", 4}, {"Noise", 1}};
    for (const auto& spec : AovFilm::pass_specs()) names.push_back(spec);
    return names;
}

std::vector<float> Session::get_pass(const std::string& name, int* channels) const {
    if (name == "Combined") {
        *channels = 4;
        std::vector<float> rgba = m_film->combined();
        if (m_exposure != 1.f)  // Film > Exposure scales the light, not the alpha
            for (size_t i = 0; i < rgba.size(); i += 4)
                for (size_t c = 0; c < 3; ++c) rgba[i + c] *= m_exposure;
        return rgba;
    }
    if (name == "Noise") {
        *channels = 1;
        std::vector<float> noise = m_film->noise();
        if (m_exposure != 1.f)
            for (float& v : noise) v *= m_exposure;
        return noise;
    }
    return m_aovs->get(name, channels);
}

}  // namespace candela
