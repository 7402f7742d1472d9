// The progressive driver every integrator renders through. An integrator counts its work in its own unit —
// camera samples per pixel, light paths per pixel, photon passes, SPPM iterations, Metropolis mutations per
// pixel — and hands the driver a function that renders a range [begin, end) of those units into the film. The
// driver runs the ranges as passes of growing size (1, 1, 2, 4, … units, up to a cap), so the user sees the
// whole frame early, and owns what every integrator needs around them: the budget, the time limit, the
// noise-threshold stop, cancel, the progress counters and the stop reason.
//
// Stopping: after `total` units, or earlier by `time_limit` (the next pass is shrunk to what the measured time per
// unit says still fits, and none is started if not even one unit fits) or by `noise_threshold` (checked after
// every pass once `min_noise_units` are done: the render stops when the upper confidence bound of the film's
// replicate estimate of the relative RMSE is under the threshold, so the reported estimate is then under it too,
// and a low estimate that is low by chance — a small border, heavy-tailed samples — does not end the render
// early). An integrator whose noise estimate is not honest (a cache or photon map shared by both noise
// replicates) passes no estimate: the noise is then reported as unknown and the noise stop is off, with a log
// line if one was asked for.
//
// Pass sizes depend on the budget and the cap only, never on timing (the time limit only ends the render
// earlier), so the film's sums — and the image — are the same for every thread count.
#pragma once

#include <cstdint>
#include <functional>

#include "film/noise_estimate.h"
#include "integrators/render_context.h"

namespace candela {

/// Units of work before the noise threshold is first checked (each pixel then has enough samples per replicate
/// for the estimate's confidence bound to mean something).
inline constexpr int64_t k_min_noise_samples = 16;

struct ProgressivePlan {
    int64_t total = 1;             // the budget, in the integrator's unit
    int64_t max_pass = 16;         // the largest pass, in units
    double time_limit = 0.0;       // seconds of rendering; 0 = none
    double noise_threshold = 0.0;  // relative RMSE to stop at; 0 = off
    int64_t min_noise_units = k_min_noise_samples;
};

/// Renders units [begin, end) into the film; returns early (keeping what it added) once ctx.cancel fires.
using RenderPass = std::function<void(int64_t begin, int64_t end)>;
/// The film's current noise estimate (Film::noise_estimate), or an empty function where it is not honest.
using NoiseSource = std::function<NoiseEstimate()>;

/// Runs the passes of `plan` (see above); sets ctx.counters' work_total, work_done, relative_error and
/// stop_reason, and returns the stop reason.
StopReason run_progressive(RenderContext& ctx, const ProgressivePlan& plan, const RenderPass& pass,
                           const NoiseSource& noise);

}  // namespace candela
