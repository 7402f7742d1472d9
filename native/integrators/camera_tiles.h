// The progressive camera tile loop shared by camera-driven integrators: the work unit is one sample per pixel,
// and each pass of the progressive driver (integrators/progressive_driver.h) runs over all tiles in parallel. A
// cancel is seen between pixel rows: the tile being rendered is abandoned (its pixels keep the passes already
// added), so workers stop within one row. Sample k of pixel (x, y) always uses sampler state (seed, x, y, k) —
// precisely sample k / B of the sampler of noise replicate k mod B (film/noise_estimate.h) — so results are the
// same for any thread count and tile order.
#pragma once

#include <algorithm>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "film/film.h"
#include "integrators/pixel_sampling.h"
#include "integrators/progressive_driver.h"
#include "integrators/render_context.h"
#include "sampling/sampler.h"
#include "scene/scene.h"
#include "scene/shutter_time.h"

namespace candela {

/// Whether Tracer can continue a path from a camera ray's traced hit: Li(ray, TracedHit, sampler, stats, alpha,
/// aov). Such tracers get their camera rays traced in packets (Scene::intersect_packet).
template <class Tracer, class = void>
struct traces_from_hit : std::false_type {};
template <class Tracer>
struct traces_from_hit<
    Tracer, std::void_t<decltype(std::declval<const Tracer&>().Li(
                std::declval<const Ray&>(), std::declval<const TracedHit&>(), std::declval<Sampler&>(),
                std::declval<PathStats&>(), static_cast<float*>(nullptr), static_cast<AovSample*>(nullptr)))>>
    : std::true_type {};

/// The largest pass of a camera render. Each pass ends at a barrier (the last tile's thread finishes alone) and
/// with a noise estimate over the film, so small images, whose passes are short, take bigger ones: up to 64
/// samples while a pass stays under ~4 M samples (256² pixels), 16 for larger images (the display refreshes per
/// finished tile, and a 16-sample pass of a large image is already seconds long) and with a noise threshold
/// (checked between passes). The cap depends on the image only, never on timing.
inline int camera_max_pass(const Film& film, const PixelSampling& ps) {
    constexpr double k_pass_samples = double(1 << 22);
    return ps.noise_threshold > 0.0
               ? 16
               : std::clamp(int(k_pass_samples / std::max(1.0, double(film.width()) * film.height())), 16, 64);
}

/// Whether Tracer also splats contributions elsewhere on the film: Li(ray, sampler, stats, alpha, aov, SplatSink).
struct SplatSink {
    SplatBuffer* buffer;
    uint32_t replicate;  // of the camera sample whose path makes the splats
    int x, y;            // the camera sample's full-frame pixel
};
template <class Tracer, class = void>
struct splats_from_camera : std::false_type {};
template <class Tracer>
struct splats_from_camera<
    Tracer, std::void_t<decltype(std::declval<const Tracer&>().Li(
                std::declval<const Ray&>(), std::declval<Sampler&>(), std::declval<PathStats&>(),
                static_cast<float*>(nullptr), static_cast<AovSample*>(nullptr), std::declval<SplatSink>()))>>
    : std::true_type {};

/// One pass [begin, end) of camera samples over one tile at a time, for Tracer: `Color Li(const Ray&, Sampler&,
/// PathStats&, float* alpha, AovSample* aov) const` (aov: null, or where the tracer records the first surface the
/// camera ray sees; integrators/camera_hit.h).
template <typename Tracer>
class CameraTilePass {
public:
    /// `motion_blur`: the tracer renders motion blur (one shutter time per camera path: render_moving); otherwise
    /// a moving scene is rendered at the shutter's middle.
    CameraTilePass(const Scene& scene, Film& film, RenderContext& ctx, const PixelSampling& ps, const Tracer& tracer,
                   bool motion_blur = false)
        : m_scene(scene),
          m_camera(scene.camera()),
          m_film(film),
          m_ctx(ctx),
          m_ps(ps),
          m_tracer(tracer),
          m_aovs(ctx.aovs && !ctx.aovs->empty() ? ctx.aovs : nullptr),
          m_motion(motion_blur && scene.has_motion()) {}

    /// Renders samples [begin, end) of every pixel of tile `tile_index` and adds them to the film; a splatting tracer's
    /// splats go to `splats` (the caller merges them in tile order). Returns false if cancelled (nothing added).
    bool render_tile(size_t tile_index, int begin, int end, SplatBuffer* splats = nullptr) const {
        const Tile& tile = m_film.tiles()[tile_index];
        TileBuffers buffers(tile, m_aovs != nullptr);
        std::vector<Sampler> replicates;
        for (uint32_t r = 0; r < k_noise_replicates; ++r) replicates.push_back(m_ps.replicate_sampler(r));
        PathStats stats;
        for (int y = tile.y0; y < tile.y1; ++y) {
            if (m_ctx.cancel.cancelled()) return false;  // abandon this tile's pass: nothing half-added
            for (int x = tile.x0; x < tile.x1; ++x) {
                const size_t i = size_t(y - tile.y0) * tile.width() + (x - tile.x0);
                render_pixel(m_film.origin_x() + x, m_film.origin_y() + y, begin, end, replicates, stats,
                             buffers.pixels[i], m_aovs ? &buffers.aovs[i] : nullptr, splats);
            }
        }
        m_film.add_tile(tile_index, buffers.pixels);
        if (m_aovs) m_aovs->add_tile(tile_index, buffers.aovs);
        stats.flush(m_ctx.counters);
        return true;
    }

private:
    struct TileBuffers {
        std::vector<PixelAccum> pixels;
        std::vector<AovAccum> aovs;
        TileBuffers(const Tile& tile, bool with_aovs)
            : pixels(size_t(tile.width()) * tile.height()), aovs(with_aovs ? pixels.size() : 0) {}
    };
    static constexpr int k_group_size = traces_from_hit<Tracer>::value ? Scene::k_packet_size : 1;

    /// The pass's samples of full-frame pixel (fx, fy), replicate by replicate (sample indices begin..end−1 with
    /// s mod k_noise_replicates = r): each replicate's sampler then sees its samples of the pixel as one run,
    /// which is what its per-pixel caches (Sobol seeds) amortise over. Only the order of the film's sums changes
    /// with this, not which samples are taken.
    __attribute__((always_inline)) void render_pixel(int fx, int fy, int begin, int end,
                                                     std::vector<Sampler>& replicates, PathStats& stats,
                                                     PixelAccum& acc, AovAccum* aov_acc, SplatBuffer* splats) const {
        for (int first = begin; first < std::min(end, begin + int(k_noise_replicates)); ++first)
            for (int s0 = first; s0 < end; s0 += k_group_size * int(k_noise_replicates))
                render_group(fx, fy, s0, end, replicates[noise_replicate_of(uint32_t(s0))], stats, acc, aov_acc,
                             splats);
    }

    /// Camera rays go to Embree in groups of up to eight consecutive samples of one replicate (s0, s0 + B, …;
    /// tracers that can continue from a traced hit): rays through one pixel traverse the BVH together several
    /// times faster than one by one. The group's rays are made first, then each path is traced with its sampler
    /// positioned again at its own sample (positioning is cheap within a pixel; the path draws only per-bounce
    /// dimensions after the camera's).
    __attribute__((always_inline)) void render_group(int fx, int fy, int s0, int end, Sampler& sampler,
                                                     PathStats& stats, PixelAccum& acc, AovAccum* aov_acc,
                                                     SplatBuffer* splats) const {
        const uint32_t replicate = noise_replicate_of(uint32_t(s0));
        if (m_motion) return render_moving(fx, fy, s0, end, sampler, stats, acc, aov_acc, splats);
        Ray rays[k_group_size];
        int samples[k_group_size];
        int n = 0;
        for (int s = s0; s < end && n < k_group_size; s += int(k_noise_replicates), ++n) {
            rays[n] = camera_ray(fx, fy, s, sampler);
            samples[n] = s;
        }
        TracedHit hits[k_group_size];
        if constexpr (k_group_size > 1) m_scene.intersect_packet(rays, n, hits);
        for (int j = 0; j < n; ++j) {
            const int s = samples[j];
            // Position the sampler at this sample again, even the group's last (the one it was left at): tracing
            // the earlier paths moved its per-sample state (the Sobol batch drawn ahead).
            if (n > 1)
                std::visit(
                    [&](auto& concrete) {
                        concrete.start_pixel_sample(uint32_t(fx), uint32_t(fy), index_in_replicate(uint32_t(s)));
                    },
                    sampler);
            float alpha = 1.f;
            AovSample aov;
            AovSample* const aov_out = m_aovs ? &aov : nullptr;
            Color L;
            if constexpr (k_group_size > 1)
                L = m_tracer.Li(rays[j], hits[j], sampler, stats, &alpha, aov_out);
            else if constexpr (splats_from_camera<Tracer>::value)
                L = m_tracer.Li(rays[j], sampler, stats, &alpha, aov_out, SplatSink{splats, replicate, fx, fy});
            else
                L = m_tracer.Li(rays[j], sampler, stats, &alpha, aov_out);
            ++stats.paths;
            acc.add(checked_radiance(L, fx, fy, s, stats), alpha, replicate);
            if (aov_acc) aov_acc->add(aov, s == 0);
        }
    }

    /// render_group for a scene with motion blur: each camera sample draws its shutter time (shutter_time_of the
    /// sampler's stream key: no sampler dimension is taken) and its whole path — the camera ray, every bounce and
    /// shadow ray, shading and splats — sees the scene at that time (a ShutterScope). The camera rays are traced
    /// one by one (each has its own time).
    void render_moving(int fx, int fy, int s0, int end, Sampler& sampler, PathStats& stats, PixelAccum& acc,
                       AovAccum* aov_acc, SplatBuffer* splats) const {
        const uint32_t replicate = noise_replicate_of(uint32_t(s0));
        int n = 0;
        for (int s = s0; s < end && n < k_group_size; s += int(k_noise_replicates), ++n) {
            const float time = std::visit(
                [&](auto& concrete) {
                    concrete.start_pixel_sample(uint32_t(fx), uint32_t(fy), index_in_replicate(uint32_t(s)));
                    return shutter_time_of(concrete.sample_stream_key());
                },
                sampler);
            const ShutterScope scope(time);
            const Ray ray = camera_ray(fx, fy, s, sampler);
            float alpha = 1.f;
            AovSample aov;
            AovSample* const aov_out = m_aovs ? &aov : nullptr;
            Color L;
            if constexpr (k_group_size > 1) {
                TracedHit hit;
                hit.found = m_scene.intersect(ray, &hit.hit);
                L = m_tracer.Li(ray, hit, sampler, stats, &alpha, aov_out);
            } else if constexpr (splats_from_camera<Tracer>::value) {
                L = m_tracer.Li(ray, sampler, stats, &alpha, aov_out, SplatSink{splats, replicate, fx, fy});
            } else {
                L = m_tracer.Li(ray, sampler, stats, &alpha, aov_out);
            }
            ++stats.paths;
            acc.add(checked_radiance(L, fx, fy, s, stats), alpha, replicate);
            if (aov_acc) aov_acc->add(aov, s == 0);
        }
    }

    /// The camera ray of sample s of pixel (fx, fy): the sampler positioned there, the filter offset drawn by
    /// filter importance sampling, the lens point if the camera has an aperture.
    __attribute__((always_inline)) Ray camera_ray(int fx, int fy, int s, Sampler& sampler) const {
        // Positioning and the filter draw in one visit, so the draw inlines.
        const Vec2 u_pixel = std::visit(
            [&](auto& concrete) {
                concrete.start_pixel_sample(uint32_t(fx), uint32_t(fy), index_in_replicate(uint32_t(s)));
                return concrete.sample_2d(dimension_index(Dim::Filter));
            },
            sampler);
        const Vec2 offset = m_ps.filter.sample(u_pixel);
        const Vec2 u_lens = m_camera.has_aperture() ? get_2d(sampler, Dim::Lens) : Vec2{0.5f, 0.5f};
        return m_camera.generate_ray({fx + 0.5f + offset.x, fy + 0.5f + offset.y}, u_lens);
    }

    /// Non-finite or negative radiance never reaches the film: it is dropped and counted. Debug builds stop right
    /// where it arises instead, naming the sample.
    static __attribute__((always_inline)) Color checked_radiance(Color L, int fx, int fy, int s, PathStats& stats) {
        if (is_finite(L) && !(min_component(L) < 0.f)) return L;
#ifndef NDEBUG
        throw InternalError("non-finite or negative radiance at pixel (" + std::to_string(fx) + ", " +
                            std::to_string(fy) + "), sample " + std::to_string(s));
#endif
        ++stats.nan_samples;
        return Color(0.f);
    }

    const Scene& m_scene;
    const Camera& m_camera;
    Film& m_film;
    RenderContext& m_ctx;
    const PixelSampling& m_ps;
    const Tracer& m_tracer;
    AovFilm* const m_aovs;
    const bool m_motion;  // one shutter time per camera path (render_moving)
};

/// Renders ps.samples camera samples per pixel with `tracer`, progressively through the driver (`motion_blur`: see
/// CameraTilePass).
template <typename Tracer>
StopReason render_camera_progressive(const Scene& scene, Film& film, RenderContext& ctx, const PixelSampling& ps,
                                     const Tracer& tracer, bool motion_blur = false) {
    const CameraTilePass<Tracer> tiles(scene, film, ctx, ps, tracer, motion_blur);
    ProgressivePlan plan;
    plan.total = ps.samples;
    plan.max_pass = camera_max_pass(film, ps);
    plan.time_limit = ps.time_limit;
    plan.noise_threshold = ps.noise_threshold;
    return run_progressive(
        ctx, plan,
        [&](int64_t begin, int64_t end) {
            parallel_for(
                ctx.threads, film.tiles().size(),
                [&](size_t tile_index) { tiles.render_tile(tile_index, int(begin), int(end)); }, &ctx.cancel);
        },
        [&] { return film.noise_estimate(); });
}

}  // namespace candela
