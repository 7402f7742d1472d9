#include "session/viewport_session.h"

#include <pthread.h>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "integrators/integrator.h"
#include "scene/camera.h"
#include "scene/mesh_bvh_cache.h"
#include "scene/scene.h"
#include "session/memory_estimate.h"

namespace candela {

namespace {

using clock = std::chrono::steady_clock;

double seconds_since(clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); }

/// Keys of a view that are the session's, not the camera's.
bool is_session_key(const std::string& key) { return key == "pixel_size" || key == "start_resolution"; }

/// The largest power-of-two multiple d of pixel_size for which the view at 1/d of its size has at most
/// start_resolution² pixels (Cycles' calculate_resolution_divider_for_resolution).
int start_divider(int width, int height, int pixel_size, int start_resolution) {
    int64_t w = std::max(1, width / pixel_size), h = std::max(1, height / pixel_size);
    const int64_t limit = int64_t(start_resolution) * start_resolution;
    int d = pixel_size;
    while (w * h > limit && (w > 1 || h > 1) && d < (1 << 20)) {
        w = std::max<int64_t>(1, w / 2);
        h = std::max<int64_t>(1, h / 2);
        d *= 2;
    }
    return d;
}

int ceil_div(int a, int b) { return (a + b - 1) / b; }

/// Puts into `p` the integrator the viewport renders with: the chosen one if it renders in the viewport
/// (IntegratorEntry::viewport) and through this camera, else PATH. Returns the header's note for a fallback, "" if
/// there is none.
std::string choose_viewport_integrator(Params& p, const Camera& camera) {
    const IntegratorEntry& chosen = find_integrator(p.get<std::string>("integrator", "PATH"));
    std::string why;
    if (!chosen.viewport)
        why = " does not render progressively";
    else if ((camera.is_panoramic() && !chosen.panoramic) || (chosen.needs_camera_connection && !camera.connectable()))
        why = " cannot see through " + camera.not_connectable_kind();
    if (why.empty()) return std::string();
    p.set("integrator", std::string("PATH"));
    return std::string(chosen.label) + why + ": the viewport shows Path Tracing";
}

}  // namespace

struct ViewportSession::Request {
    std::unique_ptr<SceneArrays> arrays;  // a new scene, or null
    std::optional<Params> settings, view;
    Affine view_xf;
    std::shared_ptr<CancelToken> render_cancel, build_cancel;
    uint64_t restart = 0;
};

ViewportSession::ViewportSession(int threads) : m_threads(resolve_thread_count(threads)) {
    m_cache = std::make_unique<MeshBvhCache>(threads);
    m_render_cancel = std::make_shared<CancelToken>();
    m_build_cancel = std::make_shared<CancelToken>();
    m_worker = std::thread([this] { run(); });
}

ViewportSession::~ViewportSession() { stop(); }

void ViewportSession::stop() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_quit = true;
        m_render_cancel->cancel();
        m_build_cancel->cancel();
    }
    m_cv.notify_all();
    if (m_worker.joinable()) m_worker.join();
    // The scene's BVHs before the cache holding their device (the worker is gone: nobody else touches them).
    m_scene.reset();
    m_cache.reset();
    std::lock_guard<std::mutex> lock(m_mutex);
    m_shown = Level();
    m_rendering = Level();
    m_status.phase = "stopped";
}

uint64_t ViewportSession::update_scene(SceneArrays arrays, Params settings) {
    arrays.validate();
    auto owned = std::make_unique<SceneArrays>(std::move(arrays));
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_quit) return 0;
    m_pending_arrays = std::move(owned);
    m_settings = std::move(settings);
    m_dirty = true;
    m_paused = false;
    ++m_restarts;
    m_render_cancel->cancel();
    m_build_cancel->cancel();  // a newer scene supersedes the one being built
    m_status.phase = "pending";
    m_status.error.reset();
    m_build_error.reset();
    m_cv.notify_all();
    return m_restarts;
}

uint64_t ViewportSession::update_settings(Params settings) {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_quit) return 0;
    m_settings = std::move(settings);
    m_dirty = true;
    m_paused = false;
    ++m_restarts;
    m_render_cancel->cancel();
    m_status.phase = "pending";
    m_status.error.reset();
    m_cv.notify_all();
    return m_restarts;
}

uint64_t ViewportSession::set_view(Params view, const Affine& camera_to_world) {
    Params probe = view;
    Camera check(probe, camera_to_world);  // throws for a bad view, here and not on the worker
    const int pixel_size = view.get<int>("pixel_size", 1), start = view.get<int>("start_resolution", 64);
    if (pixel_size < 1 || pixel_size > 64) throw InvalidParameter("viewport pixel_size must be between 1 and 64");
    if (start < 1) throw InvalidParameter("viewport start_resolution must be at least 1");
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_quit) return 0;
    m_view = std::move(view);
    m_view_xf = camera_to_world;
    m_dirty = true;
    m_paused = false;
    ++m_restarts;
    m_render_cancel->cancel();  // the scene build (if any) goes on: the view does not change the scene
    if (m_status.phase != "building") m_status.phase = "pending";
    m_status.error.reset();
    m_cv.notify_all();
    return m_restarts;
}

void ViewportSession::pause() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_paused = true;
    m_render_cancel->cancel();
}

void ViewportSession::run() {
    // Named, so tests (and `top -H`) can tell that no viewport thread outlives its session.
    pthread_setname_np(pthread_self(), "candela-view");
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_cv.wait(lock, [this] { return m_quit || (m_dirty && !m_paused); });
        if (m_quit) return;
        Request r;
        r.arrays = std::move(m_pending_arrays);
        r.settings = m_settings;
        r.view = m_view;
        r.view_xf = m_view_xf;
        r.restart = m_restarts;
        m_dirty = false;
        m_render_cancel = std::make_shared<CancelToken>();
        if (r.arrays) m_build_cancel = std::make_shared<CancelToken>();
        r.render_cancel = m_render_cancel;
        r.build_cancel = m_build_cancel;
        m_restart_time = clock::now();
        m_status.seconds_to_first_image = -1.0;
        lock.unlock();
        try {
            process(r);
        } catch (const Cancelled&) {
        } catch (const std::exception& e) {
            fail(e.what());
        } catch (...) {
            fail("unknown error in the viewport render thread");
        }
        lock.lock();
    }
}

void ViewportSession::fail(const std::string& message) {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_status.phase = "failed";
    m_status.error = message;
}

void ViewportSession::process(Request& r) {
    if (r.arrays) {
        if (!r.settings) throw InternalError("viewport scene without settings");
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_status.phase = "building";
        }
        // The scene is built with the settings' camera (a placeholder: each level sets the view's camera).
        const auto t0 = clock::now();
        std::unique_ptr<Scene> scene;
        try {
            scene = std::make_unique<Scene>(*r.arrays, *r.settings, r.build_cancel.get(), m_cache.get());
        } catch (const Cancelled&) {
            throw;
        } catch (const std::exception& e) {
            // The scene cannot be built: show nothing stale, keep the message until the next scene update.
            m_scene.reset();
            std::lock_guard<std::mutex> lock(m_mutex);
            m_build_error = e.what();
            m_status.phase = "failed";
            m_shown = Level();
            m_rendering = Level();
            return;
        }
        m_cache->end_build();
        r.arrays.reset();
        const bool empty = scene->lights().empty() && is_black(scene->lights().background());
        m_scene = std::move(scene);
        std::lock_guard<std::mutex> lock(m_mutex);
        m_status.build_seconds = seconds_since(t0);
        m_status.scene_bytes = m_scene->stats().embree_bytes + m_scene->stats().shading_bytes;
        m_status.bvh_built = m_cache->built();
        m_status.bvh_reused = m_cache->reused();
        if (empty) m_log.add("the scene has no lights and a black world: the image is black");
    }
    if (!m_scene || !r.settings || !r.view) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_status.phase = m_build_error ? "failed" : "idle";  // a scene that cannot be built stays failed
        return;
    }
    render_view(*r.settings, *r.view, r.view_xf, r.restart);
}

void ViewportSession::render_view(const Params& settings, const Params& view, const Affine& camera_to_world,
                                  uint64_t restart) {
    std::shared_ptr<CancelToken> cancel;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        cancel = m_render_cancel;
    }
    const int width = view.require<int>("width"), height = view.require<int>("height");
    const int bx0 = view.get<int>("crop_x0", 0), by0 = view.get<int>("crop_y0", 0);
    const int bx1 = view.get<int>("crop_x1", width), by1 = view.get<int>("crop_y1", height);
    if (bx0 < 0 || by0 < 0 || bx1 > width || by1 > height || bx0 >= bx1 || by0 >= by1)
        throw InvalidParameter("the viewport's render border is empty or outside the view");
    const int pixel_size = view.get<int>("pixel_size", 1);
    const float aspect_x = view.get<float>("pixel_aspect_x", 1.f), aspect_y = view.get<float>("pixel_aspect_y", 1.f);
    const int final_samples = settings.get<int>("samples", 64);
    const int first = start_divider(bx1 - bx0, by1 - by0, pixel_size, view.get<int>("start_resolution", 64));

    for (int d = first;; d /= 2) {
        const bool last = d <= pixel_size;
        // The level's frame: the view at 1/d, rounded up; its pixels are W/fw × H/fh view pixels, so the pixel
        // aspect keeps the viewplane exactly the view's.
        const int fw = ceil_div(width, d), fh = ceil_div(height, d);
        Params p = settings;
        for (const auto& [key, value] : view.values())
            if (!is_session_key(key)) p.set(key, value);
        p.set("width", int64_t(fw));
        p.set("height", int64_t(fh));
        p.set("pixel_aspect_x", double(aspect_x) * width / (double(fw) * d));
        p.set("pixel_aspect_y", double(aspect_y) * height / (double(fh) * d));
        p.set("samples", int64_t(last ? final_samples : 1));
        p.set("time_limit", 0.0);
        p.set("noise_threshold", 0.0);
        // The border in level pixels: every level pixel it touches.
        const int x0 = std::min(fw - 1, int(int64_t(bx0) * fw / width));
        const int y0 = std::min(fh - 1, int(int64_t(by0) * fh / height));
        const int x1 = std::clamp(int((int64_t(bx1) * fw + width - 1) / width), x0 + 1, fw);
        const int y1 = std::clamp(int((int64_t(by1) * fh + height - 1) / height), y0 + 1, fh);
        m_scene->set_camera(p, camera_to_world);
        const std::string note = choose_viewport_integrator(p, m_scene->camera());
        auto integrator = make_integrator(p);
        const WorkBudget budget = integrator->budget();
        auto film = std::make_shared<Film>(x1 - x0, y1 - y0, x0, y0, p.get<int>("tile_size", 32));
        auto counters = std::make_shared<RenderCounters>();
        counters->work_total = budget.total;
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            if (cancel->cancelled()) return;
            m_rendering = Level{film, counters, fw, fh, x0, y0, d, ++m_level_ids, false, restart};
            m_status.phase = "rendering";
            m_status.pixel_size = d;
            m_status.samples_total = last ? int(budget.total) : 1;
            m_status.note = note;
            m_status.film_bytes = size_t(double(film->width()) * film->height() * film_bytes_per_pixel());
        }
        // The render settings' thread count (Blender's Performance > Threads), else the session's.
        RenderContext ctx{*cancel, *counters,
                          p.has("threads") ? resolve_thread_count(p.get<int>("threads", 0)) : m_threads, nullptr,
                          &m_log};
        integrator->render(*m_scene, *film, ctx);
        std::lock_guard<std::mutex> lock(m_mutex);
        if (cancel->cancelled() || restart != m_restarts) return;
        m_rendering.finished = true;
        m_shown = m_rendering;
        if (m_status.seconds_to_first_image < 0.0) m_status.seconds_to_first_image = seconds_since(m_restart_time);
        if (last) {
            m_status.phase = "done";
            return;
        }
    }
}

uint64_t ViewportSession::image_version() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    const Level& level = m_rendering.film && m_rendering.counters->work_done >= 1 ? m_rendering : m_shown;
    if (!level.film) return 0;
    // A new level, or more tiles of the level's pass (each finished tile adds its paths).
    return (level.id << 40) | std::min<uint64_t>(level.counters->paths.load(), (uint64_t(1) << 40) - 1);
}

uint64_t ViewportSession::image_request() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    const Level& level = m_rendering.film && m_rendering.counters->work_done >= 1 ? m_rendering : m_shown;
    return level.film ? level.request : 0;
}

bool ViewportSession::image(uint64_t since, ViewportImage* out) const {
    Level level;
    uint64_t version;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        level = m_rendering.film && m_rendering.counters->work_done >= 1 ? m_rendering : m_shown;
        if (!level.film) return false;
        version = (level.id << 40) | std::min<uint64_t>(level.counters->paths.load(), (uint64_t(1) << 40) - 1);
    }
    if (version <= since) return false;
    // The film is shared: the worker may go on adding tiles while it is copied (tile by tile, under their locks).
    out->version = version;
    out->request = level.request;
    out->frame_width = level.frame_width;
    out->frame_height = level.frame_height;
    out->x0 = level.x0;
    out->y0 = level.y0;
    out->width = level.film->width();
    out->height = level.film->height();
    out->pixel_size = level.pixel_size;
    out->samples = int(level.counters->work_done.load());
    out->rgba = level.film->combined();
    return true;
}

ViewportStatus ViewportSession::status() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    ViewportStatus s = m_status;
    if (m_rendering.counters) s.samples_done = int(m_rendering.counters->work_done.load());
    if (m_build_error) s.error = m_build_error;  // a scene that cannot be built outranks a render error
    return s;
}

std::vector<std::string> ViewportSession::take_log() { return m_log.take(); }
std::vector<LogEntry> ViewportSession::take_log_entries() { return m_log.take_entries(); }

}  // namespace candela
