// AUTO (docs/auto.md): the policy's choice and reason on the shared reference scenes, rules of missing integrators
// skipped; the choice logged and named in the status; AUTO's image the chosen integrator's, bit for bit.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <variant>

#include "film/film.h"
#include "integrators/auto/auto_policy.h"
#include "integrators/auto/scene_features.h"
#include "integrators/integrator.h"
#include "reference_scenes.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

SceneFeatures features_of(const SceneArrays& a, const Params& p = basic_params(8, 8, 1, 2)) {
    const Scene scene(a, p, nullptr);
    return analyse_scene(scene);
}

AutoChoice choice_of(const SceneFeatures& f) {
    return choose_integrator(f, [](const std::string& name) {
        for (const auto& e : integrator_registry())
            if (name == e.name) return true;
        return false;
    });
}

// A 4 × 4 diffuse floor at y = −1 and, with `mirror`, a 2 × 2 mirror standing on it.
MeshBuilder floor_and_mirror(bool mirror) {
    MeshBuilder b;
    const uint32_t floor = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(add_parallelogram(b, Vec3(-2.f, -1.f, -6.f), Vec3(0.f, 0.f, 4.f), Vec3(4.f, 0.f, 0.f), floor));
    if (mirror) {
        const uint32_t m = b.add_material(Color(0.f), Color(0.f));
        b.add_closure(m, "GLOSSY", {{"color_r", 0.9f}, {"color_g", 0.9f}, {"color_b", 0.9f}, {"roughness", 0.f}});
        b.add_instance(add_parallelogram(b, Vec3(-1.f, -1.f, -5.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 2.f, 0.f), m));
    }
    return b;
}

// The policy on every shared reference scene (tests/native/reference_scenes.h).
TEST(AutoPolicy, ChoiceAndReasonOnTheReferenceScenes) {
    struct Case {
        const char* scene;
        SceneArrays arrays;
        Params params;
        const char* integrator;
        const char* rule;
    };
    std::vector<float> veach_camera;
    SceneArrays veach = veach_scene(&veach_camera);
    std::vector<Case> cases;
    cases.push_back({"cornell_box", cornell_box(), basic_params(8, 8, 1, 2), "PATH", "default"});
    cases.push_back({"glass_caustic", glass_caustic(), basic_params(8, 8, 1, 2), "BDPT", "caustics_bdpt"});
    cases.push_back(
        {"lit_room point+disk, specular", lit_room(1 | 32, true), basic_params(8, 8, 1, 2), "BDPT", "caustics_bdpt"});
    // Its 0.5 × 0.4 rectangle is 0.2 m², under 1 % of the room's πR²: small.
    cases.push_back({"lit_room rectangle+world, specular", lit_room(64 | 256, true), basic_params(8, 8, 1, 2), "BDPT",
                     "caustics_bdpt"});
    MeshBuilder large = floor_and_mirror(true);
    large.add_area_light(Vec3(0.f, 2.f, -4.f), Vec3(3.f, 0.f, 0.f), Vec3(0.f, 0.f, 3.f), Vec3(0.f, -1.f, 0.f),
                         Color(100.f), false);
    cases.push_back(
        {"mirror under a 9 m² light", large.arrays(), basic_params(8, 8, 1, 2), "PATH", "specular_large_lights"});
    cases.push_back(
        {"lit_room all lights, diffuse", lit_room(511, false), basic_params(8, 8, 1, 2), "PATH", "default"});
    cases.push_back({"smooth_lowpoly_sphere", smooth_lowpoly_sphere(), basic_params(8, 8, 1, 2), "PATH", "default"});
    cases.push_back({"veach_scene", std::move(veach), veach_params(8, 8), "PATH", "default"});
    cases.push_back({"facing_plates", facing_plates(), facing_plates_params(8, 8, 1), "PATH", "default"});
    for (const Case& c : cases) {
        const AutoChoice choice = choice_of(features_of(c.arrays, c.params));
        EXPECT_EQ(choice.integrator, c.integrator) << c.scene << ": " << choice.reason;
        EXPECT_EQ(choice.rule, c.rule) << c.scene << ": " << choice.reason;
        EXPECT_FALSE(choice.reason.empty()) << c.scene;
    }
    // The glass caustic's reason says why, with its figures.
    const AutoChoice g = choice_of(features_of(glass_caustic()));
    EXPECT_NE(g.reason.find("caustic paths"), std::string::npos) << g.reason;
    EXPECT_NE(g.reason.find("100 %"), std::string::npos) << g.reason;
}

TEST(AutoPolicy, HiddenObjectsSendCausticsToPathAndNothingLitToo) {
    MeshBuilder b = floor_and_mirror(true);
    b.add_point_light(Vec3(0.f, 1.f, -3.f), Color(50.f));
    SceneArrays a = b.arrays();
    const uint8_t flags[2] = {uint8_t(k_object_default), uint8_t(k_object_default & ~k_ray_diffuse)};
    a.set("instance_flags", ElemType::U8, {2}, flags);
    const AutoChoice c = choice_of(features_of(a));  // caustics, but only PATH honours diffuse-ray visibility
    EXPECT_EQ(c.integrator, "PATH");
    EXPECT_EQ(c.rule, "path_only_visibility");
    EXPECT_EQ(choice_of(features_of(floor_and_mirror(true).arrays())).rule, "nothing_lit");
}

TEST(AutoPolicy, RulesWhoseIntegratorIsMissingAreSkipped) {
    const SceneFeatures f = features_of(glass_caustic());
    const AutoChoice all = choose_integrator(f, [](const std::string&) { return true; });
    EXPECT_EQ(all.integrator, "BDPT");  // the measured rule comes before SPPM's
    const AutoChoice without = choose_integrator(f, [](const std::string& n) { return n != "BDPT"; });
    EXPECT_EQ(without.integrator, "SPPM");
    const AutoChoice path_only = choose_integrator(f, [](const std::string& n) { return n == "PATH"; });
    EXPECT_EQ(path_only.integrator, "PATH");
    EXPECT_EQ(path_only.rule, "default");  // the next rule that applies with an available integrator
    // Every rule names an integrator; the last always applies.
    EXPECT_TRUE(auto_rules().back().applies(SceneFeatures{}));
}

// The pilot's measurements in the policy: a measured caustic variance share decides first and says so; below it the
// static caustic rule decides.
TEST(AutoPolicy, PilotSharesDecideWhereTheyCan) {
    SceneFeatures f = features_of(glass_caustic());
    f.pilot_measured = true;
    f.pilot.total_mean = 1.0;
    f.pilot.mean = {0.1, 0.5, 0.2, 0.2};
    f.pilot.variance = {0.05, 0.2, 0.13, 0.62};
    f.pilot.caustic_path_count = 20;
    AutoChoice c = choice_of(f);
    EXPECT_EQ(c.integrator, "BDPT");
    EXPECT_EQ(c.rule, "measured_caustics_bdpt");
    EXPECT_EQ(c.reason.rfind("62 % of the variance is caustic", 0), 0u) << c.reason;
    f.pilot.caustic_path_count = 1000;
    f.pilot.variance = {0.05, 0.5, 0.3, 0.15};  // caustic (≥ 10 %), but not dominant: the static rule
    EXPECT_EQ(choice_of(f).rule, "caustics_bdpt");
    // From a point light the pilot (a path tracer) cannot see a caustic: a zero measured share leaves the static rule.
    SceneFeatures point = features_of(lit_room(1, true));
    ASSERT_TRUE(point.caustic_paths);
    point.pilot_measured = true;
    point.pilot.total_mean = 1.0;
    point.pilot.mean = {0.0, 0.7, 0.3, 0.0};
    point.pilot.variance = {0.0, 0.7, 0.3, 0.0};
    EXPECT_EQ(choice_of(point).rule, "caustics_bdpt");
}

// Rule 3a (measured_caustics_bdpt) trusts a dominant caustic share only from as many caustic paths as rule 3 needs
// (20): the held-out table_caustic's pilot measured 66 % from one path. Below the count the static rule decides and
// its reason says why; a scene without static caustic paths (a mirror under a large light) then stays with PATH.
TEST(AutoPolicy, DominantCausticShareNeedsEnoughCausticPaths) {
    SceneFeatures f = features_of(glass_caustic());
    f.pilot_measured = true;
    f.pilot.total_mean = 1.0;
    f.pilot.mean = {0.0, 0.6, 0.3, 0.1};
    f.pilot.variance = {0.0, 0.2, 0.14, 0.66};
    for (uint64_t n : {uint64_t(1), uint64_t(19)}) {
        f.pilot.caustic_path_count = n;
        const AutoChoice c = choice_of(f);
        EXPECT_EQ(c.rule, "caustics_bdpt") << n;
        EXPECT_NE(c.reason.find("found caustic light " + std::to_string(n) + " times, too few to measure"),
                  std::string::npos)
            << c.reason;
    }
    f.pilot.caustic_path_count = 20;
    EXPECT_EQ(choice_of(f).rule, "measured_caustics_bdpt");
    SceneFeatures large = features_of(floor_and_mirror(true).arrays());  // no light: add the pilot's share by hand
    large.specular_area = 4.0;
    large.caustic_paths = false;
    large.light_count = 1;
    large.pilot_measured = true;
    large.pilot = f.pilot;
    large.pilot.caustic_path_count = 1;
    large.pilot.mean = {0.0, 0.8, 0.1, 0.1};  // indirect 10 %: neither indirect rule
    EXPECT_EQ(choice_of(large).rule, "specular_large_lights");
    large.pilot.caustic_path_count = 20;
    EXPECT_EQ(choice_of(large).rule, "measured_caustics_bdpt");
}

// Rule caustics_bdpt with a pilot: the caustic must show in the measured variance (≥ 10 %), else PATH and the reason
// says so (the held-out outdoor scene: 1 % caustic, BDPT at 16× PATH's error); a scene whose power comes partly
// from a delta light keeps the static rule (the pilot cannot see its caustic), and so does a pilot whose paths found
// caustic light fewer than 20 times (too few to measure the share).
TEST(AutoPolicy, MeasuredCausticShareOverrulesTheStaticCausticRule) {
    SceneFeatures f = features_of(glass_caustic());
    ASSERT_EQ(choice_of(f).rule, "caustics_bdpt");  // without a pilot
    f.pilot_measured = true;
    f.pilot.total_mean = 1.0;
    f.pilot.mean = {0.0, 0.8, 0.19, 0.01};
    f.pilot.variance = {0.0, 0.6, 0.34, 0.06};
    f.pilot.caustic_path_count = 19;  // too few caustic paths to measure the share: the static rule
    EXPECT_EQ(choice_of(f).rule, "caustics_bdpt");
    f.pilot.caustic_path_count = 20;
    AutoChoice c = choice_of(f);
    EXPECT_EQ(c.integrator, "PATH");
    EXPECT_EQ(c.rule, "default");
    EXPECT_NE(c.reason.find("only 6 % of the variance is caustic"), std::string::npos) << c.reason;
    f.pilot.variance = {0.0, 0.6, 0.28, 0.12};
    EXPECT_EQ(choice_of(f).rule, "caustics_bdpt");
    // A soft point light (radius 0.15): not delta, the measured share decides.
    SceneFeatures soft = features_of(lit_room(2, true));
    ASSERT_TRUE(soft.caustic_paths);
    EXPECT_EQ(soft.delta_power, 0.0);
    soft.pilot_measured = true;
    soft.pilot.total_mean = 1.0;
    soft.pilot.mean = {0.0, 0.7, 0.3, 0.0};
    soft.pilot.variance = {0.0, 0.7, 0.3, 0.0};
    soft.pilot.caustic_path_count = 1000;
    EXPECT_EQ(choice_of(soft).integrator, "PATH");
    // The delta point light of lit_room(1): its power is delta, the static rule stays.
    SceneFeatures point = features_of(lit_room(1, true));
    EXPECT_GT(point.delta_power_share(), 0.99);
    point.pilot_measured = true;
    point.pilot = soft.pilot;
    EXPECT_EQ(choice_of(point).rule, "caustics_bdpt");
}

// Rule indirect_irradiance_cache: a diffuse scene whose pilot finds at least 30 % of the lit energy (direct +
// indirect + caustic) indirect goes to the irradiance cache; below that share, or with more than 5 % of the area
// glossy, specular or transmissive, PATH; the emitted class does not count (the Cornell box's visible panel).
TEST(AutoPolicy, IndirectDiffuseLightGoesToTheIrradianceCache) {
    SceneFeatures f = features_of(cornell_box());
    ASSERT_EQ(choice_of(f).rule, "default");  // without a pilot, the static features alone
    f.pilot_measured = true;
    f.pilot.total_mean = 1.0;
    f.pilot.mean = {0.53, 0.24, 0.23, 0.0};  // the Cornell box's pilot at 96 px: 49 % of the lit energy indirect
    f.pilot.variance = {0.94, 0.0, 0.06, 0.0};
    AutoChoice c = choice_of(f);
    EXPECT_EQ(c.integrator, "IRRADIANCE_CACHE");
    EXPECT_EQ(c.rule, "indirect_irradiance_cache");
    EXPECT_EQ(c.reason.rfind("49 % of the lit energy is indirect", 0), 0u) << c.reason;
    f.pilot.mean = {0.53, 0.35, 0.12, 0.0};  // 26 %: under the threshold
    EXPECT_EQ(choice_of(f).rule, "default");
    f.pilot.mean = {0.0, 0.0, 0.0, 0.0};  // nothing lit measured: no share, no cache
    EXPECT_EQ(choice_of(f).rule, "default");
    f.pilot.mean = {0.53, 0.24, 0.23, 0.0};
    f.glossy_area = 0.06 * f.total_area;  // 6 % glossy: not the diffuse scenes the rule was measured on
    EXPECT_EQ(choice_of(f).rule, "default");
    // Rule indirect_only_bdpt: 80 % or more of the lit energy indirect (the door ajar's pilot: 95 %) goes to BDPT first,
    // diffuse or not.
    f.pilot.mean = {0.0, 0.05, 0.95, 0.0};
    c = choice_of(f);
    EXPECT_EQ(c.integrator, "BDPT");
    EXPECT_EQ(c.rule, "indirect_only_bdpt");
    EXPECT_EQ(c.reason.rfind("95 % of the lit energy arrives after bounces", 0), 0u) << c.reason;
    // Without the cache in the build, PATH.
    f.pilot.mean = {0.53, 0.24, 0.23, 0.0};
    f.glossy_area = 0.0;
    EXPECT_EQ(choose_integrator(f, [](const std::string& n) { return n != "IRRADIANCE_CACHE"; }).integrator, "PATH");
}

// One frame of an animation: no integrator whose image flickers from frame to frame (caches placed anew each frame,
// Metropolis samplers); the reason names the rule passed over. Stills are unchanged.
TEST(AutoPolicy, AnimationChoosesNoCacheOrMetropolisThatFlickers) {
    SceneFeatures f = features_of(cornell_box());
    f.pilot_measured = true;
    f.pilot.total_mean = 1.0;
    f.pilot.mean = {0.0, 0.5, 0.5, 0.0};  // indirect-heavy diffuse: the irradiance cache for a still
    ASSERT_EQ(choice_of(f).integrator, "IRRADIANCE_CACHE");
    f.animation = true;
    const AutoChoice c = choice_of(f);
    EXPECT_EQ(c.integrator, "PATH");
    EXPECT_EQ(c.rule, "default");
    EXPECT_NE(c.reason.find("animation: not IRRADIANCE_CACHE (rule indirect_irradiance_cache)"), std::string::npos)
        << c.reason;
    // SPPM (the caustic rule without BDPT in the build) is ruled out too; BDPT is not.
    SceneFeatures g = features_of(glass_caustic());
    g.animation = true;
    EXPECT_EQ(choice_of(g).integrator, "BDPT");
    EXPECT_EQ(choose_integrator(g, [](const std::string& n) { return n != "BDPT"; }).integrator, "PATH");
    for (const char* name : {"MLT", "MMLT", "IRRADIANCE_CACHE", "PHOTON", "SPPM"})
        EXPECT_TRUE(flickers_in_animation(name));
    for (const char* name : {"PATH", "BDPT", "LIGHT"}) EXPECT_FALSE(flickers_in_animation(name));
}

// AUTO renders the chosen integrator's image, bit for bit, and says what it chose in the log and the status.
void expect_auto_is(SceneArrays arrays, const char* expected) {
    Params base = basic_params(16, 12, 4, 3);
    base.set("threads", int64_t(2));
    const PreparedScene scene(std::move(arrays), base);
    Params chosen, autop;
    chosen.set("integrator", std::string(expected));
    autop.set("integrator", std::string("AUTO"));
    const RenderResult a = scene.render(autop), b = scene.render(chosen);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    size_t differ = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) differ += a.rgba[i] != b.rgba[i];
    EXPECT_EQ(differ, 0u) << expected;
    EXPECT_EQ(a.samples_done, b.samples_done);
    EXPECT_GT(a.mean_rgb, 0.0);

    Params p = base;
    p.set("integrator", std::string("AUTO"));
    Film film(16, 12, 0, 0, 32);
    const std::unique_ptr<Integrator> integrator = make_integrator(p);
    CancelToken cancel;
    RenderCounters counters;
    MessageLog log;
    RenderContext ctx{cancel, counters, 2, nullptr, &log};
    integrator->render(scene.scene(), film, ctx);
    const std::string method = counters.method.get();
    EXPECT_EQ(method.rfind(std::string("Auto: ") + expected + " \xe2\x80\x94 ", 0), 0u) << method;
    const std::vector<std::string> lines = log.take();
    bool features = false, decision = false, pilot = false, tree = false;
    // The light tree (the pilot's and PATH's) is PATH's cost when PATH with the tree is chosen, the analysis's else.
    const std::string tree_note =
        std::string(expected) == "PATH" ? "PATH's own, not counted" : "counted in the analysis";
    for (const std::string& l : lines) {
        std::printf("%s\n", l.c_str());  // what the user's log shows (docs/auto.md quotes it)
        features |= l.rfind("Auto: scene features:", 0) == 0;
        decision |= l.rfind(std::string("Auto: chose ") + expected, 0) == 0;
        pilot |= l.rfind("Auto: pilot ", 0) == 0;
        tree |= l.rfind("Auto: chose ", 0) == 0 && l.find("; light tree ") != std::string::npos &&
                l.find(tree_note) != std::string::npos;
    }
    EXPECT_TRUE(features && decision && pilot && tree) << expected;
    EXPECT_EQ(counters.work_total.load(), 4);
}

// The "animation" param (the add-on sends it to AUTO for a frame of an animation) reaches the policy: the Cornell box,
// a still's IRRADIANCE_CACHE, renders with PATH and the status says why.
TEST(AutoIntegrator, AnimationParamRulesOutTheCache) {
    const PreparedScene scene(cornell_box(), basic_params(16, 12, 4, 3));
    Params p = basic_params(16, 12, 4, 3);
    p.set("integrator", std::string("AUTO"));
    p.set("animation", true);
    Film film(16, 12, 0, 0, 32);
    const std::unique_ptr<Integrator> integrator = make_integrator(p);
    CancelToken cancel;
    RenderCounters counters;
    MessageLog log;
    RenderContext ctx{cancel, counters, 2, nullptr, &log};
    integrator->render(scene.scene(), film, ctx);
    const std::string method = counters.method.get();
    EXPECT_EQ(method.rfind("Auto: PATH \xe2\x80\x94 ", 0), 0u) << method;
    EXPECT_NE(method.find("animation: not IRRADIANCE_CACHE"), std::string::npos) << method;
    for (const std::string& key : p.unused_keys()) EXPECT_NE(key, "animation");  // read: no unused-setting warning
}

TEST(AutoIntegrator, RendersTheChosenIntegratorsImageBitForBit) {
    // The Cornell box's pilot (its panel unseen from this camera) finds 41 % of the lit energy indirect.
    expect_auto_is(cornell_box(), "IRRADIANCE_CACHE");
    expect_auto_is(glass_caustic(), "BDPT");
    // Every light kind; its pilot here finds 28 % of the lit energy indirect, under the cache's 30 %: rule default.
    expect_auto_is(lit_room(511, false), "PATH");
}

}  // namespace
}  // namespace candela::test
