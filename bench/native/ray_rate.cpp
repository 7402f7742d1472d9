// Raw Embree incoherent-ray rate on a scene dump: the ceiling a path tracer on this scene can approach.
// Rays are made like a path tracer's secondary rays: camera rays find surface points, then each point
// shoots a uniformly random direction over the sphere (incoherent). Only the closest-hit queries are
// timed (bare rtcIntersect1, no shading lookups), on the same thread count as renders. Prints one JSON line.
// --skip-origin runs the same rays through Scene::intersect with the origin triangle skipped by Embree's
// context filter (what the path tracer does), to show that filter's cost.
//   candela_bench_rays DUMP_DIR [--rays N] [--threads T] [--skip-origin]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/scene_dump.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "sampling/warp.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

using namespace candela;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: candela_bench_rays DUMP_DIR [--rays N] [--threads T]\n");
        return 2;
    }
    size_t ray_count = 2'000'000;
    int threads = 0;
    bool skip_origin = false;
    for (int i = 2; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--rays") && i + 1 < argc)
            ray_count = std::stoull(argv[++i]);
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = std::stoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--skip-origin"))
            skip_origin = true;
    }
    try {
        SceneDump dump = read_scene_dump(argv[1]);
        dump.params.set("threads", int64_t(threads));
        dump.arrays.validate();
        const Scene scene(dump.arrays, dump.params, nullptr);
        const Camera& cam = scene.camera();

        // Ray origins on visible surfaces, directions uniform on the sphere.
        std::vector<Ray> rays;
        std::vector<PrimitiveRef> origins;
        rays.reserve(ray_count);
        Pcg32 rng(7, 11);
        size_t attempts = 0;
        while (rays.size() < ray_count && attempts < 4 * ray_count) {
            ++attempts;
            const Ray primary =
                cam.generate_ray({rng.next_float() * cam.full_width(), rng.next_float() * cam.full_height()});
            SurfaceHit hit;
            if (!scene.intersect(primary, &hit)) continue;
            const Vec3 d = sample_uniform_sphere({rng.next_float(), rng.next_float()});
            rays.push_back({spawn_origin(hit.p, hit.ng, d), d, 0.f, 1e30f});
            origins.push_back(hit.primitive);
        }
        if (rays.empty()) throw std::runtime_error("the camera sees no surface");

        const size_t chunk = 4096, chunks = (rays.size() + chunk - 1) / chunk;
        std::vector<uint32_t> hits(chunks, 0);
        const auto t0 = std::chrono::steady_clock::now();
        parallel_for(threads, chunks, [&](size_t c) {
            uint32_t n = 0;
            if (skip_origin) {
                SurfaceHit hit;
                for (size_t i = c * chunk; i < std::min(rays.size(), (c + 1) * chunk); ++i)
                    n += scene.intersect(rays[i], &hit, origins[i]);
                hits[c] = n;
                return;
            }
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (size_t i = c * chunk; i < std::min(rays.size(), (c + 1) * chunk); ++i) {
                const Ray& r = rays[i];
                RTCRayHit rh;
                rh.ray = {r.o.x, r.o.y, r.o.z, r.tmin, r.d.x, r.d.y, r.d.z, 0.f, r.tmax, 0xFFFFFFFFu, 0, 0};
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene.embree_scene(), &context, &rh);
                n += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
            hits[c] = n;
        });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        size_t total_hits = 0;
        for (uint32_t h : hits) total_hits += h;
        std::printf(
            "{\"rays\": %zu, \"seconds\": %.6f, \"rays_per_second\": %.1f, \"hit_fraction\": %.4f, \"threads\": %d, "
            "\"skip_origin\": %s}\n",
            rays.size(), seconds, rays.size() / seconds, double(total_hits) / rays.size(),
            resolve_thread_count(threads), skip_origin ? "true" : "false");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
