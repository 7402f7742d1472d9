// The photon mappers (integrators/photon_map/; docs/photon-mapping.md, "Verification"):
//   - the kd-tree forest's k-nearest and radius queries equal brute force (ties, the disc filter, the side check)
//     and do not depend on the build's thread count;
//   - the photon-map bias law on a plane under a point light (box and cone kernels, three radii);
//   - the closed-sphere furnace for PHOTON (within its documented disc bias) and SPPM;
//   - PHOTON and SPPM against PATH on a diffuse room and on a room with a glass sphere;
//   - the caustic map only where the scene calls for it; determinism across thread counts; cancel during the
//     photon pass and the tree build; bad settings refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

#include "agreement.h"
#include "core/error.h"
#include "core/rng.h"
#include "integrators/integrator.h"
#include "integrators/photon_map/caustic_emission.h"
#include "integrators/photon_map/density_kernel.h"
#include "integrators/photon_map/photon_map.h"
#include "integrators/photon_map/photon_shooting.h"
#include "session/session.h"

namespace candela::test {
namespace {

// ---- the kd-tree -------------------------------------------------------------------------------------------

std::vector<Photon> random_photons(size_t n, uint64_t seed) {
    Pcg32 rng(seed, 7);
    std::vector<Photon> out(n);
    for (size_t i = 0; i < n; ++i) {
        Photon& p = out[i];
        if (i > 0 && rng.next_float() < 0.1f) {  // exact duplicates: ties at every distance
            p = out[size_t(rng.next_u32() % uint32_t(i))];
        } else {
            // A slab, a few exact lattice points (ties in distance), the rest uniform.
            p.x = rng.next_float() * 4.f - 2.f;
            p.y = rng.next_float() * 4.f - 2.f;
            p.z = rng.next_float() * 0.5f;
            if (rng.next_float() < 0.2f) {
                p.x = std::round(p.x * 8.f) / 8.f;
                p.y = std::round(p.y * 8.f) / 8.f;
                p.z = 0.f;
            }
            const Vec3 d = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
            p.dir = encode_direction(d);
            p.flux = uint32_t(i);
        }
    }
    return out;
}

std::vector<PhotonNeighbor> brute_force(const PhotonMap& map, const Vec3& x, float max2, const PhotonFilter& f) {
    std::vector<PhotonNeighbor> all;
    for (size_t i = 0; i < map.size(); ++i) {
        const Photon& p = map[i];
        const float dx = p.x - x.x, dy = p.y - x.y, dz = p.z - x.z;
        float d2 = 0.f;  // in nanoflann's order of operations
        d2 += dx * dx;
        d2 += dy * dy;
        d2 += dz * dz;
        const float m = f.metric(p, x, d2);
        if (m <= max2) all.push_back({uint32_t(i), m});
    }
    std::sort(all.begin(), all.end(), [](const PhotonNeighbor& a, const PhotonNeighbor& b) {
        return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
    });
    return all;
}

TEST(PhotonMapTree, NearestAndRadiusQueriesEqualBruteForce) {
    PhotonMap map;
    map.build(random_photons(150000, 3), 2, nullptr, nullptr);  // several cells of the forest
    ASSERT_GT(map.cells(), 4u);
    Pcg32 rng(11, 5);
    std::vector<PhotonNeighbor> got(200), within;
    for (int q = 0; q < 60; ++q) {
        Vec3 x(rng.next_float() * 4.f - 2.f, rng.next_float() * 4.f - 2.f, rng.next_float() * 0.5f);
        if (q % 3 == 0) x = map[rng.next_u32() % uint32_t(map.size())].position();  // on a photon (ties at 0)
        if (q % 5 == 0) x = Vec3(std::round(x.x * 8.f) / 8.f + 1.f / 16.f, std::round(x.y * 8.f) / 8.f, 0.f);
        PhotonFilter f;
        if (q % 2 == 1) {
            f.normal = normalize(Vec3(0.2f, -0.1f, 1.f));
            f.flatten = 15.f;
            f.front_only = q % 4 == 1;
        }
        const int k = 1 + int(rng.next_u32() % 150u);
        const float max2 = q % 7 == 0 ? 1e9f : 0.002f + 0.05f * rng.next_float();
        const std::vector<PhotonNeighbor> all = brute_force(map, x, max2, f);
        const int n = map.nearest(x, k, max2, f, got.data());
        ASSERT_EQ(n, std::min<int>(k, int(all.size()))) << "query " << q;
        for (int i = 0; i < n; ++i) {
            ASSERT_EQ(got[size_t(i)].index, all[size_t(i)].index) << "query " << q << ", neighbour " << i;
            ASSERT_EQ(got[size_t(i)].dist2, all[size_t(i)].dist2) << "query " << q;
        }
        if (max2 < 1.f) {
            map.within(x, max2, f, within);
            ASSERT_EQ(within.size(), all.size()) << "query " << q;
            for (size_t i = 0; i < all.size(); ++i) ASSERT_EQ(within[i].index, all[i].index) << "query " << q;
        }
    }
}

TEST(PhotonMapTree, BuildDoesNotDependOnThreads) {
    PhotonMap a, b;
    a.build(random_photons(120000, 9), 1, nullptr, nullptr);
    b.build(random_photons(120000, 9), 2, nullptr, nullptr);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(Photon)), 0) << i;
}

TEST(PhotonMapTree, FluxEncodingIsUnbiased) {
    // Stochastic rounding: the mean decoded value over u equals the input (to float precision), for values across
    // the exponent range.
    for (float v : {1.f, 0.3f, 1e-3f, 7.77e-6f, 123.f}) {
        double sum = 0.0;
        const int n = 4096;
        for (int i = 0; i < n; ++i) sum += decode_flux(encode_flux(Color(v, 0.5f * v, 0.1f * v), (i + 0.5f) / n)).y;
        EXPECT_NEAR(sum / n, 0.5 * v, 1e-4 * v) << v;
    }
}

// ---- the bias law ------------------------------------------------------------------------------------------

// A point light of power Φ at height h over a large diffuse plane: photons of max_bounces = 0 land where the light
// sends them, with density E(d) = Φh/(4π(h² + d²)^(3/2)) per unit flux. The estimate at the foot with kernel K of
// fixed radius r, Σ K·Φ_p/N, has relative bias −(3/2)·m₂/h² + (15/8)·m₄/h⁴ (density_kernel.h). E's true value is
// calibrated from the same photons: they carry the flux through the plane's solid angle Ω, so E(0) = (Σ Φ_p/N)/(Ω h²).
// Eight seeds (independent Sobol' scrambles); the standard error of the mean relative bias from their spread, and
// the measured bias within 3 standard errors of the law (t with 7 degrees of freedom: two-sided false alarm 2 % per
// check; the seeds are fixed, so the outcome is deterministic).
TEST(PhotonMapBias, PlaneUnderPointLightFollowsTheKernelLaw) {
    const float h = 1.f, a = 40.f;
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    // The camera at the origin (scenes are built camera-relative), looking down at the plane z = −2.
    const Vec3 foot(0.f, 0.f, -2.f);
    b.add_instance(b.add_quad_z(-a, a, -a, a, foot.z, m));
    b.add_point_light(foot + Vec3(0.f, 0.f, h), Color(100.f));
    const std::vector<float> cam = look_at(Vec3(0.f), foot, Vec3(0.f, 1.f, 0.f));
    Params base = basic_params(8, 8, 1, 0);
    const PreparedScene prepared(b.arrays(cam.data()), base);
    const Scene& scene = prepared.scene();
    const EmitterSet emitters(scene.lights(), scene.bounds());
    PhotonRules rules;
    rules.max_bounces = 0;
    const PhotonTracer tracer(scene, emitters, rules);
    const double omega = 4.0 * std::atan(double(a) * a / (double(h) * std::sqrt(2.0 * a * a + double(h) * h)));
    const int seeds = 8;
    const int64_t paths = 1000000;
    const float ratios[3] = {0.2f, 0.1f, 0.05f};
    const DensityKernel kernels[2] = {DensityKernel::Box, DensityKernel::Cone};
    const double m2[2] = {0.5, 0.3}, m4[2] = {1.0 / 3.0, 1.0 / 7.0};
    double rel[2][3][8] = {};
    for (int s = 0; s < seeds; ++s) {
        CancelToken cancel;
        RenderCounters counters;
        RenderContext ctx{cancel, counters, 2};
        PhotonMap map = build_photon_map(
            shoot_photons(tracer, emitters, PhotonStore::Global, paths, uint64_t(s + 1), 0, ctx, "t"), ctx, "b");
        double total = 0.0;
        for (size_t i = 0; i < map.size(); ++i) total += luminance(map.flux(map[i]));
        const double e_true = total / map.emitted_paths / (omega * h * h);
        if (s == 0) {
            PhotonNeighbor nb[1];
            const int n = map.nearest(foot, 1, 1e30f, PhotonFilter{}, nb);
            std::printf("photons %zu, total %g, nearest %d at %g: (%g %g %g)\n", map.size(), total, n, nb[0].dist2,
                        map[nb[0].index].x, map[nb[0].index].y, map[nb[0].index].z);
        }
        std::vector<PhotonNeighbor> found;
        for (int j = 0; j < 3; ++j) {
            const float r = ratios[j] * h;
            map.within(foot, r * r, PhotonFilter{}, found);
            for (int k = 0; k < 2; ++k) {
                double sum = 0.0;
                for (const PhotonNeighbor& nb : found)
                    sum += kernel_weight(kernels[k], nb.dist2 / (r * r)) * luminance(map.flux(map[nb.index]));
                const double e = sum / (double(k_pi) * r * r * map.emitted_paths);
                rel[k][j][s] = e / e_true - 1.0;
            }
        }
    }
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 3; ++j) {
            double mean = 0.0, var = 0.0;
            for (int s = 0; s < seeds; ++s) mean += rel[k][j][s] / seeds;
            for (int s = 0; s < seeds; ++s) var += (rel[k][j][s] - mean) * (rel[k][j][s] - mean) / (seeds - 1);
            const double se = std::sqrt(var / seeds);
            const double q = double(ratios[j]) * ratios[j];
            const double law = -1.5 * m2[k] * q + 1.875 * m4[k] * q * q;
            std::printf("kernel %s r/h %.2f: relative bias %+.5f ± %.5f, law %+.5f\n", k == 0 ? "BOX " : "CONE",
                        ratios[j], mean, se, law);
            EXPECT_LT(std::fabs(mean - law), 3.0 * se + 1e-6) << "kernel " << k << " r/h " << ratios[j];
            // The test can fail: at r/h = 0.2 the bias is many standard errors away from 0.
            if (j == 0) {
                EXPECT_GT(std::fabs(mean), 3.0 * se) << "kernel " << k;
            }
        }
}

// ---- scenes -----------------------------------------------------------------------------------------------

/// A diffuse room (albedo 0.6/0.5/0.4) with a rough glossy sphere, a point light and a disk area light behind the
/// camera; the camera at its centre. With `glass`, a smooth glass sphere stands on the floor under the point light.
SceneArrays room(bool glass) {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f, 0.5f, 0.4f), Color(0.f));
    const uint32_t glossy = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glossy, "GLOSSY", {{"color_r", 0.8f}, {"color_g", 0.8f}, {"color_b", 0.8f}, {"roughness", 0.4f}});
    b.add_instance(b.add_box(Vec3(2.f, 1.5f, 3.f), wall));
    const std::vector<float> xf = {1, 0, 0, -0.6f, 0, 1, 0, -1.f, 0, 0, 1, -1.8f, 0, 0, 0, 1};
    b.add_instance(b.add_sphere(0.5f, 24, 12, glossy), xf.data());
    b.add_point_light(Vec3(1.f, 0.8f, -1.2f), Color(6.f));
    // Behind the camera, facing the room: no pixel sees the light itself (its edge would dominate the noise).
    b.add_area_light(Vec3(0.8f, -1.f, 2.9f), Vec3(0.8f, 0.f, 0.f), Vec3(0.f, 0.5f, 0.f), Vec3(0.f, 0.f, -1.f),
                     Color(8.f, 6.f, 4.f), /*disk=*/true);
    if (glass) {
        const uint32_t g = b.add_material(Color(0.f), Color(0.f));
        b.add_closure(g, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
        const std::vector<float> gx = {1, 0, 0, 1.f, 0, 1, 0, -1.1f, 0, 0, 1, -1.2f, 0, 0, 0, 1};
        b.add_instance(b.add_sphere(0.4f, 32, 16, g), gx.data());
    }
    return b.arrays();
}

Params room_params(const char* integrator, int samples) {
    Params p = basic_params(32, 24, samples, 20);
    p.set("threads", int64_t(2));
    p.set("integrator", std::string(integrator));
    return p;
}

std::vector<std::string> render_log(const SceneArrays& arrays, const Params& p) {
    Session s(arrays, p);
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    return s.take_log();
}

bool log_has(const std::vector<std::string>& log, const std::string& what) {
    for (const std::string& l : log)
        if (l.find(what) != std::string::npos) return true;
    return false;
}

// ---- furnaces ----------------------------------------------------------------------------------------------

// The point-light furnace (docs/verification.md §1): L = 1 everywhere, irradiance uniform, so no kernel bias. SPPM
// must give 1; PHOTON's disc (search sphere flattened to t = 1/4 across the surface) loses the photons of the curved
// wall beyond the flattened region: on a sphere of radius R the k-nearest radius r grows by a relative (15/8)(r/R)²,
// a relative bias of −(15/4)(r/R)² on the map's share (docs/photon-mapping.md, "Kernels and their bias"). Noise:
// per-pixel standard error for PHOTON (independent camera samples over one map: the map's own noise is correlated
// and is bounded by the bias allowance), four seeds' spread for SPPM.
TEST(PhotonFurnace, PhotonAndSppmInThePointLightSphere) {
    const int K = 40;
    const double expected = furnace_expected(FurnaceScene::PointLight, K) * (1.0 + furnace_facet_bias(128, 64));
    {
        Params p = basic_params(16, 16, 16, K);
        p.set("integrator", std::string("PHOTON"));
        p.set("threads", int64_t(2));
        const RenderResult r = render(furnace_scene(FurnaceScene::PointLight), p);
        // 200 000 paths storing 1/(1 − ρ) = 2 photons each over the sphere's 4π: r² = (k − 1)/(πλ).
        const double lambda = 400000.0 / (4.0 * k_pi);
        const double bias = 3.75 * 49.0 / (k_pi * lambda);
        std::printf("PHOTON furnace %.5f (expected %.5f, disc bias allowance %.5f, se %.5f)\n", r.mean_rgb, expected,
                    2.0 * bias, r.standard_error);
        EXPECT_GT(r.mean_rgb, expected * (1.0 - 2.0 * bias) - 4.0 * r.standard_error);
        EXPECT_LT(r.mean_rgb, expected + 4.0 * r.standard_error);
    }
    {
        Params p = basic_params(8, 8, 16, K);
        p.set("integrator", std::string("SPPM"));
        p.set("threads", int64_t(2));
        p.set("sppm_photons", int64_t(50000));
        p.set("sppm_radius", 0.1);  // uniform irradiance: no kernel bias at any radius, and less noise
        const SeedMean m = seed_mean(render_seeds(furnace_scene(FurnaceScene::PointLight), p, 4));
        std::printf("SPPM furnace %.5f ± %.5f (expected %.5f)\n", m.mean, m.standard_error, expected);
        // t with 3 degrees of freedom: |t| < 5.84 is a two-sided false alarm of 1 %.
        EXPECT_LT(std::fabs(m.mean - expected), 5.84 * m.standard_error + 1e-4);
    }
}

// ---- agreement with PATH -----------------------------------------------------------------------------------

// Image means against PATH's, one seed each, with PATH's and PHOTON's standard errors from their per-pixel
// variances (4 σ of their combination: a two-sided false alarm of 6e-5 for a normal error). SPPM's film entries
// are not independent samples (sppm.h), so SPPM gets the same camera-noise allowance as PATH at its 32 camera samples
// per pixel (PATH's σ scaled by √(256/32)). Bias allowances: SPPM 2 % (the target) after 32 iterations;
// PHOTON 1 % (measured −0.2 % and +0.03 %: the k-nearest estimate at the corners and under the lights' falloff,
// docs/photon-mapping.md).
TEST(PhotonAgreement, PhotonAndSppmMatchPathInARoom) {
    for (bool glass : {false, true}) {
        const SceneArrays arrays = room(glass);
        const RenderResult path = render(arrays, room_params("PATH", 256));
        const RenderResult photon = render(arrays, room_params("PHOTON", 8));
        Params sp = room_params("SPPM", 32);
        sp.set("sppm_photons", int64_t(50000));
        const RenderResult sppm = render(arrays, sp);
        const double ph = photon.mean_rgb / path.mean_rgb - 1.0, sd = sppm.mean_rgb / path.mean_rgb - 1.0;
        const double se_ph = std::hypot(path.standard_error, photon.standard_error) / path.mean_rgb;
        const double se_sd = std::hypot(path.standard_error, std::sqrt(8.0) * path.standard_error) / path.mean_rgb;
        std::printf("%s: PATH %.5f, PHOTON %+.4f (se %.4f), SPPM %+.4f (se %.4f)\n",
                    glass ? "glass room" : "diffuse room", path.mean_rgb, ph, se_ph, sd, se_sd);
        EXPECT_LT(std::fabs(ph), 0.01 + 4.0 * se_ph) << (glass ? "glass" : "diffuse");
        EXPECT_LT(std::fabs(sd), 0.02 + 4.0 * se_sd) << (glass ? "glass" : "diffuse");
    }
}

// ---- only what the scene calls for -------------------------------------------------------------------------

TEST(PhotonScene, CausticMapOnlyWithSpecularSurfaces) {
    Params p = room_params("PHOTON", 1);
    p.set("global_photons", int64_t(20000));
    p.set("caustic_photons", int64_t(20000));
    p.set("final_gather_rays", int64_t(1));
    const std::vector<std::string> diffuse = render_log(room(false), p);
    EXPECT_TRUE(log_has(diffuse, "no caustic map: no mirror, glass or narrow glossy material"));
    EXPECT_FALSE(log_has(diffuse, "caustic map of"));
    const std::vector<std::string> glass = render_log(room(true), p);
    EXPECT_TRUE(log_has(glass, "caustic map of")) << (glass.empty() ? "" : glass.front());
    EXPECT_TRUE(log_has(glass, "aimed at 1 specular object"));
    EXPECT_FALSE(log_has(glass, "no caustic map"));
}

// ---- determinism, cancel, settings -------------------------------------------------------------------------

TEST(PhotonDeterminism, SameImageForEveryThreadCount) {
    for (const char* integrator : {"PHOTON", "SPPM"}) {
        Params p = room_params(integrator, 2);
        p.set("global_photons", int64_t(30000));
        p.set("caustic_photons", int64_t(30000));
        p.set("sppm_photons", int64_t(30000));
        p.set("final_gather_rays", int64_t(2));
        p.set("threads", int64_t(1));
        const RenderResult one = render(room(true), p);
        p.set("threads", int64_t(2));
        const RenderResult two = render(room(true), p);
        ASSERT_EQ(one.rgba.size(), two.rgba.size());
        EXPECT_EQ(std::memcmp(one.rgba.data(), two.rgba.data(), one.rgba.size() * sizeof(float)), 0) << integrator;
    }
}

// Cancel while the stage runs: the render ends cancelled, with no camera pass started (work_done 0), and the
// stage's progress shows it stopped early (its shooting is checked between batches of 4096 paths, its build
// between splits and cells).
TEST(PhotonCancel, DuringShootingAndTreeBuild) {
    for (const char* stage : {"Tracing photons", "Building photon map"}) {
        Params p = room_params("PHOTON", 4);
        p.set("global_photons", int64_t(1500000));
        Session s(room(false), p);
        s.start();
        bool seen = false;
        for (int i = 0; i < 200000 && !seen; ++i) {
            const SessionProgress pr = s.progress();
            if (pr.stage.name == stage)
                seen = true;
            else if (pr.work_done > 0 || pr.stop_reason != StopReason::Running)
                break;
            else
                std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
        s.cancel();
        s.join();
        ASSERT_TRUE(seen) << stage;
        const SessionProgress pr = s.progress();
        EXPECT_EQ(pr.stop_reason, StopReason::Cancelled) << stage;
        EXPECT_EQ(pr.work_done, 0) << stage;
        EXPECT_FALSE(s.error().has_value()) << stage;
    }
}

TEST(PhotonSettings, BadSettingsAreRefusedByName) {
    auto refused = [](Params p, const std::string& key) {
        try {
            render(room(false), p);
        } catch (const std::exception& e) {
            return std::string(e.what()).find(key) != std::string::npos;
        }
        return false;
    };
    Params p = room_params("PHOTON", 1);
    p.set("photon_k", int64_t(0));
    EXPECT_TRUE(refused(p, "photon_k"));
    p = room_params("PHOTON", 1);
    p.set("photon_kernel", std::string("TRIANGLE"));
    EXPECT_TRUE(refused(p, "photon_kernel"));
    p = room_params("SPPM", 1);
    p.set("sppm_alpha", 0.0);
    EXPECT_TRUE(refused(p, "sppm_alpha"));
    p = room_params("PHOTON", 1);
    p.set("global_photons", int64_t(1000000000));
    p.set("memory_limit_mb", 2000.0);
    EXPECT_TRUE(refused(p, "global_photons"));
}

}  // namespace
}  // namespace candela::test
