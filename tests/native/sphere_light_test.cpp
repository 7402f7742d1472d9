// A soft point light (Blender's point light with a radius) close to a diffuse floor: BDPT, LIGHT and each of BDPT's
// strategies against PATH. PATH lights a shading point x by Cycles 3.4's model (lights/point_light.h): a disk of
// radius r through the light's centre, facing x, of radiance I/(πr²). A sphere of the same radius and radiance gives
// x more light — its solid angle is 2π(1 − √(1 − r²/d²)) against the disk's 2π(1 − d/√(d² + r²)), the irradiance
// ratio straight under it 1 + r²/d² — so light-rooted strategies that emit from the sphere must count only the rays
// that arrive through the disk their first receiver sees (lights/light_emission.h). Here r²/d² is about 0.4 under the
// light: a strategy that renders the sphere is off by far more than the noise.
//
// Statistics: 12 seeds per side; the image mean's t (22 degrees of freedom) within 4, two-sided false alarm 6e-4 per
// comparison, every 4×4 block within 6 (5e-6 per block); the per-strategy means within 4 standard errors of the
// difference (1.6e-3 each with 11 degrees of freedom). This file makes 2 image comparisons of 12 blocks each and 5
// strategy comparisons: a family-wise false-alarm rate below 1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "agreement.h"
#include "integrators/bdpt/strategy_images.h"
#include "reference_scenes.h"
#include "session/session.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 12;

/// A diffuse floor (y = −1) and back wall (z = −4) with a sphere light of radius 0.45 whose centre is 0.7 above the
/// floor, seen from above and in front.
SceneArrays sphere_light_room() {
    MeshBuilder b;
    const uint32_t white = b.add_material(Color(0.7f, 0.65f, 0.6f), Color(0.f));
    b.add_instance(add_parallelogram(b, Vec3(-3.f, -1.f, -6.f), Vec3(0.f, 0.f, 6.f), Vec3(6.f, 0.f, 0.f), white));
    b.add_instance(add_parallelogram(b, Vec3(-3.f, -1.f, -4.f), Vec3(6.f, 0.f, 0.f), Vec3(0.f, 4.f, 0.f), white));
    b.add_point_light(Vec3(0.2f, -0.3f, -2.8f), Color(30.f), 0.45f);
    const std::vector<float> camera = look_at(Vec3(0.f, 1.f, 0.f), Vec3(0.1f, -0.9f, -3.f), Vec3(0.f, 1.f, 0.f));
    return b.arrays(camera.data());
}

Params room_params(const std::string& integrator, int samples, int max_bounces) {
    Params p = basic_params(16, 12, samples, max_bounces);
    p.set("integrator", integrator);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BOX"));
    p.set("filter_width", 1.0);
    p.set("rr_start_bounce", int64_t(2));
    return p;
}

TEST(SphereLight, BdptAndLightTracingEqualPathTracing) {
    const SceneArrays arrays = sphere_light_room();
    const std::vector<RenderResult> path = render_seeds(arrays, room_params("PATH", 32, 1), k_seeds);
    for (const auto& [integrator, samples] : {std::pair<std::string, int>{"BDPT", 16}, {"LIGHT", 32}}) {
        const Agreement g =
            compare_seed_sets(render_seeds(arrays, room_params(integrator, samples, 1), k_seeds), path, 4);
        EXPECT_GT(g.mean_b, 0.0) << integrator;
        EXPECT_LT(std::fabs(g.mean_z), 4.0) << integrator << ": mean " << g.mean_a << ", PATH " << g.mean_b;
        EXPECT_LT(std::fabs(g.worst_block_z), 6.0) << integrator << ": block " << g.worst_block << " of " << g.blocks;
    }
}

double mean_of(const std::vector<float>& rgb, int stride) {
    double sum = 0.0;
    for (size_t i = 0; i < rgb.size(); i += size_t(stride)) sum += rgb[i] + rgb[i + 1] + rgb[i + 2];
    return sum / double(3 * (rgb.size() / size_t(stride)));
}

struct Estimate {
    double mean = 0.0, se = 0.0;
    void add(double x) { v.push_back(x); }
    void finish() {
        double s = 0.0, s2 = 0.0;
        for (double x : v) s += x, s2 += x * x;
        const double n = double(v.size());
        mean = s / n;
        se = std::sqrt(std::max(0.0, (s2 - n * mean * mean) / (n - 1.0)) / n);
    }
    std::vector<double> v;
};

TEST(SphereLight, EachBdptStrategyEqualsPathTracing) {
    // Depth 1 (direct light: (1, 2) next-event estimation, (2, 1) light tracing) against PATH with no bounce; depth 2
    // ((1, 3), (2, 2), (3, 1)) against PATH's one-bounce image minus its direct one. (0, t) cannot hit the light.
    const SceneArrays arrays = sphere_light_room();
    std::string passes;
    for (const StrategyId& id : StrategyImages::strategies(2))
        passes += (passes.empty() ? "" : ",") + StrategyImages::name(id, true);
    Estimate direct, one_bounce, strategy[3][4];
    for (int seed = 1; seed <= k_seeds; ++seed) {
        Params p = room_params("BDPT", 16, 1);
        p.set("seed", int64_t(seed));
        p.set("bdpt_strategy_images", true);
        p.set("bdpt_strategy_depth", int64_t(2));
        p.set("passes", passes);
        Session s(arrays, std::move(p));
        s.start();
        s.join();
        if (auto e = s.error()) FAIL() << *e;
        int ch = 0;
        for (const StrategyId& id : StrategyImages::strategies(2))
            if (id.depth >= 1 && id.s >= 1)
                strategy[id.depth][id.s].add(mean_of(s.get_pass(StrategyImages::name(id, true), &ch), 3));
        Params q = room_params("PATH", 32, 0);
        q.set("seed", int64_t(seed));
        const double d0 = render(arrays, q).mean_rgb;
        q.set("max_bounces", int64_t(1));
        q.set("seed", int64_t(seed + 1000));
        direct.add(d0);
        one_bounce.add(render(arrays, q).mean_rgb - d0);
    }
    direct.finish();
    one_bounce.finish();
    for (int depth = 1; depth <= 2; ++depth)
        for (int s = 1; s <= depth + 1; ++s) {
            Estimate& e = strategy[depth][s];
            e.finish();
            const Estimate& ref = depth == 1 ? direct : one_bounce;
            std::printf("depth %d, (s, t) = (%d, %d): unweighted %.5f ± %.5f, PATH %.5f ± %.5f\n", depth, s,
                        depth + 2 - s, e.mean, e.se, ref.mean, ref.se);
            EXPECT_GT(ref.mean, 0.0);
            EXPECT_NEAR(e.mean, ref.mean, 4.0 * std::sqrt(e.se * e.se + ref.se * ref.se))
                << "depth " << depth << ", s = " << s;
        }
}

}  // namespace
}  // namespace candela::test
