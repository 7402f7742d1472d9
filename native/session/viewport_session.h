// The 3D viewport's render session: one long-lived worker thread that keeps a built scene, renders it through
// the view's camera and restarts whenever the view, the settings or the scene change, coarse to fine.
//
// Coarse to fine (Cycles' viewport "start resolution" and "pixel size"): after a restart the view is rendered at
// 1/d of its resolution for the largest power of two d that leaves at most start_resolution² pixels, with one
// sample per pixel; then at d/2, d/4, ... (one sample each), and finally at `pixel_size` (1, or 2 on a HiDPI
// screen) with the viewport sample limit, refining for as long as the user looks. Each level is a complete
// render of its own film through the same integrator, so the first image after a view change costs about
// 1/d² of one full sample.
//
// Scene updates (update_scene) are validated on the caller's thread and built on the worker with a mesh BVH
// cache (scene/mesh_bvh_cache.h): meshes whose vertices and triangles did not change keep their BVHs, so moving
// objects rebuilds only the top-level BVH. A view change never rebuilds the scene (Scene::set_camera).
//
// Threads: the caller (Blender's main thread) only stores requests, cancels the current render and reads the
// newest image; the worker does every build and render. The destructor cancels and joins: no thread outlives
// the session. Errors of a build or render are kept for status() (the viewport header shows them) and
// cleared by the next request.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/message_log.h"
#include "core/params.h"
#include "core/transform.h"
#include "film/film.h"
#include "input/scene_arrays.h"
#include "integrators/render_context.h"

namespace candela {

class MeshBvhCache;
class Scene;

struct ViewportImage {
    uint64_t version = 0;                   // grows with every change of what image() returns
    uint64_t request = 0;                   // the request (update_scene/update_settings/set_view) whose render it is
    int frame_width = 0, frame_height = 0;  // the view's frame in this level's pixels
    int x0 = 0, y0 = 0;                     // the film's origin in that frame (a render border)
    int width = 0, height = 0;              // the film
    int pixel_size = 1;                     // view pixels per film pixel (about: the frame is rounded up)
    int samples = 0;                        // samples per pixel the film has (at least)
    std::vector<float> rgba;                // width × height RGBA, rows bottom to top
};

struct ViewportStatus {
    std::string phase = "idle";  // idle, pending (a request not taken yet), building, rendering, done, failed, stopped
    int samples_done = 0, samples_total = 0;
    int pixel_size = 0;                    // of the level being rendered
    double build_seconds = 0.0;            // of the latest scene build
    double seconds_to_first_image = -1.0;  // from the latest restart to its first image (< 0: none yet)
    size_t scene_bytes = 0, film_bytes = 0;
    size_t bvh_built = 0, bvh_reused = 0;  // mesh BVHs built / taken from the cache, over the session
    std::string note;  // the viewport renders with PATH instead of the chosen integrator, and why ("": not)
    std::optional<std::string> error;
};

class ViewportSession {
public:
    /// `threads` as the `threads` param (0 = every hardware thread): Embree's builds, and renders whose settings
    /// have no `threads`.
    explicit ViewportSession(int threads);
    ~ViewportSession();
    ViewportSession(const ViewportSession&) = delete;
    ViewportSession& operator=(const ViewportSession&) = delete;

    /// New scene content and render settings (the params of a render; width/height and the camera come from
    /// set_view). Validates on the calling thread (throws InvalidScene / InvalidParameter), builds on the worker.
    /// Each request returns its number (ViewportImage::request tells which request an image belongs to).
    uint64_t update_scene(SceneArrays arrays, Params settings);
    /// New render settings only (integrator, samples, ...): restarts without rebuilding.
    uint64_t update_settings(Params settings);
    /// The view: camera params as Camera reads them, `width`/`height` the view's size in pixels, an optional
    /// border (crop_x0..crop_y1, view pixels), `pixel_size` and `start_resolution`; camera_to_world is rigid.
    /// Validated here (throws InvalidParameter).
    uint64_t set_view(Params view, const Affine& camera_to_world);
    /// Stops rendering (nothing is lost: the next request restarts).
    void pause();
    /// Cancels whatever runs, joins the worker and frees the scene; later requests are ignored. The destructor
    /// calls it too.
    void stop();

    /// Version of the newest image (0: none yet); cheap, for polling.
    uint64_t image_version() const;
    /// The request the newest image belongs to (0: none yet): after a view change the caller can wait a moment
    /// for the first image of the new view (the coarsest level takes milliseconds) and draw that at once.
    uint64_t image_request() const;
    /// The newest image, if its version is above `since`.
    bool image(uint64_t since, ViewportImage* out) const;
    ViewportStatus status() const;
    std::vector<std::string> take_log();
    std::vector<LogEntry> take_log_entries();

private:
    struct Request;
    void run();
    void process(Request& request);
    void render_view(const Params& settings, const Params& view, const Affine& camera_to_world, uint64_t restart);
    void fail(const std::string& message);  // a render error (cleared by the next request)

    const int m_threads;
    std::unique_ptr<MeshBvhCache> m_cache;  // worker only
    std::unique_ptr<Scene> m_scene;         // worker only (image() never touches it)

    mutable std::mutex m_mutex;
    std::condition_variable m_cv;
    bool m_quit = false, m_dirty = false, m_paused = false;
    std::unique_ptr<SceneArrays> m_pending_arrays;
    std::optional<Params> m_settings;
    std::optional<Params> m_view;
    Affine m_view_xf;
    uint64_t m_restarts = 0;                       // requests so far
    std::shared_ptr<CancelToken> m_render_cancel;  // of the render in progress
    std::shared_ptr<CancelToken> m_build_cancel;   // of the scene build in progress

    // What image() shows: the last finished level, or the level being rendered once it has a first pass.
    struct Level {
        std::shared_ptr<Film> film;
        std::shared_ptr<RenderCounters> counters;
        int frame_width = 0, frame_height = 0, x0 = 0, y0 = 0, pixel_size = 1;
        uint64_t id = 0;
        bool finished = false;
        uint64_t request = 0;
    };
    Level m_shown, m_rendering;
    uint64_t m_level_ids = 0;
    std::chrono::steady_clock::time_point m_restart_time;
    ViewportStatus m_status;
    std::optional<std::string> m_build_error;  // until the next update_scene
    MessageLog m_log;      // the scene build's and the integrators' lines (ctx.log), drained by take_log
    std::thread m_worker;  // last: started after everything above exists
};

}  // namespace candela
