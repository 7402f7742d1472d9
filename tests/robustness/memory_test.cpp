// Memory: a scene too large for the memory available is refused before anything is built, naming its biggest
// mesh; and the estimate behind that refusal really bounds what a build allocates (measured here: the peak
// resident growth while Embree builds the BVH).
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "core/error.h"
#include "scene/scene.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

// A small quad, a 65,024-triangle sphere and a 1,000-triangle sphere drawn twice.
SceneArrays three_meshes() {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_quad_z(-1, 1, -1, 1, -3, m));
    b.add_instance(b.add_sphere(1.f, 256, 128, m));
    const uint32_t small = b.add_sphere(0.2f, 20, 26, m);
    b.add_instance(small);
    b.add_instance(small);
    b.add_point_light(Vec3(0.f), Color(10.f));
    return b.arrays();
}

TEST(Memory, SceneTooLargeForTheLimitIsRefusedNamingTheBiggestMesh) {
    Params p = basic_params(64, 48, 1, 1);
    p.set("memory_limit_mb", 2.0);  // far below the ~12 MB the sphere needs
    try {
        Session s(three_meshes(), p);
        FAIL() << "a scene over the memory limit was accepted";
    } catch (const InvalidScene& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("mesh 1 with 65,024 triangles"), std::string::npos) << m;
        EXPECT_NE(m.find("memory_limit_mb"), std::string::npos) << m;
        EXPECT_NE(m.find("2 MB are available"), std::string::npos) << m;
    }
    // The same scene under a limit it fits renders.
    p.set("memory_limit_mb", 200.0);
    const RenderResult r = render(three_meshes(), p);
    EXPECT_GT(r.mean_rgb, 0.0);
}

TEST(Memory, ResolutionTooLargeForTheLimitIsRefusedBeforeAllocation) {
    Params p = basic_params(20000, 20000, 1, 1);  // 400 Mpixel: ~38 GB of film
    p.set("memory_limit_mb", 16000.0);
    try {
        Session s(three_meshes(), p);
        FAIL() << "a film over the memory limit was accepted";
    } catch (const InvalidParameter& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("20000x20000"), std::string::npos) << m;
        EXPECT_NE(m.find("GB"), std::string::npos) << m;
        EXPECT_NE(m.find("resolution"), std::string::npos) << m;
    }
}

// Without a limit, the machine's MemAvailable is the limit, and a normal scene fits it.
TEST(Memory, TheDefaultLimitIsTheAvailableMemory) {
    const double available = available_memory_bytes();
    ASSERT_GT(available, 0.0) << "/proc/meminfo has no MemAvailable";
    SceneArrays a = three_meshes();
    const MemoryEstimate e = Session::estimate_memory(a, basic_params(64, 48, 1, 1));
    EXPECT_EQ(e.limit_source, "available memory (MemAvailable)");
    EXPECT_NEAR(e.limit_bytes, available, 0.2 * available);  // other processes allocate meanwhile
    EXPECT_TRUE(e.fits());
    EXPECT_EQ(e.biggest_mesh, 1);
}

#if !defined(__SANITIZE_ADDRESS__)  // ASan's shadow memory and quarantine make resident sizes meaningless
// The estimate must stay above the real peak (else the refusal would not prevent an OOM kill) without being
// absurdly above it (else renders that fit would be refused): measured ≤ estimate ≤ 3 × measured, for a smooth
// mesh and a random triangle soup (Embree's spatial splits duplicate more references for overlapping triangles).
TEST(Memory, EstimateBoundsThePeakOfARealBuild) {
    for (int soup = 0; soup < 2; ++soup) {
        MeshBuilder b;
        const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
        if (soup) {
            std::mt19937 g(7);
            std::uniform_real_distribution<float> u(0.f, 1.f);
            const uint32_t n = 250000;
            for (uint32_t t = 0; t < n; ++t) {
                const float cx = u(g), cy = u(g), cz = u(g), size = 0.3f * u(g);
                for (int k = 0; k < 3; ++k)
                    b.positions.insert(b.positions.end(), {cx + size * u(g), cy + size * u(g), cz + size * u(g)});
                b.triangles.insert(b.triangles.end(), {3 * t, 3 * t + 1, 3 * t + 2});
                b.tri_material.push_back(m);
            }
            b.mesh_tri_start.push_back(n);
            b.add_instance(0);
        } else {
            b.add_instance(b.add_sphere(1.f, 512, 256, m));
        }
        b.add_point_light(Vec3(0.f), Color(1.f));
        const SceneArrays a = b.arrays();
        const Params p = basic_params(4, 4, 1, 1);
        const MemoryEstimate e = Session::estimate_memory(a, p);
        malloc_trim(0);
        { std::ofstream("/proc/self/clear_refs") << "5"; }  // resets VmHWM (the peak) to the current RSS
        const long before_kb = proc_status_kb("VmRSS:");
        long peak_kb = 0;
        {
            const Scene scene(a, p, nullptr);
            peak_kb = proc_status_kb("VmHWM:");
        }
        ASSERT_GT(before_kb, 0);
        const double measured = double(peak_kb - before_kb) * 1024.0;
        const double triangles = double(b.triangles.size() / 3);
        std::printf("  %s: %.0f triangles, peak %.1f MB (%.0f B/triangle), estimate %.1f MB (%.0f B/triangle)\n",
                    soup ? "soup  " : "sphere", triangles, measured / 1e6, measured / triangles, e.geometry_bytes / 1e6,
                    e.geometry_bytes / triangles);
        EXPECT_GE(e.geometry_bytes, measured);
        EXPECT_LE(e.geometry_bytes, 3.0 * measured);
    }
}
#endif

}  // namespace
}  // namespace candela::test
