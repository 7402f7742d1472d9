// The IRRADIANCE_CACHE integrator as a whole (docs/irradiance_cache.md, "How it is tested"):
//   - with a → 0 (a = 10⁻⁴, no minimum spacing: no record is ever usable at another sample's point, so every sample's
//     indirect light is its own gather) it is an unbiased path tracer, and its image equals PATH's on the Cornell box
//     (with a sky outside its open front) within noise: 6 × 6-pixel block means agree within 5σ, σ from both films' noise estimates (honest here: the
//     samples are independent; one degree of freedom per pixel) — Student's t with ~36 degrees of freedom,
//     P(|t| > 5) ≈ 1.5·10⁻⁵ per block, 12 blocks, and so does the whole image's mean (the pooled check: 5σ is under
//     1.5 % of it). The frame leaves out the rows showing the light, whose edge pixels are heavy-tailed (with them
//     4 × 4 blocks gave 5.5σ for one seed of four) and would hide a bias of the rest;
//   - records and image are the same for 1, 2 and 4 threads and tile sizes 8 and 64, bit for bit;
//   - cancel is seen in every stage: after the flag each worker finishes at most the gather ray it is tracing (pre-pass
//     and render), or the pixel row it is in (render passes without gathers, the camera tile loop's bound);
//   - the closed-sphere furnace (every facet emits 0.5, albedo 0.5: L = 1 − 0.5^(K+2) for K bounces, exact for any
//     closed shape) is met within 5σ, σ from 12 independent renders (t with 11 degrees of freedom: P(|t| > 5) ≈
//     4·10⁻⁴), with and without gradients: a uniform radiance field has a uniform irradiance, so interpolation adds no
//     bias (the documented bias here is 0).
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "core/frame.h"
#include "core/rng.h"
#include "film/film.h"
#include "ic_test_scenes.h"
#include "integrators/camera_tiles.h"
#include "integrators/irradiance_cache/ic_integrator.h"
#include "sampling/warp.h"
#include "scene/ray_offset.h"
#include "scene/scene.h"
#include "session/session.h"

namespace candela::test {
namespace {

struct Rendered {
    std::vector<float> rgba, noise, records;
    std::vector<std::string> log;
    StopReason stop;
    double note_records = -1;
};

Rendered render_session(SceneArrays arrays, Params p) {
    Session s(std::move(arrays), std::move(p));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    Rendered r;
    int ch = 0;
    r.rgba = s.get_pass("Combined", &ch);
    r.noise = s.get_pass("Noise", &ch);
    r.records = s.get_pass("IC Records", &ch);
    r.log = s.take_log();
    r.stop = s.progress().stop_reason;
    return r;
}

double luminance_at(const std::vector<float>& rgba, size_t i) {
    return 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2];
}

// The pre-pass's grid: every pixel of a film (at any origin) is visited exactly once, at one stride and one
// sub-pass, and the points of one sub-pass lie 2s apart along both axes (a multiple of 2s in each coordinate
// difference), so none of them is a neighbour of another on its own grid.
TEST(IrradianceCache, PrepassSubPassesVisitEveryPixelOnceAndSpreadOut) {
    for (int top : {1, 2, 16, 64})
        for (auto [x0, y0, w, h] : {std::array{0, 0, 37, 23}, std::array{5, 130, 70, 9}}) {
            std::vector<int> visits(size_t(w) * h, 0);
            for (int st = top; st >= 1; st /= 2)
                for (int sub = 0; sub < 4; ++sub) {
                    std::vector<std::pair<int, int>> points;
                    for (int y = y0; y < y0 + h; ++y)
                        for (int x = x0; x < x0 + w; ++x)
                            if (ic_prepass_sub_pass(x, y, st, top) == sub) {
                                ++visits[size_t(y - y0) * w + (x - x0)];
                                points.push_back({x, y});
                            }
                    if (st < top) EXPECT_TRUE(sub < 3 || points.empty()) << "stride " << st;
                    for (const auto& [x, y] : points) {
                        ASSERT_EQ((x - points[0].first) % (2 * st), 0) << "stride " << st << " sub-pass " << sub;
                        ASSERT_EQ((y - points[0].second) % (2 * st), 0) << "stride " << st << " sub-pass " << sub;
                    }
                }
            for (size_t i = 0; i < visits.size(); ++i) ASSERT_EQ(visits[i], 1) << "pixel " << i << ", top " << top;
        }
}

// `sky`: the Cornell box with a sky outside its open front (a constant world: light no next-event estimation
// samples, which the gathers and the camera paths' continuations must not both count); black: the closed box's
// only light is its two emitting triangles, so camera continuations of β = 0 are traced only where they may meet
// them (IcTracer::may_find_light) — a filter that dropped rays which find the light would darken the image.
void expect_equals_path_as_the_error_tends_to_zero(Color sky) {
    // The lower three quarters of a 24 × 24 frame (a border): the light's edge pixels, whose noise would hide a bias
    // of the rest, are left out.
    const int w = 24, h = 18;
    Params ic = cornell_box_params(w, 24, 256, "IRRADIANCE_CACHE");
    ic.set("crop_y1", int64_t(h));
    ic.set("ic_error", 1e-4);
    ic.set("ic_min_spacing", 0.0);
    ic.set("ic_gather_rays", int64_t(8));
    ic.set("seed", int64_t(1));
    Params path = cornell_box_params(w, 24, 256, "PATH");
    path.set("crop_y1", int64_t(h));
    path.set("seed", int64_t(2));
    const Rendered a = render_session(cornell_box_arrays(sky), ic), b = render_session(cornell_box_arrays(sky), path);
    int blocks = 0;
    double worst = 0.0, sum_a = 0, sum_b = 0, var = 0;
    for (int by = 0; by < h; by += 6)
        for (int bx = 0; bx < w; bx += 6) {
            double da = 0, db = 0, va = 0, vb = 0;
            for (int y = by; y < by + 6; ++y)
                for (int x = bx; x < bx + 6; ++x) {
                    const size_t i = size_t(y) * w + x;
                    da += luminance_at(a.rgba, i);
                    db += luminance_at(b.rgba, i);
                    va += double(a.noise[i]) * a.noise[i];
                    vb += double(b.noise[i]) * b.noise[i];
                }
            const double z = std::fabs(da - db) / std::sqrt(va + vb);
            worst = std::max(worst, z);
            sum_a += da;
            sum_b += db;
            var += va + vb;
            ++blocks;
            EXPECT_LT(z, 5.0) << "block (" << bx << ", " << by << "): " << da / 36 << " vs " << db / 36;
        }
    EXPECT_EQ(blocks, 12);
    const double z_image = std::fabs(sum_a - sum_b) / std::sqrt(var);
    EXPECT_LT(z_image, 5.0) << sum_a / (w * h) << " vs " << sum_b / (w * h);
    EXPECT_LT(5.0 * std::sqrt(var) / sum_b, 0.015) << "precise enough";
    std::printf("largest block deviation %.2f σ, image %.2f σ (σ = %.2f %%)\n", worst, z_image,
                100 * std::sqrt(var) / sum_b);
}

TEST(IrradianceCache, EqualsPathAsTheErrorTendsToZero) {
    expect_equals_path_as_the_error_tends_to_zero({0.5f, 0.6f, 1.f});
}

TEST(IrradianceCache, EqualsPathAsTheErrorTendsToZeroInTheClosedBox) {
    expect_equals_path_as_the_error_tends_to_zero(Color(0.f));
}

// The light filter of β = 0 continuations (IcTracer::LightFilter): on the closed Cornell box (two emitting
// triangles, no world) every ray whose first hit the scene finds on the light is let through, and most rays that
// find something else are not (what the filter saves). Rays from random points on the box's surfaces in
// cosine-distributed directions about the normal, as continuations leave. A filter that rejected every ray, or
// tested only one triangle of the two, fails it.
TEST(IrradianceCache, LightFilterLetsThroughEveryRayThatFindsTheLight) {
    const PreparedScene prepared(cornell_box_arrays(), cornell_box_params(16, 16, 1, "IRRADIANCE_CACHE"));
    const Scene& scene = prepared.scene();
    const IcTracer::LightFilter filter = IcTracer::LightFilter::of(scene);
    ASSERT_TRUE(filter.active);
    ASSERT_EQ(filter.triangles.size(), 2u);
    Pcg32 rng(3, 5);
    int to_light = 0, elsewhere = 0, kept_elsewhere = 0;
    const Camera& cam = scene.camera();
    for (int i = 0; i < 200000; ++i) {
        // A surface point: the first hit of a random camera ray.
        SurfaceHit first;
        const Ray primary = cam.generate_ray({rng.next_float() * 16.f, rng.next_float() * 16.f});
        if (!scene.intersect(primary, &first, PrimitiveRef{})) continue;
        const Vec3 n = dot(first.ng, primary.d) < 0.f ? first.ng : -first.ng;
        const Frame frame(n);
        const Vec3 d = frame.to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
        const Vec3 o = offset_ray_origin(first.p, n);
        SurfaceHit hit;
        const bool found =
            scene.intersect(Ray{o, d, 0.f, std::numeric_limits<float>::infinity()}, &hit, first.primitive);
        const bool pass = filter.may_hit(o, d);
        if (found && hit.light >= 0) {
            ++to_light;
            ASSERT_TRUE(pass) << "ray " << i << " finds the light but is filtered out";
        } else {
            ++elsewhere;
            kept_elsewhere += pass;
        }
    }
    EXPECT_GT(to_light, 500);
    EXPECT_LT(kept_elsewhere, elsewhere / 2) << "the filter lets through most rays that find no light";
    std::printf("rays to the light %d (all let through); others %d, of which %d let through\n", to_light, elsewhere,
                kept_elsewhere);
}

Rendered lit_render(int threads, int tile) {
    Params p = cornell_box_params(40, 30, 6, "IRRADIANCE_CACHE");
    p.set("threads", int64_t(threads));
    p.set("tile_size", int64_t(tile));
    p.set("passes", std::string("IC Records"));
    p.set("ic_gather_rays", int64_t(64));
    return render_session(cornell_box_arrays(), p);
}

TEST(IrradianceCache, RecordsAndImageAreThreadCountAndTileInvariant) {
    const Rendered ref = lit_render(1, 8);
    double records = 0;
    for (float c : ref.records) records += c;
    EXPECT_GT(records, 50.0);
    for (auto [threads, tile] : {std::pair{2, 64}, std::pair{4, 8}, std::pair{4, 64}}) {
        const Rendered r = lit_render(threads, tile);
        EXPECT_EQ(r.records, ref.records) << threads << " threads, tile " << tile;
        EXPECT_EQ(r.rgba, ref.rgba) << threads << " threads, tile " << tile;
    }
}

/// A render on its own context (cancel token, counters) with a probe.
struct ProbedRender {
    CancelToken cancel;
    RenderCounters counters;
    std::atomic<uint64_t> gather_rays{0}, camera_paths{0}, after_cancel{0};
    IcProbe probe;
};

StopReason run_probed(ProbedRender& pr, const Params& p, int threads) {
    SceneArrays arrays = cornell_box_arrays();
    arrays.validate();
    const Scene scene(arrays, p, nullptr);
    Film film(p.require<int>("width"), p.require<int>("height"), 0, 0, 8);
    RenderContext ctx{pr.cancel, pr.counters, threads};
    const auto integrator = make_ic_integrator(p, &pr.probe);
    integrator->render(scene, film, ctx);
    return StopReason(pr.counters.stop_reason.load());
}

TEST(IrradianceCache, CancelIsSeenInEveryStage) {
    for (int threads : {1, 2, 4}) {
        // Pre-pass and render-time gathers: at most one gather ray per worker after the flag.
        for (IcStage stage : {IcStage::Prepass, IcStage::Render}) {
            ProbedRender pr;
            Params p = cornell_box_params(32, 32, 64, "IRRADIANCE_CACHE");
            if (stage == IcStage::Render) {  // every sample gathers: no record is usable at another sample's point
                p.set("ic_error", 1e-4);
                p.set("ic_min_spacing", 0.0);
            }
            p.set("ic_gather_rays", int64_t(64));
            const uint64_t at = 3000;
            pr.probe.on_gather_ray = [&](IcStage s) {
                if (pr.cancel.cancelled())
                    ++pr.after_cancel;
                else if (s == stage && ++pr.gather_rays == at)
                    pr.cancel.cancel();
            };
            EXPECT_EQ(run_probed(pr, p, threads), StopReason::Cancelled);
            EXPECT_EQ(pr.gather_rays.load(), at) << "the cancel was reached";
            EXPECT_LE(pr.after_cancel.load(), uint64_t(threads)) << threads << " threads, stage " << int(stage);
            if (stage == IcStage::Prepass) EXPECT_EQ(pr.counters.work_done.load(), 0);
        }
        // Render passes reading the cache only: at most a pixel row (8 pixels) of a pass per worker.
        ProbedRender pr;
        Params p = cornell_box_params(32, 32, 100000, "IRRADIANCE_CACHE");
        p.set("ic_gather_rays", int64_t(16));
        const uint64_t at = 20000;
        pr.probe.on_camera_path = [&] {
            if (pr.cancel.cancelled())
                ++pr.after_cancel;
            else if (++pr.camera_paths == at)
                pr.cancel.cancel();
        };
        EXPECT_EQ(run_probed(pr, p, threads), StopReason::Cancelled);
        const uint64_t pass = uint64_t(camera_max_pass(Film(32, 32, 0, 0, 8), PixelSampling::from_params(p)));
        EXPECT_LE(pr.after_cancel.load(), uint64_t(threads) * 8u * pass) << threads << " threads";
    }
}

TEST(IrradianceCache, ClosedSphereFurnace) {
    const int K = 12;
    const double expected = furnace_expected(FurnaceScene::EmissiveSphere, K);
    for (bool gradients : {true, false}) {
        std::vector<double> means;
        for (int seed = 0; seed < 12; ++seed) {
            Params p = basic_params(12, 12, 4, K);
            p.set("integrator", std::string("IRRADIANCE_CACHE"));
            p.set("seed", int64_t(seed));
            p.set("ic_gradients", gradients);
            p.set("ic_gather_rays", int64_t(128));
            const Rendered r = render_session(furnace_scene(FurnaceScene::EmissiveSphere, 24, 12), p);
            double sum = 0;
            for (size_t i = 0; i < r.rgba.size(); i += 4) sum += (r.rgba[i] + r.rgba[i + 1] + r.rgba[i + 2]) / 3.0;
            means.push_back(sum / double(r.rgba.size() / 4));
        }
        double m = 0, s2 = 0;
        for (double v : means) m += v;
        m /= means.size();
        for (double v : means) s2 += (v - m) * (v - m);
        const double se = std::sqrt(s2 / (means.size() - 1) / means.size());
        EXPECT_LT(std::fabs(m - expected), 5.0 * se) << "gradients " << gradients << ": " << m << " vs " << expected;
        EXPECT_LT(5.0 * se, 0.01) << "precise enough";
        std::printf("furnace (gradients %d): %.5f ± %.5f, expected %.5f\n", int(gradients), m, se, expected);
    }
}

}  // namespace
}  // namespace candela::test

namespace candela::test {
namespace {

// The memory hook: the session's estimate reserves the cache's capacity — one record per Min Spacing² pixels (at
// least half a pixel) plus 4096 — at k_ic_bytes_per_record each; PATH reserves nothing.
TEST(IrradianceCache, TheMemoryEstimateReservesTheRecords) {
    const SceneArrays arrays = cornell_box_arrays();
    Params p = cornell_box_params(200, 100, 4, "IRRADIANCE_CACHE");
    EXPECT_EQ(ic_record_capacity(IcSettings::from_params(p), 20000.0), size_t(std::ceil(20000.0 / 2.25)) + 4096);
    EXPECT_DOUBLE_EQ(Session::estimate_memory(arrays, p).integrator_bytes,
                     double(size_t(std::ceil(20000.0 / 2.25)) + 4096) * double(k_ic_bytes_per_record));
    p.set("ic_min_spacing", 0.0);
    EXPECT_DOUBLE_EQ(Session::estimate_memory(arrays, p).integrator_bytes, (80000.0 + 4096.0) * k_ic_bytes_per_record);
    EXPECT_EQ(Session::estimate_memory(arrays, cornell_box_params(200, 100, 4, "PATH")).integrator_bytes, 0.0);
}

}  // namespace
}  // namespace candela::test
