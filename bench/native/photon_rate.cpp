// Photon shooting rate on a scene dump (`make bench`, issue 16): photon paths per second and the rays they cast
// per second, as a share of the raw Embree incoherent ray rate measured in the same run on the same scene (rays
// from visible surface points in uniform directions, bare rtcIntersect1: the ceiling), and the kd-tree build time
// of the stored photons (target: 10 M photons in ≤ 2 s on 2 cores). Prints one JSON line.
//   candela_bench_photons DUMP_DIR [--paths N] [--threads T] [--raw-rays R]
// (--raw-rays: rays per raw-rate measurement, 2 M by default; a small R keeps a profiler's run on the shooting.)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "cli/scene_dump.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "integrators/photon_map/photon_shooting.h"
#include "sampling/warp.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"

using namespace candela;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// Process CPU seconds (all threads): on a machine shared with other work, rates per CPU second stay comparable
/// where wall-clock rates do not.
double cpu_now() { return double(std::clock()) / CLOCKS_PER_SEC; }

/// Raw incoherent closest-hit rate (as candela_bench_rays measures it), per wall-clock and per CPU second.
double raw_ray_rate(const Scene& scene, int threads, size_t count, double* per_cpu_second) {
    const Camera& cam = scene.camera();
    std::vector<Ray> rays;
    Pcg32 rng(7, 11);
    for (size_t attempts = 0; rays.size() < count && attempts < 4 * count; ++attempts) {
        const Ray primary =
            cam.generate_ray({rng.next_float() * cam.full_width(), rng.next_float() * cam.full_height()});
        SurfaceHit hit;
        if (!scene.intersect(primary, &hit)) continue;
        const Vec3 d = sample_uniform_sphere({rng.next_float(), rng.next_float()});
        rays.push_back({spawn_origin(hit.p, hit.ng, d), d, 0.f, 1e30f});
    }
    if (rays.empty()) throw std::runtime_error("the camera sees no surface");
    const size_t chunk = 4096, chunks = (rays.size() + chunk - 1) / chunk;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_now();
    parallel_for(threads, chunks, [&](size_t c) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t i = c * chunk; i < std::min(rays.size(), (c + 1) * chunk); ++i) {
            const Ray& r = rays[i];
            RTCRayHit rh;
            rh.ray = {r.o.x, r.o.y, r.o.z, r.tmin, r.d.x, r.d.y, r.d.z, 0.f, r.tmax, 0xFFFFFFFFu, 0, 0};
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene.embree_scene(), &context, &rh);
        }
    });
    *per_cpu_second = double(rays.size()) / (cpu_now() - c0);
    return double(rays.size()) / seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: candela_bench_photons DUMP_DIR [--paths N] [--threads T] [--raw-rays R]\n");
        return 2;
    }
    int64_t paths = 4'000'000;
    int threads = 0;
    size_t raw_rays = 2'000'000;
    for (int i = 2; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--paths") && i + 1 < argc)
            paths = std::stoll(argv[++i]);
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = std::stoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--raw-rays") && i + 1 < argc)
            raw_rays = size_t(std::stoll(argv[++i]));
    }
    try {
        SceneDump dump = read_scene_dump(argv[1]);
        dump.params.set("threads", int64_t(threads));
        dump.arrays.validate();
        const Scene scene(dump.arrays, dump.params, nullptr);
        const EmitterSet emitters(scene.lights(), scene.bounds());
        PhotonRules rules;
        const PhotonTracer tracer(scene, emitters, rules);
        CancelToken cancel;
        RenderCounters counters;
        RenderContext ctx{cancel, counters, threads};

        double raw_cpu_before = 0.0, raw_cpu_after = 0.0;
        const double raw_before = raw_ray_rate(scene, threads, raw_rays, &raw_cpu_before);
        auto t0 = std::chrono::steady_clock::now();
        double c0 = cpu_now();
        PhotonShot shot = shoot_photons(tracer, emitters, PhotonStore::Global, paths, 1, 0, ctx, "Tracing photons");
        const double shoot_s = seconds_since(t0), shoot_cpu = cpu_now() - c0;
        const size_t stored = shot.photons.size();
        // FNV-1a over the photon array's bytes: equal hashes for equal photon sets (a speed-up that claims to keep
        // the photons bit for bit is checked by it).
        uint64_t photons_hash = 0xcbf29ce484222325ULL;
        for (const Photon& p : shot.photons) {
            unsigned char bytes[sizeof(Photon)];
            std::memcpy(bytes, &p, sizeof(Photon));
            for (unsigned char c : bytes) photons_hash = (photons_hash ^ c) * 0x100000001b3ULL;
        }
        const uint64_t rays = counters.rays.load();
        t0 = std::chrono::steady_clock::now();
        c0 = cpu_now();
        const PhotonMap map = build_photon_map(std::move(shot), ctx, "Building photon map");
        const double build_s = seconds_since(t0), build_cpu = cpu_now() - c0;
        const double raw_after = raw_ray_rate(scene, threads, raw_rays, &raw_cpu_after);
        const double raw = 0.5 * (raw_before + raw_after), raw_cpu = 0.5 * (raw_cpu_before + raw_cpu_after);
        std::printf(
            "{\"photon_paths\": %lld, \"stored_photons\": %zu, \"shoot_seconds\": %.4f, "
            "\"photon_paths_per_second\": %.1f, \"stored_photons_per_second\": %.1f, "
            "\"photon_rays_per_second\": %.1f, \"raw_rays_per_second\": %.1f, \"share_of_raw\": %.4f, "
            "\"build_seconds\": %.4f, \"build_seconds_per_10M\": %.4f, \"map_bytes_per_photon\": %.2f, "
            "\"shoot_cpu_seconds\": %.4f, \"build_cpu_seconds\": %.4f, \"share_of_raw_per_cpu_second\": %.4f, "
            "\"threads\": %d, \"photons_hash\": \"%016llx\"}\n",
            (long long)paths, stored, shoot_s, double(paths) / shoot_s, double(stored) / shoot_s,
            double(rays) / shoot_s, raw, double(rays) / shoot_s / raw, build_s,
            stored ? build_s * 1e7 / double(stored) : 0.0, stored ? map.memory_bytes() / double(stored) : 0.0,
            shoot_cpu, build_cpu, (double(rays) / shoot_cpu) / raw_cpu, resolve_thread_count(threads),
            (unsigned long long)photons_hash);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
