// PHOTON's caustic map converges to the exact image as photons grow (integrators/photon_map/; docs/photon-mapping.md,
// "Verification"). The density estimate of N photons within a disc of radius r has a variance ∝ 1/(N r²) and a
// kernel bias ∝ r² (Jensen 2001, §7; the bias law is tested in photon_map_test.cpp):
//   - the glass slab (docs/verification.md §2.10): all of the floor's light passes the glass, so it is all caustic
//     photons; the floor's irradiance is uniform, so a fixed radius has no bias: the image mean is ρ·T·E₀/π with
//     T = 12/13, and the RMSE falls as N^(−1/2);
//   - a glass sphere's caustic against BDPT's image: with the radius shrinking as N^(−1/6) (the MSE-optimal rate
//     in two dimensions: bias² ∝ r⁴ and variance ∝ 1/(N r²) then both fall as N^(−2/3)), the RMSE falls at least
//     as N^(−1/3) (faster while the radius is not small against the caustic's width).
// The error measured is the maps' alone: the camera side's own variance (next-event estimation, gather rays, the
// lookup point within a pixel), the per-pixel standard error of each render, is subtracted from each pixel's
// squared error; given the maps, a pixel's mean is unbiased for what those maps give.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/vec.h"
#include "reference_scenes.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

std::vector<double> pixel_luminance(const RenderResult& r) {
    std::vector<double> out(size_t(r.width) * r.height);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = luminance(Color(r.rgba[4 * i], r.rgba[4 * i + 1], r.rgba[4 * i + 2]));
    return out;
}

double fit_slope(const std::vector<double>& xs, const std::vector<double>& ys) {
    double mx = 0.0, my = 0.0;
    for (size_t i = 0; i < xs.size(); ++i) mx += xs[i] / xs.size(), my += ys[i] / xs.size();
    double sxy = 0.0, sxx = 0.0;
    for (size_t i = 0; i < xs.size(); ++i) sxy += (xs[i] - mx) * (ys[i] - my), sxx += (xs[i] - mx) * (xs[i] - mx);
    return sxy / sxx;
}

/// Relative MSE of `r` against `ref` (per-pixel values; `ref_noise` their standard errors, or empty for an exact
/// reference), both renders' own per-pixel variances subtracted.
double map_mse(const RenderResult& r, const std::vector<double>& ref, const std::vector<float>& ref_noise) {
    const std::vector<double> l = pixel_luminance(r);
    double sum = 0.0, mean = 0.0;
    for (size_t i = 0; i < l.size(); ++i) {
        const double d = l[i] - ref[i];
        const double rn = ref_noise.empty() ? 0.0 : double(ref_noise[i]);
        sum += d * d - double(r.noise[i]) * double(r.noise[i]) - rn * rn;
        mean += ref[i];
    }
    mean /= double(l.size());
    return sum / double(l.size()) / (mean * mean);
}

struct Decay {
    double slope = 0.0, seed_se = 0.0;
    double last_mean = 0.0;  // the image mean at the largest count, over the seeds
    double last_mean_se = 0.0;
    std::vector<double> rmse;  // per photon count
};

/// Renders `params` with caustic photon counts n0·4^j (j < steps), `configure` setting each count's other
/// settings, over `seeds` seeds; fits log RMSE against log N.
template <class Configure>
Decay decay(const SceneArrays& arrays, Params params, int64_t n0, int steps, int seeds, const std::vector<double>& ref,
            const std::vector<float>& ref_noise, Configure configure) {
    std::vector<double> xs, ys;
    std::vector<std::vector<double>> seed_ys(static_cast<size_t>(seeds));
    Decay out;
    for (int j = 0; j < steps; ++j) {
        const int64_t n = n0 << (2 * j);
        double mse = 0.0;
        std::vector<double> means;
        for (int s = 1; s <= seeds; ++s) {
            Params p = params;
            p.set("seed", int64_t(s));
            configure(p, n, j);
            const RenderResult r = render(arrays, p);
            const double m = map_mse(r, ref, ref_noise);
            mse += m / seeds;
            seed_ys[size_t(s - 1)].push_back(0.5 * std::log(std::max(m, 1e-12)));
            means.push_back(r.mean_rgb);
        }
        xs.push_back(std::log(double(n)));
        ys.push_back(0.5 * std::log(std::max(mse, 1e-12)));
        out.rmse.push_back(std::sqrt(std::max(mse, 0.0)));
        std::printf("  N = %lld: relative RMSE of the maps %.5f\n", static_cast<long long>(n), out.rmse.back());
        if (j == steps - 1) {
            for (double v : means) out.last_mean += v / seeds;
            double var = 0.0;
            for (double v : means) var += (v - out.last_mean) * (v - out.last_mean) / (seeds - 1);
            out.last_mean_se = std::sqrt(var / seeds);
        }
    }
    out.slope = fit_slope(xs, ys);
    std::vector<double> per_seed;
    double mean = 0.0, var = 0.0;
    for (const auto& y : seed_ys) per_seed.push_back(fit_slope(xs, y));
    for (double v : per_seed) mean += v / seeds;
    for (double v : per_seed) var += (v - mean) * (v - mean) / (seeds - 1);
    out.seed_se = std::sqrt(var / seeds);
    return out;
}

/// A glass sphere (η 1.5, radius 0.5) on a diffuse floor, lit from the side by a small disk light: the sphere
/// focuses the light 0.75 beyond its centre (f = ηR / (2(η − 1))), and the beam spreads again onto the floor
/// behind it, around x ≈ 1.3, inside the sphere's shadow. The camera looks straight down on that part of the floor
/// (x ∈ [0.5, 2.7]): every pixel sees the floor, none the sphere or the light, so no pixel's light is a specular
/// chain from the camera, where every integrator's camera side is heavy-tailed.
SceneArrays sphere_caustic_from_above() {
    MeshBuilder b;
    const uint32_t floor = b.add_material(Color(0.7f), Color(0.f));
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    b.add_instance(add_parallelogram(b, Vec3(-3.f, 0.f, -3.f), Vec3(0.f, 0.f, 6.f), Vec3(6.f, 0.f, 0.f), floor));
    const std::vector<float> at_sphere = translation(0.f, 0.5f, 0.f);
    b.add_instance(b.add_sphere(0.5f, 48, 24, glass), at_sphere.data());
    const Vec3 light(-2.5f, 1.5f, 0.f);
    b.add_area_light(light, Vec3(0.f, 0.15f, 0.f) * 0.f + Vec3(0.08f, 0.2f, 0.f), Vec3(0.f, 0.f, 0.2f),
                     normalize(Vec3(0.f, 0.5f, 0.f) - light), Color(60.f), /*disk=*/true);
    const std::vector<float> camera = look_at(Vec3(1.6f, 3.f, 0.f), Vec3(1.6f, 0.f, 0.f), Vec3(0.f, 0.f, -1.f));
    return b.arrays(camera.data());
}

Params photon_params(int w, int h, int samples, int bounces) {
    Params p = basic_params(w, h, samples, bounces);
    p.set("threads", int64_t(2));
    p.set("integrator", std::string("PHOTON"));
    p.set("photon_kernel", std::string("BOX"));
    p.set("photon_k", int64_t(10000));  // the radius, not k, bounds every estimate
    return p;
}

TEST(CausticMapConvergence, GlassSlabMeanIsTwelveThirteenthsAndRmseFallsAsOneOverRootN) {
    const SceneArrays arrays = glass_slab();
    Params p = photon_params(16, 16, 4, 12);
    p.set("global_photons", int64_t(1000));
    p.set("photon_max_radius", 0.1);
    const std::vector<double> ref(16 * 16, slab_expected());
    std::printf("glass slab, radius 0.1:\n");
    const Decay d =
        decay(arrays, p, 5000, 4, 4, ref, {}, [](Params& q, int64_t n, int) { q.set("caustic_photons", n); });
    std::printf("slab: slope %.4f ± %.4f (expected −0.5); mean %.6e ± %.2e, expected %.6e\n", d.slope, d.seed_se,
                d.last_mean, d.last_mean_se, slab_expected());
    EXPECT_NEAR(d.slope, -0.5, 0.1);
    EXPECT_LT(d.seed_se, 0.03);
    // 4 seeds: t with 3 degrees of freedom, |t| < 5.84 is a two-sided false alarm of 1 %; plus the slab's own
    // returned light (relative < 2·10⁻⁴, reference_scenes.h) and the grey floor's luminance = each channel.
    EXPECT_LT(std::fabs(d.last_mean - slab_expected()), 5.84 * d.last_mean_se + 2e-4 * slab_expected());
}

// The radius starts at 0.1 (about a third of the caustic's width) and shrinks as N^(−1/6); k does not bind. The
// caustic is sharp, so while the radius is not small against it the blur's bias falls faster than the asymptotic
// law (measured: 0.356, 0.224, 0.108, 0.022 for N = 20 k … 1.28 M: factors 0.63, 0.48, 0.21 per 4× photons against
// the law's 0.63). The checks: every 4× photons cuts the error by at least 0.8 (the law's 0.63 with room for the
// seeds' noise), the error at 1.28 M paths is under 5 % (a 10 % error in the photons' flux or a missing caustic
// map would leave at least 10 %), and the image mean is BDPT's within 1 % plus 3.5 σ.
// What it catches: a missing caustic map (the caustic's pixels, at 1.0–1.3, would read the floor's ~0.3: an error
// far over 5 %) and a flux error of 10 % (a floor of about 10 %). What it does not: the radius schedule — with
// k = 50 nearest photons and a fixed radius the error falls below this measure's noise floor by 320 k paths
// (0.102, 0.018, then 0 after the subtraction), so the map's error here is resolved only above about 1 %.
TEST(CausticMapConvergence, GlassSphereCausticConvergesToBdpt) {
    const SceneArrays arrays = sphere_caustic_from_above();
    Params base = basic_params(24, 18, 0, 6);
    base.set("threads", int64_t(2));
    Params pr = base;
    pr.set("integrator", std::string("BDPT"));
    pr.set("samples", int64_t(4096));
    pr.set("seed", int64_t(77));
    const RenderResult ref_r = render(arrays, pr);
    const std::vector<double> ref = pixel_luminance(ref_r);
    Params p = photon_params(24, 18, 16, 6);
    p.set("gather_distance", 0.0);
    std::printf("glass sphere caustic:\n");
    const Decay d = decay(arrays, p, 20000, 4, 4, ref, ref_r.noise, [](Params& q, int64_t n, int j) {
        q.set("caustic_photons", n);
        q.set("global_photons", n);
        q.set("photon_max_radius", 0.1 * std::pow(2.0, -j / 3.0));
    });
    std::printf("caustic: slope %.4f ± %.4f; mean %.5f ± %.5f against BDPT's %.5f ± %.5f\n", d.slope, d.seed_se,
                d.last_mean, d.last_mean_se, ref_r.mean_rgb, ref_r.standard_error);
    for (size_t j = 1; j < d.rmse.size(); ++j) EXPECT_LT(d.rmse[j], 0.8 * d.rmse[j - 1]) << "step " << j;
    EXPECT_LT(d.rmse.back(), 0.05);
    EXPECT_LT(std::fabs(d.last_mean / ref_r.mean_rgb - 1.0),
              0.01 + 3.5 * std::hypot(d.last_mean_se, ref_r.standard_error) / ref_r.mean_rgb);
}

}  // namespace
}  // namespace candela::test
