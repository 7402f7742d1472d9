#include "integrators/progressive_driver.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace candela {

StopReason run_progressive(RenderContext& ctx, const ProgressivePlan& plan, const RenderPass& pass,
                           const NoiseSource& noise) {
    using clock = std::chrono::steady_clock;
    auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    ctx.counters.work_total = plan.total;
    ctx.counters.noise_unavailable = !noise;
    if (plan.noise_threshold > 0.0 && !noise)
        ctx.log("the noise threshold is off for this integrator: its noise estimate would not be honest");
    const bool noise_stop = plan.noise_threshold > 0.0 && noise;
    const int64_t max_pass = std::max<int64_t>(1, plan.max_pass);
    const auto start = clock::now();
    double seconds_per_unit = 0.0;  // from the last pass
    StopReason stop = StopReason::Running;
    int64_t done = 0, pass_size = 1;
    while (done < plan.total && !ctx.cancel.cancelled()) {
        int64_t size = pass_size;
        if (plan.time_limit > 0.0 && done > 0) {
            const double remaining = plan.time_limit - seconds_since(start);
            const int64_t fit = seconds_per_unit > 0.0 ? int64_t(std::min(remaining / seconds_per_unit, 1e9)) : size;
            if (fit < 1) {
                stop = StopReason::TimeLimit;
                break;
            }
            size = std::min(size, fit);
        }
        const int64_t begin = done, end = std::min(plan.total, done + size);
        const auto pass_start = clock::now();
        pass(begin, end);
        if (ctx.cancel.cancelled()) break;  // a partly rendered pass stays in the film as it is
        seconds_per_unit = seconds_since(pass_start) / double(end - begin);
        done = end;
        ctx.counters.work_done = done;
        if (noise) {
            const NoiseEstimate estimate = noise();
            ctx.counters.relative_error = std::isfinite(estimate.relative_rmse) ? estimate.relative_rmse : -1.0;
            if (noise_stop && done >= plan.min_noise_units && estimate.relative_rmse_bound <= plan.noise_threshold) {
                stop = StopReason::NoiseThreshold;
                break;
            }
        }
        if (plan.time_limit > 0.0 && seconds_since(start) >= plan.time_limit && done < plan.total) {
            stop = StopReason::TimeLimit;
            break;
        }
        pass_size = std::min(pass_size * 2, max_pass);
        if (done == 1) pass_size = 1;
    }
    if (ctx.cancel.cancelled())
        stop = StopReason::Cancelled;
    else if (stop == StopReason::Running)
        stop = StopReason::Samples;
    ctx.counters.stop_reason = int(stop);
    return stop;
}

}  // namespace candela
