// Cancel latency, as a deterministic bound in work: once the cancel flag is set, every worker of the camera tile
// pass finishes at most the pixel row it is in (the flag is checked before each row), and the driver starts no
// further pass. So the work done after a cancel is at most threads × tile width × pass size camera samples,
// whatever the machine's load; its time is that many samples at the render's own rate (Esc → stop ≈ one poll
// of the add-on plus that, measured by tests/robustness/test_blender_cancel.py and printed there).
#include <gtest/gtest.h>

#include <atomic>

#include "integrators/camera_tiles.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// A tracer that counts its paths and cancels the render at the `cancel_at`-th.
struct CountingTracer {
    CancelToken* cancel;
    uint64_t cancel_at;
    mutable std::atomic<uint64_t> paths{0};
    Color Li(const Ray&, Sampler&, PathStats&, float* alpha, AovSample*) const {
        *alpha = 1.f;
        if (++paths == cancel_at) cancel->cancel();
        return Color(0.5f);
    }
};

TEST(Cancel, WorkAfterTheCancelFlagIsAtMostOneRowPerWorker) {
    MeshBuilder b;
    b.add_instance(b.add_quad_z(-1.f, 1.f, -1.f, 1.f, -2.f, b.add_material(Color(0.5f), Color(0.f))));
    const SceneArrays arrays = b.arrays();
    for (int threads : {1, 2, 4}) {
        for (uint64_t cancel_at : {1ull, 777ull, 20000ull}) {
            Params p = basic_params(96, 64, 100000, 1);
            p.set("tile_size", int64_t(16));
            const Scene scene(arrays, p, nullptr);
            Film film(96, 64, 0, 0, 16);
            CancelToken cancel;
            RenderCounters counters;
            RenderContext ctx{cancel, counters, threads};
            const PixelSampling ps = PixelSampling::from_params(p);
            CountingTracer tracer{&cancel, cancel_at};
            const StopReason stop = render_camera_progressive(scene, film, ctx, ps, tracer);
            EXPECT_EQ(stop, StopReason::Cancelled);
            const uint64_t pass = uint64_t(camera_max_pass(film, ps));
            const uint64_t bound = uint64_t(threads) * 16u * pass;  // one row of a 16-pixel tile, one pass's samples
            EXPECT_LE(tracer.paths.load() - cancel_at, bound) << threads << " threads, cancel at " << cancel_at;
        }
    }
}

}  // namespace
}  // namespace candela::test
