// The ordered parallel loop: work items are produced in parallel, and their results are consumed one at a
// time in item order, so whatever a consumer accumulates (splats on the film, photons in a map, records in a
// cache) is summed in the same order for every thread count. TBB's parallel_pipeline with a serial in-order
// last stage does exactly this; the number of tokens bounds how many produced results wait for their turn,
// which bounds the memory a pass holds (a light-tracing pass keeps max_in_flight splat buffers, not one per
// item).
#pragma once

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <optional>
#include <utility>

#include "core/parallel.h"

namespace candela {

/// Calls produce(i) for i in [0, count) on `threads` threads (0 = all) and consume(i, result) for every produced
/// item in increasing i, never two consumes at once. At most max_in_flight (≥ 1) items are between their produce
/// and their consume. Once `cancel` fires no further item starts; every item produced is still consumed, in order,
/// so a cancelled loop leaves a prefix of the items consumed. The first exception thrown by produce or consume
/// is rethrown here after the others stop.
template <class Produce, class Consume>
void parallel_ordered(int threads, size_t count, size_t max_in_flight, Produce&& produce, Consume&& consume,
                      const CancelToken* cancel = nullptr) {
    using Result = decltype(produce(size_t(0)));
    const int n = resolve_thread_count(threads);
    if (max_in_flight < 1) max_in_flight = 1;
    if (n == 1 || count <= 1) {
        for (size_t i = 0; i < count; ++i) {
            if (cancel && cancel->cancelled()) return;
            consume(i, produce(i));
        }
        return;
    }
    struct Item {
        size_t index;
        std::optional<Result> result;
    };
    size_t next = 0;
    tbb::task_arena arena(n);
    arena.execute([&] {
        tbb::parallel_pipeline(
            max_in_flight,
            tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> size_t {
                if (next >= count || (cancel && cancel->cancelled())) {
                    fc.stop();
                    return 0;
                }
                return next++;
            }) & tbb::make_filter<size_t, Item>(tbb::filter_mode::parallel, [&](size_t i) {
                return Item{i, std::optional<Result>(produce(i))};
            }) & tbb::make_filter<Item, void>(tbb::filter_mode::serial_in_order, [&](Item item) {
                consume(item.index, std::move(*item.result));
            }));
    });
}

}  // namespace candela
