// AUTO's pilot render (integrators/auto/pilot.h, docs/auto.md "Pilot"): its class energies agree with independent
// estimates — a closed form (the facing plates' one bounce), PATH's direct-only image, PATH with the Caustics
// switches off — and classes that a scene cannot have measure exactly 0; deterministic for a seed whatever the thread
// count. Agreement tolerances are 4 σ of the difference (σ from the per-pixel sample variances of the pilot and of
// PATH's Noise pass; σ's summed, not combined in quadrature, where the two PATH images share a seed): a false-alarm
// rate under 1e-4 per comparison.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "integrators/auto/auto_policy.h"
#include "integrators/auto/pilot.h"
#include "integrators/auto/scene_features.h"
#include "reference_scenes.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr double k_z = 4.0;

PilotSettings settings_for(const Params& p, int samples, uint64_t seed = 7, int threads = 2) {
    PilotSettings s;
    s.downscale = 1;
    s.samples = samples;
    s.max_bounces = p.get<int>("max_bounces", 12);
    s.seed = seed;
    s.threads = threads;
    s.width = p.get<int>("width", 0);
    s.height = p.get<int>("height", 0);
    return s;
}

double mean_luminance(const RenderResult& r) {
    double sum = 0.0;
    const size_t n = size_t(r.width) * r.height;
    for (size_t i = 0; i < n; ++i)
        sum += 0.2126 * r.rgba[4 * i] + 0.7152 * r.rgba[4 * i + 1] + 0.0722 * r.rgba[4 * i + 2];
    return sum / double(n);
}

void print(const char* scene, const PilotResult& r) { std::printf("%s: %s\n", scene, r.summary().c_str()); }

// The facing plates with one bounce: the receiver has no direct light (it is coplanar with the light), so every bit
// of its radiance is indirect, and the image mean is the closed-form one-bounce answer.
TEST(Pilot, FacingPlatesAreAllIndirectAndMatchTheClosedForm) {
    const Params p = facing_plates_params(16, 16, 1);
    const Scene scene(facing_plates(), p, nullptr);
    const PilotResult r = run_pilot(scene, settings_for(p, 64));
    print("facing_plates", r);
    EXPECT_EQ(r.mean[int(PathClass::Emitted)], 0.0);
    EXPECT_EQ(r.mean[int(PathClass::Direct)], 0.0);
    EXPECT_EQ(r.mean[int(PathClass::Caustic)], 0.0);
    EXPECT_EQ(r.through_transmissive_mean, 0.0);
    const double expected = facing_plates_expected();
    EXPECT_NEAR(r.mean[int(PathClass::Indirect)], expected, k_z * r.class_standard_error[int(PathClass::Indirect)])
        << "expected " << expected;
    EXPECT_GT(r.standard_error, 0.0);
}

// The Cornell box: no delta surface, nothing transmissive — no caustic energy and nothing through glass, exactly.
// Emitted + direct agree with PATH at max_bounces 0 (direct lighting only), the total with PATH's full image.
TEST(Pilot, CornellBoxClassesAgreeWithPathsDirectAndFullImages) {
    const Params base = basic_params(32, 32, 1, 8);
    const PreparedScene prepared(cornell_box(), base);
    const PilotResult r = run_pilot(prepared.scene(), settings_for(base, 64));
    print("cornell_box", r);
    EXPECT_EQ(r.mean[int(PathClass::Caustic)], 0.0);
    EXPECT_EQ(r.variance[int(PathClass::Caustic)], 0.0);
    EXPECT_EQ(r.through_transmissive_mean, 0.0);
    EXPECT_EQ(r.specular_after_diffuse_mean, 0.0);
    EXPECT_GT(r.energy_share(PathClass::Indirect), 0.0);

    Params direct;
    direct.set("samples", int64_t(256));
    direct.set("max_bounces", int64_t(0));
    const RenderResult d = prepared.render(direct);
    const double pilot_direct = r.mean[int(PathClass::Emitted)] + r.mean[int(PathClass::Direct)];
    const double sd =
        std::hypot(r.class_standard_error[int(PathClass::Emitted)] + r.class_standard_error[int(PathClass::Direct)],
                   d.standard_error);
    EXPECT_NEAR(pilot_direct, mean_luminance(d), k_z * sd);

    Params full;
    full.set("samples", int64_t(256));
    const RenderResult f = prepared.render(full);
    EXPECT_NEAR(r.total_mean, mean_luminance(f), k_z * std::hypot(r.standard_error, f.standard_error));
}

// The glass caustic: the caustic class carries a large share of the variance (the floor's caustic, found by hitting
// the small light after the glass), and what the Caustics switches remove from PATH's image is what the pilot counts
// as a delta scatter after a diffuse one (the scene's non-delta lobes are all diffuse, so the caustic class is part
// of it).
TEST(Pilot, GlassCausticIsCausticAndMatchesPathsCausticsSwitch) {
    const Params base = basic_params(32, 24, 1, 8);
    const PreparedScene prepared(glass_caustic(), base);
    const PilotResult r = run_pilot(prepared.scene(), settings_for(base, 64));
    print("glass_caustic", r);
    EXPECT_GT(r.variance_share(PathClass::Caustic), 0.5);
    EXPECT_GT(r.energy_share(PathClass::Caustic), 0.0);
    EXPECT_LE(r.mean[int(PathClass::Caustic)], r.specular_after_diffuse_mean);
    EXPECT_GT(r.through_transmissive_mean, 0.0);  // the sphere's shadow: light behind glass
    // With these measurements AUTO's policy: the 76 % share comes from 10 caustic paths, under the 20 rule 3a needs
    // (auto_policy.cpp), so the static caustic rule decides and says why; a pilot of 4× the paths finds enough, and
    // then the policy names the caustic variance as its reason.
    SceneFeatures f = analyse_scene(prepared.scene());
    f.pilot = r;
    f.pilot_measured = true;
    const auto all_available = [](const std::string&) { return true; };
    ASSERT_LT(r.caustic_path_count, 20u);
    AutoChoice choice = choose_integrator(f, all_available);
    EXPECT_EQ(choice.rule, "caustics_bdpt") << choice.reason;
    EXPECT_NE(choice.reason.find("too few to measure"), std::string::npos) << choice.reason;
    f.pilot = run_pilot(prepared.scene(), settings_for(base, 256));
    print("glass_caustic, 256 paths", f.pilot);
    ASSERT_GE(f.pilot.caustic_path_count, 20u);
    choice = choose_integrator(f, all_available);
    EXPECT_EQ(choice.rule, "measured_caustics_bdpt") << choice.reason;
    EXPECT_NE(choice.reason.find("of the variance is caustic"), std::string::npos) << choice.reason;
    std::printf("Auto: %s \xe2\x80\x94 %s\n", choice.integrator.c_str(), choice.reason.c_str());

    Params all, off;
    all.set("samples", int64_t(512));
    off.set("samples", int64_t(512));
    off.set("caustics_reflective", false);
    off.set("caustics_refractive", false);
    const RenderResult a = prepared.render(all), o = prepared.render(off);
    const double removed = mean_luminance(a) - mean_luminance(o);
    // A bound on the σ of the sum of the pilot's tallies: the caustic class's and the rest of the delta-after-diffuse
    // energy are parts of the total, so the total's σ bounds neither; their upper bound is the total's plus the
    // caustic's.
    const double s_pilot = r.standard_error + r.class_standard_error[int(PathClass::Caustic)];
    EXPECT_NEAR(r.specular_after_diffuse_mean, removed, k_z * (s_pilot + a.standard_error + o.standard_error));
    EXPECT_GT(removed, 0.0);
}

// Deterministic for a seed whatever the thread count; another seed gives another estimate.
TEST(Pilot, DeterministicForASeed) {
    const Params base = basic_params(24, 18, 1, 8);
    const Scene scene(glass_caustic(), base, nullptr);
    const PilotResult a = run_pilot(scene, settings_for(base, 8, 3, 1));
    const PilotResult b = run_pilot(scene, settings_for(base, 8, 3, 2));
    const PilotResult c = run_pilot(scene, settings_for(base, 8, 4, 2));
    for (int k = 0; k < k_path_classes; ++k) {
        EXPECT_EQ(a.mean[k], b.mean[k]) << path_class_name(PathClass(k));
        EXPECT_EQ(a.variance[k], b.variance[k]) << path_class_name(PathClass(k));
    }
    EXPECT_EQ(a.rays, b.rays);
    EXPECT_EQ(a.firefly_share, b.firefly_share);
    EXPECT_NE(a.total_mean, c.total_mean);
}

// The pilot's size: a coarser grid for larger films, always the film's region.
TEST(Pilot, SettingsScaleWithTheFilm) {
    EXPECT_EQ(pilot_settings_for(0, 0, 1920, 1080, 64, 12, 0, 0).downscale, 4);
    EXPECT_EQ(pilot_settings_for(0, 0, 100, 64, 64, 12, 0, 0).downscale, 2);
    // 96 × 54 (16:9 at make accuracy-auto's size): 2×, 1/32 of a 64-sample render's paths (docs/auto.md, "Acceptance":
    // at 1× the pilot was 7–11 % of the render's time on the glossy and Veach scenes)
    EXPECT_EQ(pilot_settings_for(0, 0, 96, 54, 64, 12, 0, 0).downscale, 2);
    EXPECT_EQ(pilot_settings_for(0, 0, 40, 31, 64, 12, 0, 0).downscale, 1);
    EXPECT_EQ(pilot_settings_for(0, 0, 16, 12, 64, 12, 0, 0).downscale, 1);
    EXPECT_EQ(pilot_settings_for(0, 0, 16, 12, 64, 12, 0, 0).samples, 8);
    EXPECT_EQ(pilot_settings_for(0, 0, 16, 12, 1024, 12, 0, 0).samples, 8);
    EXPECT_EQ(pilot_settings_for(0, 0, 16, 12, 4, 12, 0, 0).samples, 2);  // the fewest with a variance
    const PilotSettings s = pilot_settings_for(10, 20, 300, 200, 64, 5, 9, 2);
    EXPECT_EQ(s.x0, 10);
    EXPECT_EQ(s.y0, 20);
    EXPECT_EQ(s.max_bounces, 5);
    EXPECT_EQ(s.seed, 9u);
}

}  // namespace
}  // namespace candela::test
