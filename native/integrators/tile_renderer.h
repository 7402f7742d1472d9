// The progressive tile loop shared by camera-driven integrators. The image is refined in passes of
// growing sample counts (1, 1, 2, 4, …, 16 samples per pixel), each pass running over all tiles in
// parallel, so the user sees the whole frame early. A cancel is seen between pixel rows: the tile being
// rendered is abandoned (its pixels keep the passes already added), so workers stop within one row.
// Sample k of pixel (x, y) always uses sampler state (seed, x, y, k) — precisely sample k / B of the
// sampler of noise replicate k mod B (film/noise_estimate.h) — so results are the same for any thread count
// and tile order.
//
// Stopping: after `samples` passes' worth, or earlier by `time_limit` (the next pass is shrunk to what the
// measured time per sample says still fits, and none is started if not even one sample per pixel fits)
// or by `noise_threshold` (checked after every pass once each pixel has k_min_noise_samples samples: the
// render stops when the upper confidence bound of the film's replicate estimate of the relative RMSE is
// under the threshold, so the reported estimate is then under it too, and a low estimate that is low by
// chance — a small border, heavy-tailed samples — does not end the render early).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "film/film.h"
#include "integrators/pixel_sampling.h"
#include "integrators/render_context.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

inline constexpr int k_min_noise_samples = 16;

/// Whether Tracer can continue a path from a camera ray's traced hit: Li(ray, TracedHit, sampler, stats, alpha,
/// aov). Such tracers get their camera rays traced in packets (Scene::intersect_packet).
template <class Tracer, class = void>
struct traces_from_hit : std::false_type {};
template <class Tracer>
struct traces_from_hit<Tracer, std::void_t<decltype(std::declval<const Tracer&>().Li(
                                   std::declval<const Ray&>(), std::declval<const TracedHit&>(), std::declval<Sampler&>(),
                                   std::declval<PathStats&>(), static_cast<float*>(nullptr), static_cast<AovSample*>(nullptr)))>>
    : std::true_type {};

/// Tracer: `Color Li(const Ray&, Sampler&, PathStats&, float* alpha, AovSample* aov) const` (aov: null, or
/// where the tracer records the first surface the camera ray sees; integrators/camera_hit.h).
template <typename Tracer>
void render_progressive(const Scene& scene, Film& film, RenderContext& ctx, const PixelSampling& ps,
                        const Tracer& tracer) {
    const Camera& camera = scene.camera();
    AovFilm* const aovs = ctx.aovs && !ctx.aovs->empty() ? ctx.aovs : nullptr;
    using clock = std::chrono::steady_clock;
    auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    ctx.counters.samples_total = ps.samples;
    const auto start = clock::now();
    double seconds_per_sample = 0.0;  // per sample per pixel, from the last pass
    StopReason stop = StopReason::Running;
    int done = 0, pass_size = 1;
    // Passes double from 1 sample up to a cap. Each pass ends at a barrier (the last tile's thread finishes
    // alone) and with a noise estimate over the film, so small images, whose passes are short, take bigger
    // ones: up to 64 samples while a pass stays under ~4 M samples (256² pixels), 16 for larger images (the
    // display refreshes per finished tile, and a 16-sample pass of a large image is already seconds long) and
    // with a noise threshold (checked between passes). The cap depends on the image only, never on timing, so
    // the film's sums — and the image — stay the same for every thread count.
    constexpr double k_pass_samples = double(1 << 22);
    const int max_pass_size =
        ps.noise_threshold > 0.0
            ? 16
            : std::clamp(int(k_pass_samples / std::max(1.0, double(film.width()) * film.height())), 16, 64);
    while (done < ps.samples && !ctx.cancel.cancelled()) {
        int size = pass_size;
        if (ps.time_limit > 0.0 && done > 0) {
            const double remaining = ps.time_limit - seconds_since(start);
            const int fit = seconds_per_sample > 0.0 ? int(std::min(remaining / seconds_per_sample, 1e9)) : size;
            if (fit < 1) {
                stop = StopReason::TimeLimit;
                break;
            }
            size = std::min(size, fit);
        }
        const int begin = done, end = std::min(ps.samples, done + size);
        const auto pass_start = clock::now();
        parallel_for(
            ctx.threads, film.tiles().size(),
            [&](size_t tile_index) {
                const Tile& tile = film.tiles()[tile_index];
                std::vector<PixelAccum> accum(size_t(tile.width()) * tile.height());
                std::vector<AovAccum> aov_accum(aovs ? accum.size() : 0);
                std::vector<Sampler> replicates;
                for (uint32_t r = 0; r < k_noise_replicates; ++r) replicates.push_back(ps.replicate_sampler(r));
                PathStats stats;
                for (int y = tile.y0; y < tile.y1; ++y) {
                    if (ctx.cancel.cancelled()) return;  // abandon this tile's pass: nothing half-added
                    for (int x = tile.x0; x < tile.x1; ++x) {
                        const int fx = film.origin_x() + x, fy = film.origin_y() + y;  // full-frame pixel
                        PixelAccum& acc = accum[size_t(y - tile.y0) * tile.width() + (x - tile.x0)];
                        // The pass's samples of this pixel, replicate by replicate (sample indices begin..end−1
                        // with s mod k_noise_replicates = r): each replicate's sampler then sees its samples of
                        // the pixel as one run, which is what its per-pixel caches (Sobol seeds) amortise over.
                        // Only the order of the film's sums changes with this, not which samples are taken.
                        //
                        // Camera rays go to Embree in groups of up to eight consecutive samples of one replicate
                        // (tracers that can continue from a traced hit): rays through one pixel traverse the BVH
                        // together several times faster than one by one. The group's rays are made first, then
                        // each path is traced with its sampler positioned again at its own sample (positioning is
                        // cheap within a pixel; the path draws only per-bounce dimensions after the camera's).
                        constexpr int group_size = traces_from_hit<Tracer>::value ? Scene::k_packet_size : 1;
                        for (int first = begin; first < std::min(end, begin + int(k_noise_replicates)); ++first)
                        for (int s0 = first; s0 < end; s0 += group_size * int(k_noise_replicates)) {
                            const uint32_t replicate = noise_replicate_of(uint32_t(s0));
                            Sampler& sampler = replicates[replicate];
                            Ray rays[group_size];
                            int samples[group_size];
                            int n = 0;
                            for (int s = s0; s < end && n < group_size; s += int(k_noise_replicates), ++n) {
                                // Positioning and the filter draw in one visit, so the draw inlines.
                                const Vec2 u_pixel = std::visit(
                                    [&](auto& concrete) {
                                        concrete.start_pixel_sample(uint32_t(fx), uint32_t(fy), index_in_replicate(uint32_t(s)));
                                        return concrete.sample_2d(dimension_index(Dim::Filter));
                                    },
                                    sampler);
                                const Vec2 offset = ps.filter.sample(u_pixel);
                                const Vec2 u_lens = camera.has_aperture() ? get_2d(sampler, Dim::Lens) : Vec2{0.5f, 0.5f};
                                rays[n] = camera.generate_ray({fx + 0.5f + offset.x, fy + 0.5f + offset.y}, u_lens);
                                samples[n] = s;
                            }
                            TracedHit hits[group_size];
                            if constexpr (group_size > 1) scene.intersect_packet(rays, n, hits);
                            for (int j = 0; j < n; ++j) {
                                const int s = samples[j];
                                // Position the sampler at this sample again, even the group's last (the one it
                                // was left at): tracing the earlier paths moved its per-sample state (the Sobol
                                // batch drawn ahead).
                                if (n > 1)
                                    std::visit([&](auto& concrete) {
                                        concrete.start_pixel_sample(uint32_t(fx), uint32_t(fy), index_in_replicate(uint32_t(s)));
                                    }, sampler);
                                float alpha = 1.f;
                                AovSample aov;
                                Color L;
                                AovSample* const aov_out = aovs ? &aov : nullptr;
                                if constexpr (group_size > 1) L = tracer.Li(rays[j], hits[j], sampler, stats, &alpha, aov_out);
                                else L = tracer.Li(rays[j], sampler, stats, &alpha, aov_out);
                                ++stats.paths;
                                // Non-finite or negative radiance never reaches the film: drop and count it.
                                // Debug builds stop right where it arises instead, naming the sample.
                                if (!is_finite(L) || min_component(L) < 0.f) {
#ifndef NDEBUG
                                    throw InternalError("non-finite or negative radiance at pixel (" + std::to_string(fx) +
                                                        ", " + std::to_string(fy) + "), sample " + std::to_string(s));
#endif
                                    ++stats.nan_samples;
                                    L = Color(0.f);
                                }
                                acc.add(L, alpha, replicate);
                                if (aovs) aov_accum[size_t(y - tile.y0) * tile.width() + (x - tile.x0)].add(aov, s == 0);
                            }
                        }
                    }
                }
                film.add_tile(tile_index, accum);
                if (aovs) aovs->add_tile(tile_index, aov_accum);
                stats.flush(ctx.counters);
            },
            &ctx.cancel);
        if (ctx.cancel.cancelled()) break;  // a partly rendered pass stays in the film as it is
        seconds_per_sample = seconds_since(pass_start) / (end - begin);
        done = end;
        ctx.counters.samples_done = done;
        const NoiseEstimate estimate = film.noise_estimate();
        const double error = estimate.relative_rmse;
        ctx.counters.relative_error = std::isfinite(error) ? error : -1.0;
        if (ps.noise_threshold > 0.0 && done >= k_min_noise_samples &&
            estimate.relative_rmse_bound <= ps.noise_threshold) {
            stop = StopReason::NoiseThreshold;
            break;
        }
        if (ps.time_limit > 0.0 && seconds_since(start) >= ps.time_limit && done < ps.samples) {
            stop = StopReason::TimeLimit;
            break;
        }
        pass_size = std::min(pass_size * 2, max_pass_size);
        if (done == 1) pass_size = 1;
    }
    if (ctx.cancel.cancelled()) stop = StopReason::Cancelled;
    else if (stop == StopReason::Running) stop = StopReason::Samples;
    ctx.counters.stop_reason = int(stop);
}

}  // namespace candela
