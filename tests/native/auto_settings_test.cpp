// AUTO's settings table (docs/auto.md, "Settings"): the chosen integrator's main settings from the features on the
// built feature scenes, logged and in the status line, and a setting the caller set kept.
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

SceneFeatures features_of(const SceneArrays& a) {
    const Scene scene(a, basic_params(8, 8, 1, 2), nullptr);
    return analyse_scene(scene);
}

AutoChoice choice_of(const SceneFeatures& f) {
    return choose_integrator(f, [](const std::string& name) {
        for (const auto& e : integrator_registry())
            if (name == e.name) return true;
        return false;
    });
}

// The settings table on the built feature scenes: PATH's light selection from the light-set entries (one: POWER;
// more, an emissive mesh counting one per triangle: TREE); BDPT and IRRADIANCE_CACHE have no entry.
TEST(AutoPolicy, SettingsChosenFromTheFeatures) {
    struct Case {
        const char* scene;
        SceneArrays arrays;
        const char* integrator;
        const char* light_selection;  // nullptr: no setting
    };
    std::vector<float> veach_camera;
    std::vector<Case> cases;
    cases.push_back({"lit_room point", lit_room(1, false), "PATH", "POWER"});
    cases.push_back({"lit_room every light", lit_room(511, false), "PATH", "TREE"});
    cases.push_back({"cornell_box", cornell_box(), "PATH", "TREE"});
    cases.push_back({"veach_mis", veach_scene(&veach_camera), "PATH", "TREE"});
    cases.push_back({"glass_caustic", glass_caustic(), "BDPT", nullptr});
    for (Case& c : cases) {
        const SceneFeatures f = features_of(c.arrays);
        const AutoChoice choice = choice_of(f);
        ASSERT_EQ(choice.integrator, c.integrator) << c.scene;
        if (c.light_selection == nullptr) {
            EXPECT_TRUE(choice.settings.empty()) << c.scene;
            continue;
        }
        ASSERT_EQ(choice.settings.size(), 1u) << c.scene;
        const AutoSetting& s = choice.settings[0];
        EXPECT_EQ(s.key, "light_selection");
        EXPECT_EQ(std::get<std::string>(s.value), c.light_selection) << c.scene << ": " << s.describe();
        EXPECT_EQ(s.describe().rfind(std::string("light_selection ") + c.light_selection + " (", 0), 0u);
        EXPECT_EQ(std::string(c.light_selection) == "POWER", f.light_count <= 1) << c.scene << f.light_count;
    }
}

// A one-light scene AUTO renders with PATH: the settings table picks POWER light selection, the log and the status
// line say so, and the image is PATH's default (TREE) image bit for bit: with one light both pick it with
// probability 1 (the claim the setting's reason rests on).
TEST(AutoIntegrator, OneLightPathUsesPowerSelectionAndTheSameImage) {
    Params base = basic_params(16, 12, 4, 3);
    base.set("threads", int64_t(2));
    const PreparedScene scene(lit_room(1, false), base);
    Params autop, tree, power;
    autop.set("integrator", std::string("AUTO"));
    tree.set("integrator", std::string("PATH"));
    power.set("integrator", std::string("PATH"));
    power.set("light_selection", std::string("POWER"));
    const RenderResult a = scene.render(autop), t = scene.render(tree), w = scene.render(power);
    ASSERT_EQ(a.rgba.size(), t.rgba.size());
    size_t differ_tree = 0, differ_power = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        differ_tree += a.rgba[i] != t.rgba[i];
        differ_power += a.rgba[i] != w.rgba[i];
    }
    EXPECT_EQ(differ_power, 0u);
    EXPECT_EQ(differ_tree, 0u);

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
    EXPECT_EQ(method.rfind("Auto: PATH \xe2\x80\x94 ", 0), 0u) << method;
    EXPECT_NE(method.find("; settings: light_selection POWER (one light"), std::string::npos) << method;
    bool logged = false, counted = false;
    for (const std::string& l : log.take()) {
        std::printf("%s\n", l.c_str());
        logged |= l.rfind("Auto: PATH settings: light_selection POWER (one light", 0) == 0;
        counted |= l.rfind("Auto: chose PATH", 0) == 0 && l.find("counted in the analysis") != std::string::npos;
    }
    EXPECT_TRUE(logged);
    EXPECT_TRUE(counted);  // PATH without the tree: the pilot's tree is the analysis's cost

    // A light selection the caller set is kept, and the status says what AUTO would have chosen.
    p.set("light_selection", std::string("UNIFORM"));
    Film film2(16, 12, 0, 0, 32);
    RenderCounters counters2;
    RenderContext ctx2{cancel, counters2, 2, nullptr, &log};
    make_integrator(p)->render(scene.scene(), film2, ctx2);
    EXPECT_NE(counters2.method.get().find("light_selection as set, not light_selection POWER"), std::string::npos)
        << counters2.method.get();
    (void)log.take();
}

}  // namespace
}  // namespace candela::test
