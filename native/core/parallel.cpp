#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <thread>

namespace candela {

int resolve_thread_count(int threads) {
    if (threads > 0) return threads;
    const unsigned hw = std::thread::hardware_concurrency();
    return hw > 0 ? static_cast<int>(hw) : 1;
}

void parallel_for(int threads, size_t count, const std::function<void(size_t)>& body, const CancelToken* cancel) {
    const int n = resolve_thread_count(threads);
    auto run_item = [&](size_t i) {
        if (cancel && cancel->cancelled()) return;
        body(i);
    };
    if (n == 1 || count <= 1) {
        for (size_t i = 0; i < count; ++i) run_item(i);
        return;
    }
    tbb::task_arena arena(n);
    arena.execute([&] {
        // simple_partitioner with grain 1: each tile is one task, so load balances across uneven tiles.
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, count, 1),
            [&](const tbb::blocked_range<size_t>& r) {
                for (size_t i = r.begin(); i != r.end(); ++i) run_item(i);
            },
            tbb::simple_partitioner());
    });
}

}  // namespace candela
