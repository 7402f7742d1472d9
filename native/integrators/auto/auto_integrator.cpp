#include "integrators/auto/auto_integrator.h"

#include <chrono>
#include <cstdio>

#include "integrators/auto/auto_policy.h"
#include "integrators/auto/scene_features.h"
#include "integrators/path/path_settings.h"
#include "integrators/scene_skips.h"
#include "lights/light_sampler.h"

namespace candela {

namespace {

bool in_registry(const std::string& name) {
    for (const auto& e : integrator_registry())
        if (name == e.name && name != "AUTO") return true;
    return false;
}

class AutoIntegrator final : public Integrator {
public:
    explicit AutoIntegrator(const Params& params)
        : m_params(params),
          // Built from the caller's params so their common keys count as read (Session reports unread ones), and
          // for the budget before the scene exists: PATH's, in samples; render() replaces it by the choice's.
          m_probe(find_integrator("PATH").create(params)),
          m_animation(params.get<bool>("animation", false)) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        ctx.counters.stage.begin("Analysing scene", 0);
        const PathSettings path = PathSettings::from_params(m_params);
        // The light tree the pilot's next-event estimation uses, built first and timed apart: the scene caches it,
        // and a chosen PATH with the tree (its default) uses the same one, so it is PATH's cost, not the analysis's
        // (on Veach's MIS scene, 8,832 emissive triangles, it was most of the pilot's time: docs/auto.md).
        const auto t_tree = std::chrono::steady_clock::now();
        (void)scene.light_sampler(LightSelection::Tree);
        const auto t0 = std::chrono::steady_clock::now();
        const double tree_ms = std::chrono::duration<double, std::milli>(t0 - t_tree).count();
        SceneFeatures features = analyse_scene(scene);
        // The pilot (pilot.h): PATH's bounce limit and seed, over the film's region.
        features.pilot =
            run_pilot(scene,
                      pilot_settings_for(film.origin_x(), film.origin_y(), film.width(), film.height(),
                                         path.pixel.samples, path.max_bounces, path.pixel.seed, ctx.threads),
                      &ctx.cancel);
        features.pilot_measured = true;
        features.animation = m_animation;
        const AutoChoice choice = choose_integrator(features, &in_registry);
        // The chosen integrator's main settings (auto_setting_rules), where the caller did not set them.
        Params chosen_params = m_params;
        std::string settings;
        for (const AutoSetting& s : choice.settings) {
            settings += settings.empty() ? "" : "; ";
            if (m_params.has(s.key)) {  // the caller's (a scene dump of another integrator's params, a script)
                settings += s.key + " as set, not " + s.describe();
                continue;
            }
            chosen_params.set(s.key, s.value);
            settings += s.describe();
        }
        const bool tree_shared =
            choice.integrator == "PATH" &&
            parse_light_selection(PathSettings::from_params(chosen_params).light_selection) == LightSelection::Tree;
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() +
                          (tree_shared ? 0.0 : tree_ms);
        ctx.counters.stage.end();
        ctx.info(features.summary());
        ctx.info(features.pilot.summary());
        char took[192];
        std::snprintf(took, sizeof took, " (rule %s; analysis %.1f ms, of which pilot %.1f ms; light tree %.1f ms, %s)",
                      choice.rule.c_str(), ms, features.pilot.milliseconds, tree_ms,
                      tree_shared ? "PATH's own, not counted" : "counted in the analysis");
        ctx.info("Auto: chose " + choice.integrator + " \xe2\x80\x94 " + choice.reason + took);
        if (!settings.empty()) ctx.info("Auto: " + choice.integrator + " settings: " + settings);
        ctx.counters.method.set("Auto: " + choice.integrator + " \xe2\x80\x94 " + choice.reason +
                                (settings.empty() ? "" : "; settings: " + settings));
        const std::string skipped = scene_skips_line(scene_skips(choice.integrator, scene));
        if (!skipped.empty()) ctx.info(skipped);
        std::unique_ptr<Integrator> chosen = find_integrator(choice.integrator).create(chosen_params);
        const std::string note = unhonoured_features_note(choice.integrator, chosen->honoured_features(), scene);
        if (!note.empty()) ctx.log(note);
        ctx.counters.work_total = chosen->budget().total;
        chosen->render(scene, film, ctx);
    }

    WorkBudget budget() const override { return m_probe->budget(); }
    /// What AUTO's choice does not honour is logged after the choice, under the chosen integrator's name; the
    /// session must not log it before, for AUTO itself.
    uint32_t honoured_features() const override { return ~0u; }

private:
    Params m_params;
    std::unique_ptr<Integrator> m_probe;
    bool m_animation;  // one frame of an animation (the add-on sends it): no integrator that flickers
};

}  // namespace

std::unique_ptr<Integrator> make_auto_integrator(const Params& params) {
    return std::make_unique<AutoIntegrator>(params);
}

const std::vector<ParamSpec>& auto_param_specs() {
    static const std::vector<ParamSpec> specs;
    return specs;
}

}  // namespace candela
