// The parallel loop every integrator uses: work items (tiles, photon batches) are handed to a TBB arena
// capped at the render's thread count. Work items must write disjoint outputs; results never depend on
// which thread ran an item or in which order, so the thread count cannot change an image.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>

namespace candela {

/// Shared cancellation flag: set from any thread (Blender's Esc), polled by workers between work items.
class CancelToken {
public:
    void cancel() { m_cancelled.store(true, std::memory_order_relaxed); }
    bool cancelled() const { return m_cancelled.load(std::memory_order_relaxed); }

private:
    std::atomic<bool> m_cancelled{false};
};

/// The number of worker threads a request of `threads` means: 0 = every hardware thread.
int resolve_thread_count(int threads);

/// Calls body(i) for every i in [0, count) on `threads` threads. Items not yet started when `cancel`
/// fires are skipped. The first exception thrown by a body is rethrown here after the others stop.
void parallel_for(int threads, size_t count, const std::function<void(size_t)>& body,
                  const CancelToken* cancel = nullptr);

}  // namespace candela
