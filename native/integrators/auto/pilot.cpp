// The pilot render (pilot.h): pilot pixels' paths traced by the pilot's path tracer (pilot_tracer.h), their
// tallies summed per pixel and turned into the energy and variance shares by path class.
#include "integrators/auto/pilot.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "integrators/auto/pilot_tracer.h"

namespace candela {

namespace {

using pilot::PathTally;
using pilot::PilotTracer;
using pilot::Uniform;

/// One pilot pixel's sums over its paths (luminance).
struct PixelSums {
    double s[k_path_classes] = {}, s2[k_path_classes] = {};
    double total = 0.0, total2 = 0.0, through = 0.0, sad = 0.0;
    uint64_t caustic_paths = 0;
};

double sample_variance(double s, double s2, int n) { return n > 1 ? std::max(0.0, (s2 - s * s / n) / (n - 1)) : 0.0; }

}  // namespace

const char* path_class_name(PathClass c) {
    switch (c) {
    case PathClass::Emitted: return "emitted";
    case PathClass::Direct: return "direct";
    case PathClass::Indirect: return "indirect";
    default: return "caustic";
    }
}

PilotSettings pilot_settings_for(int x0, int y0, int width, int height, int samples, int max_bounces, uint64_t seed,
                                 int threads) {
    PilotSettings s;
    const int short_side = std::min(width, height);
    s.downscale = short_side >= 128 ? 4 : short_side >= 32 ? 2 : 1;
    s.samples = std::clamp(samples / 8, 2, 8);  // at least 2: a per-pixel variance
    s.max_bounces = max_bounces;
    s.seed = seed;
    s.threads = threads;
    s.x0 = x0;
    s.y0 = y0;
    s.width = width;
    s.height = height;
    return s;
}

double PilotResult::variance_share(PathClass c) const {
    double sum = 0.0;
    for (double v : variance) sum += v;
    return sum > 0.0 ? variance[int(c)] / sum : 0.0;
}

std::string PilotResult::summary() const {
    char buf[512];
    auto pct = [](double x) { return 100.0 * x; };
    std::snprintf(buf, sizeof buf,
                  "Auto: pilot %d px x %d paths (%.1f ms): energy emitted %.0f %%, direct %.0f %%, indirect %.0f %%, "
                  "caustic %.0f %%; variance emitted %.0f %%, direct %.0f %%, indirect %.0f %%, caustic %.0f %%; "
                  "through transmissive %.0f %%; fireflies %.0f %% of the variance in 1 %% of the pixels; %llu "
                  "paths with caustic light",
                  pixels, samples, milliseconds, pct(energy_share(PathClass::Emitted)),
                  pct(energy_share(PathClass::Direct)), pct(energy_share(PathClass::Indirect)),
                  pct(energy_share(PathClass::Caustic)), pct(variance_share(PathClass::Emitted)),
                  pct(variance_share(PathClass::Direct)), pct(variance_share(PathClass::Indirect)),
                  pct(variance_share(PathClass::Caustic)), pct(through_transmissive_share()), pct(firefly_share),
                  static_cast<unsigned long long>(caustic_path_count));
    return buf;
}

PilotResult run_pilot(const Scene& scene, const PilotSettings& s, const CancelToken* cancel) {
    const auto t0 = std::chrono::steady_clock::now();
    const int d = std::max(1, s.downscale);
    const int pw = std::max(1, (s.width + d - 1) / d), ph = std::max(1, (s.height + d - 1) / d);
    const int n = std::max(1, s.samples);
    const PilotTracer tracer(scene, s.max_bounces);
    const Camera& camera = scene.camera();
    std::vector<PixelSums> pixels(size_t(pw) * ph);
    std::vector<uint64_t> row_rays(size_t(ph), 0);
    parallel_for(
        resolve_thread_count(s.threads), size_t(ph),
        [&](size_t row) {
            const int py = int(row);
            for (int px = 0; px < pw; ++px) {
                const size_t index = size_t(py) * pw + px;
                Uniform u(hash_combine(s.seed, 0x70696c6f74ULL), index);  // "pilot"
                PixelSums& acc = pixels[index];
                // The block of film pixels this pilot pixel covers (the last ones clipped to the film).
                const float bx = float(s.x0 + px * d), by = float(s.y0 + py * d);
                const float bw = float(std::min(d, s.width - px * d)), bh = float(std::min(d, s.height - py * d));
                for (int k = 0; k < n; ++k) {
                    const Vec2 up = u.next2();
                    const Vec2 ul = u.next2();
                    const Ray ray = camera.generate_ray({bx + up.x * bw, by + up.y * bh}, ul);
                    PathTally t;
                    if (ray.tmax > ray.tmin) tracer.trace(ray, u, t, row_rays[row]);
                    double total = 0.0;
                    for (int c = 0; c < k_path_classes; ++c) {
                        const double l = luminance(t.c[c]);
                        acc.s[c] += l;
                        acc.s2[c] += l * l;
                        total += l;
                    }
                    if (luminance(t.c[int(PathClass::Caustic)]) > 0.f) ++acc.caustic_paths;
                    acc.total += total;
                    acc.total2 += total * total;
                    acc.through += luminance(t.through_transmissive);
                    acc.sad += luminance(t.specular_after_diffuse);
                }
            }
        },
        cancel);

    PilotResult r;
    r.pixels = pw * ph;
    r.samples = n;
    const double P = double(r.pixels);
    std::vector<double> pixel_variance(pixels.size());
    double class_var_of_mean[k_path_classes] = {}, var_of_mean = 0.0;
    for (size_t i = 0; i < pixels.size(); ++i) {  // in pixel order: deterministic sums
        const PixelSums& p = pixels[i];
        for (int c = 0; c < k_path_classes; ++c) {
            r.mean[c] += p.s[c] / n / P;
            const double v = sample_variance(p.s[c], p.s2[c], n);
            r.variance[c] += v;
            class_var_of_mean[c] += v / n / (P * P);
        }
        pixel_variance[i] = sample_variance(p.total, p.total2, n);
        r.total_variance += pixel_variance[i];
        var_of_mean += pixel_variance[i] / n / (P * P);
        r.total_mean += p.total / n / P;
        r.through_transmissive_mean += p.through / n / P;
        r.specular_after_diffuse_mean += p.sad / n / P;
        r.caustic_path_count += p.caustic_paths;
    }
    r.standard_error = std::sqrt(var_of_mean);
    for (int c = 0; c < k_path_classes; ++c) r.class_standard_error[c] = std::sqrt(class_var_of_mean[c]);
    const size_t top = std::max<size_t>(1, pixel_variance.size() / 100);
    std::partial_sort(pixel_variance.begin(), pixel_variance.begin() + long(top), pixel_variance.end(),
                      std::greater<double>());
    double top_sum = 0.0;
    for (size_t i = 0; i < top; ++i) top_sum += pixel_variance[i];
    r.firefly_share = r.total_variance > 0.0 ? top_sum / r.total_variance : 0.0;
    for (uint64_t x : row_rays) r.rays += x;
    r.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace candela
