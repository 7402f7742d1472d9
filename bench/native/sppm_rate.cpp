// SPPM's speed on two reference scenes (tests/native/reference_scenes.h: the Cornell box and the glass sphere's
// caustic), against PATH at the same samples per pixel in the same run: SPPM's iterations (camera pass, photon pass,
// gather) cost in wall-clock and CPU seconds, and the ratio to PATH's (a baseline that moves with the machine's
// load, so the ratio stays comparable where seconds do not), and the photon pass alone (the same photon paths
// shot without SPPM), so that SPPM's CPU time besides shooting is the camera pass and the gather. Prints one JSON
// line per scene.
//   candela_bench_sppm [--size W] [--iterations N] [--photons P] [--threads T] [--repeats R]
// With --slope: the log-log slope of SPPM's RMSE against iterations (--from 4 to --to 64, doubling) on both scenes at α = 2/3 and α = 1,
// against PATH at --reference-samples (default 16384) samples per pixel on a 16-pixel-wide image, the reference's
// own per-pixel variance (from its Noise pass) subtracted from the mean squared error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "integrators/photon_map/photon_shooting.h"
#include "reference_scenes.h"
#include "scene/scene.h"
#include "test_helpers.h"

using namespace candela;
using namespace candela::test;

namespace {

struct Timing {
    double wall = 0.0, cpu = 0.0;  // the fastest of the repeats
    double mean = 0.0;
};

double cpu_now() { return double(std::clock()) / CLOCKS_PER_SEC; }

Timing time_render(const SceneArrays& arrays, const Params& p, int repeats) {
    Timing t;
    t.wall = t.cpu = 1e30;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpu_now();
        const RenderResult res = render(arrays, p);
        t.wall = std::min(t.wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        t.cpu = std::min(t.cpu, cpu_now() - c0);
        t.mean = res.mean_rgb;
    }
    return t;
}

/// The photon pass alone: `iterations` streams of `photons` paths stored as SPPM stores them, in CPU seconds.
double shooting_cpu_seconds(const SceneArrays& arrays, const Params& p, int iterations, int64_t photons) {
    const PreparedScene prepared(arrays, p);
    const Scene& scene = prepared.scene();
    const EmitterSet emitters(scene.lights(), scene.bounds());
    PhotonRules rules;
    rules.max_bounces = int(p.get<int>("max_bounces", 12));
    rules.alpha_threshold = 0.f;
    const PhotonTracer tracer(scene, emitters, rules);
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, int(p.get<int>("threads", 0))};
    const double c0 = cpu_now();
    for (int i = 0; i < iterations; ++i)
        shoot_photons(tracer, emitters, PhotonStore::Indirect, photons, 1, 2 + uint32_t(i), ctx, "Tracing photons");
    return cpu_now() - c0;
}

double luminance_of(const RenderResult& r, size_t i) {
    return 0.2126 * r.rgba[4 * i] + 0.7152 * r.rgba[4 * i + 1] + 0.0722 * r.rgba[4 * i + 2];
}

/// Relative MSE of `r` against `ref` per pixel (luminance), less the reference's own variance.
double relative_mse(const RenderResult& r, const RenderResult& ref) {
    const size_t n = size_t(r.width) * r.height;
    double se2 = 0.0, mean = 0.0, sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double d = luminance_of(r, i) - luminance_of(ref, i);
        sum += d * d;
        se2 += double(ref.noise[i]) * ref.noise[i];
        mean += luminance_of(ref, i);
    }
    mean /= double(n);
    return (sum - se2) / double(n) / (mean * mean);
}

void slope_run(const char* name, int reference_samples, int64_t photons, int from, int to) {
    const bool cornell = !std::strcmp(name, "cornell");
    const SceneArrays arrays = cornell ? cornell_box() : glass_caustic();
    Params p = basic_params(16, cornell ? 16 : 12, reference_samples, cornell ? 5 : 6);
    p.set("threads", int64_t(2));
    p.set("integrator", std::string("PATH"));
    const RenderResult ref = render(arrays, p);
    for (double alpha : {2.0 / 3.0, 1.0}) {
        std::vector<double> xs, ys;
        std::string points;
        for (int it = from; it <= to; it *= 2) {
            double mse = 0.0;
            for (int seed = 1; seed <= 2; ++seed) {
                Params q = p;
                q.set("integrator", std::string("SPPM"));
                q.set("samples", int64_t(it));
                q.set("seed", int64_t(seed));
                q.set("sppm_photons", photons);
                q.set("sppm_alpha", alpha);
                mse += 0.5 * relative_mse(render(arrays, q), ref);
            }
            xs.push_back(std::log(double(it)));
            ys.push_back(0.5 * std::log(std::max(mse, 1e-30)));
            points += (points.empty() ? "" : ", ") + std::to_string(std::sqrt(std::max(mse, 0.0)));
        }
        double mx = 0.0, my = 0.0, sxy = 0.0, sxx = 0.0;
        for (size_t i = 0; i < xs.size(); ++i) mx += xs[i] / double(xs.size()), my += ys[i] / double(xs.size());
        for (size_t i = 0; i < xs.size(); ++i) sxy += (xs[i] - mx) * (ys[i] - my), sxx += (xs[i] - mx) * (xs[i] - mx);
        std::printf(
            "{\"scene\": \"%s\", \"alpha\": %.4f, \"reference_samples\": %d, \"photons_per_iteration\": %lld, "
            "\"iterations\": [%d, %d], \"relative_rmse\": [%s], \"rmse_slope\": %.4f}\n",
            name, alpha, reference_samples, (long long)photons, from, to, points.c_str(), sxy / sxx);
        std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
    int size = 64, iterations = 16, threads = 2, repeats = 2;
    int64_t photons = 100000;
    bool slope = false;
    int reference_samples = 16384, from = 4, to = 64;
    for (int i = 1; i < argc; ++i) {
        auto next = [&] { return i + 1 < argc ? argv[++i] : "0"; };
        if (!std::strcmp(argv[i], "--size"))
            size = std::stoi(next());
        else if (!std::strcmp(argv[i], "--iterations"))
            iterations = std::stoi(next());
        else if (!std::strcmp(argv[i], "--photons"))
            photons = std::stoll(next());
        else if (!std::strcmp(argv[i], "--threads"))
            threads = std::stoi(next());
        else if (!std::strcmp(argv[i], "--repeats"))
            repeats = std::stoi(next());
        else if (!std::strcmp(argv[i], "--slope"))
            slope = true;
        else if (!std::strcmp(argv[i], "--from"))
            from = std::stoi(next());
        else if (!std::strcmp(argv[i], "--to"))
            to = std::stoi(next());
        else if (!std::strcmp(argv[i], "--reference-samples"))
            reference_samples = std::stoi(next());
    }
    try {
        if (slope) {
            for (const char* name : {"cornell", "caustic"}) slope_run(name, reference_samples, photons, from, to);
            return 0;
        }
        for (const char* name : {"cornell", "caustic"}) {
            const bool cornell = !std::strcmp(name, "cornell");
            const SceneArrays arrays = cornell ? cornell_box() : glass_caustic();
            Params p = basic_params(size, cornell ? size : size * 3 / 4, iterations, cornell ? 5 : 6);
            p.set("threads", int64_t(threads));
            p.set("integrator", std::string("SPPM"));
            p.set("sppm_photons", photons);
            const Timing sppm = time_render(arrays, p, repeats);
            const double shoot_cpu = shooting_cpu_seconds(arrays, p, iterations, photons);
            p.set("integrator", std::string("PATH"));
            const Timing path = time_render(arrays, p, repeats);
            std::printf(
                "{\"scene\": \"%s\", \"size\": %d, \"iterations\": %d, \"photons_per_iteration\": %lld, "
                "\"threads\": %d, \"sppm_seconds\": %.3f, \"sppm_cpu_seconds\": %.3f, \"path_seconds\": %.3f, "
                "\"path_cpu_seconds\": %.3f, \"sppm_over_path\": %.3f, \"sppm_over_path_cpu\": %.3f, "
                "\"shooting_cpu_seconds\": %.3f, \"sppm_cpu_seconds_besides_shooting\": %.3f, "
                "\"sppm_mean\": %.5f, \"path_mean\": %.5f}\n",
                name, size, iterations, (long long)photons, threads, sppm.wall, sppm.cpu, path.wall, path.cpu,
                sppm.wall / path.wall, sppm.cpu / path.cpu, shoot_cpu, sppm.cpu - shoot_cpu, sppm.mean, path.mean);
            std::fflush(stdout);
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
