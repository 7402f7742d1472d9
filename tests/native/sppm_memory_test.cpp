// SPPM's memory estimate bounds what a render allocates: the peak resident growth of a whole session (scene,
// film, visible points and their grid, the photons, the gather rounds' pair buffers) measured against
// Session::estimate_memory. The scene is chosen so that the gather needs several rounds at the pair budget
// (k_pair_budget, sppm_gather.h): a large initial radius puts each photon in the spheres of dozens of points.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "integrators/photon_map/sppm_gather.h"
#include "reference_scenes.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

#if !defined(__SANITIZE_ADDRESS__)  // ASan's shadow memory and quarantine make resident sizes meaningless
TEST(SppmMemory, EstimateBoundsThePeakOfARenderWithFullGatherRounds) {
    Params p = basic_params(160, 160, 1, 8);
    p.set("integrator", std::string("SPPM"));
    p.set("sppm_photons", int64_t(100000));
    p.set("sppm_radius", 0.4);  // the box is 2 wide: hundreds of the 160² points around each photon on a wall
    p.set("threads", int64_t(2));
    const SceneArrays arrays = cornell_box();
    const MemoryEstimate e = Session::estimate_memory(arrays, p);
    // A fixed mmap threshold: every buffer over 256 KB is mapped and returned to the system when freed. glibc's
    // default raises the threshold after each such free, so later large buffers come from the per-thread heaps and
    // stay resident after they are freed; the peak then depended on which of the two threads freed what first
    // (measured 82–115 MB in repeated runs of the same render), a measure of the allocator, not of the render.
    // (So a render under glibc's defaults can hold up to about a third more than the estimate, freed but resident.)
    mallopt(M_MMAP_THRESHOLD, 256 * 1024);
    malloc_trim(0);
    { std::ofstream("/proc/self/clear_refs") << "5"; }  // resets VmHWM (the peak) to the current RSS
    const long before_kb = proc_status_kb("VmRSS:");
    RenderResult r;
    long peak_kb = 0;
    {
        r = render(arrays, p);
        peak_kb = proc_status_kb("VmHWM:");
    }
    ASSERT_GT(before_kb, 0);
    ASSERT_EQ(r.samples_done, 1);
    const double measured = double(peak_kb - before_kb) * 1024.0;
    std::printf(
        "  SPPM 160x160, 100 k photons: peak %.1f MB; estimate %.1f MB (integrator %.1f, of which gather "
        "rounds %.1f; film %.1f; geometry %.1f)\n",
        measured / 1e6, e.total_bytes() / 1e6, e.integrator_bytes / 1e6, k_gather_round_bytes / 1e6, e.film_bytes / 1e6,
        e.geometry_bytes / 1e6);
    // The render must really have needed the round buffers, or the test cannot tell an estimate without them.
    EXPECT_GT(measured, e.total_bytes() - 0.75 * k_gather_round_bytes);
    EXPECT_GE(e.total_bytes(), measured);
}
#endif

}  // namespace
}  // namespace candela::test
