// The policy table (docs/auto.md, "Policy"). Thresholds marked "guess" there are not tuned by measurement yet.
#include "integrators/auto/auto_policy.h"

#include <cstdio>
#include <variant>

#include "core/error.h"
#include "scene/ray_visibility.h"

namespace candela {

namespace {

std::string percent(double share) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f %%", 100.0 * share);
    return buf;
}

// Ray types that only camera-rooted paths can honour (light-rooted integrators say so and ignore them).
constexpr uint32_t k_path_only_visibility = k_ray_diffuse | k_ray_glossy | k_ray_transmission;

bool nothing_lit(const SceneFeatures& f) { return f.light_count == 0 && f.world == WorldKind::None; }
bool path_only_visibility(const SceneFeatures& f) { return (f.hidden_ray_types & k_path_only_visibility) != 0; }
// The pilot's indirect share of the lit energy (all but the emitted class) that calls for the irradiance cache, and
// the share of the area that may be other than diffuse (docs/auto.md, "Acceptance": the Cornell box's 0.49 and the
// room lit through a window's 0.56 against ≤ 0.13 on every other accuracy scene; both diffuse-only).
constexpr double k_indirect_energy_share = 0.3;
// The indirect share above which the light reaches what the camera sees only after bounces, from a source the
// camera's paths rarely find (Veach's door ajar: 0.95; docs/auto.md, "Acceptance"): light subpaths carry it (BDPT).
constexpr double k_indirect_only_share = 0.8;
constexpr double k_non_diffuse_area_share = 0.05;

double lit_indirect_share(const SceneFeatures& f) {
    const double lit = f.pilot.mean[int(PathClass::Direct)] + f.pilot.mean[int(PathClass::Indirect)] +
                       f.pilot.mean[int(PathClass::Caustic)];
    return lit > 0.0 ? f.pilot.mean[int(PathClass::Indirect)] / lit : 0.0;
}
bool indirect_diffuse(const SceneFeatures& f) {
    return f.pilot_measured && lit_indirect_share(f) >= k_indirect_energy_share &&
           f.area_share(f.glossy_area + f.specular_area + f.transmissive_area) <= k_non_diffuse_area_share;
}
bool indirect_only(const SceneFeatures& f) {
    return f.pilot_measured && lit_indirect_share(f) >= k_indirect_only_share;
}
// With a pilot, the static caustic rule needs the caustic to show in the measured variance (docs/auto.md, rule 3:
// the held-out outdoor scene, 1 % caustic, and mirror_interior, 6 %, were 16× and 1.5× PATH's error with BDPT; the
// caustic scene 98 %). Not where delta lights carry power: the pilot, a path tracer, cannot see their caustics (nor
// can PATH render them), so there the static feature decides.
// Nor where the pilot's paths found caustic light too rarely to measure its share (a guess: with 20 such paths the
// caustic mean's relative standard error is about 1/√20 ≈ 22 % for contributions of similar size; the glass caustic's
// test pilot of 192 px × 2 paths finds none).
constexpr double k_static_caustic_variance_share = 0.1;
constexpr uint64_t k_measured_caustic_paths = 20;
bool caustic_share_measured(const SceneFeatures& f) {
    return f.pilot_measured && f.delta_power <= 0.0 && f.pilot.caustic_path_count >= k_measured_caustic_paths;
}
// Rule 3a: a measured caustic variance share that calls for BDPT (a guess), trusted only from as many caustic paths
// as rule 3 needs (until 2026-12-03 it had no count and fired on a share from one path: table_caustic's 66 % and
// mirror_interior at 64 px, docs/auto.md); with fewer, rule 3's static feature decides.
constexpr double k_caustic_variance_share = 0.5;
bool measured_caustics(const SceneFeatures& f) {
    return f.pilot_measured && f.pilot.caustic_path_count >= k_measured_caustic_paths &&
           f.pilot.variance_share(PathClass::Caustic) >= k_caustic_variance_share;
}
bool caustics(const SceneFeatures& f) {
    if (!f.caustic_paths) return false;
    if (!caustic_share_measured(f)) return true;
    return f.pilot.variance_share(PathClass::Caustic) >= k_static_caustic_variance_share;
}
bool specular_large_lights(const SceneFeatures& f) { return f.specular_area > 0.0 && !f.caustic_paths; }
bool always(const SceneFeatures&) { return true; }

std::string caustic_reason(const SceneFeatures& f) {
    std::string r = "caustic paths (L S+ D): delta surfaces " + percent(f.area_share(f.specular_area)) +
                    " of the area, " + percent(f.unhittable_power_share() + f.small_power_share()) +
                    " of the light power from lights a path tracer cannot hit or rarely hits";
    if (f.pilot_measured && !caustic_share_measured(f))
        r += f.delta_power > 0.0 ? " (delta lights: the pilot cannot see their caustics)"
                                 : " (the pilot's paths found caustic light " +
                                       std::to_string(f.pilot.caustic_path_count) + " times, too few to measure)";
    return r;
}

std::string default_reason(const SceneFeatures& f) {
    if (f.caustic_paths)  // the static caustic rule overruled by the pilot (caustics above)
        return "caustic paths possible, but only " + percent(f.pilot.variance_share(PathClass::Caustic)) +
               " of the variance is caustic (pilot): path tracing with light sampling";
    return "diffuse and glossy surfaces, no caustic paths: path tracing with light sampling";
}

}  // namespace

const std::vector<AutoRule>& auto_rules() {
    static const std::vector<AutoRule> rules = {
        {"nothing_lit", "PATH", &nothing_lit,
         [](const SceneFeatures&) -> std::string { return "no lights and a black world: nothing to estimate"; }},
        {"path_only_visibility", "PATH", &path_only_visibility,
         [](const SceneFeatures&) -> std::string {
             return "objects hidden from diffuse, glossy or transmission rays: only path tracing honours that";
         }},
        // BDPT before SPPM: BDPT's carrying of caustics is measured (docs/bdpt.md's strategy images, the caustic
        // agreement tests) and unbiased; SPPM for caustics is a guess not yet measured in make accuracy.
        {"measured_caustics_bdpt", "BDPT", &measured_caustics,
         [](const SceneFeatures& f) -> std::string {
             return percent(f.pilot.variance_share(PathClass::Caustic)) + " of the variance is caustic (" +
                    percent(f.pilot.energy_share(PathClass::Caustic)) + " of the energy; pilot)";
         }},
        {"caustics_bdpt", "BDPT", &caustics, &caustic_reason},
        {"caustics_sppm", "SPPM", &caustics, &caustic_reason},
        {"specular_large_lights", "PATH", &specular_large_lights,
         [](const SceneFeatures& f) -> std::string {
             return "delta surfaces (" + percent(f.area_share(f.specular_area)) +
                    " of the area) lit only by large lights a path tracer hits";
         }},
        {"indirect_only_bdpt", "BDPT", &indirect_only,
         [](const SceneFeatures& f) -> std::string {
             return percent(lit_indirect_share(f)) +
                    " of the lit energy arrives after bounces: light paths find it (pilot)";
         }},
        {"indirect_irradiance_cache", "IRRADIANCE_CACHE", &indirect_diffuse,
         [](const SceneFeatures& f) -> std::string {
             return percent(lit_indirect_share(f)) +
                    " of the lit energy is indirect, on diffuse surfaces: cached irradiance (pilot)";
         }},
        {"default", "PATH", &always, &default_reason},
    };
    return rules;
}

namespace {

// PATH's light selection (docs/auto.md, "Settings"). With one light-set entry every selection picks it with
// probability 1, so POWER's constant-time pick gives the same estimator as the tree without its traversal (tested:
// the same image bit for bit); with more (an emissive mesh counts one per triangle) the light tree, the default,
// which docs/sampling.md measures at 8× POWER's efficiency among 64 lights.
AutoSetting path_light_selection(const SceneFeatures& f) {
    if (f.light_count <= 1)
        return {"light_selection", std::string("POWER"),
                f.light_count == 0 ? "no lights to select among"
                                   : "one light: every selection picks it, POWER without the tree's traversal"};
    return {"light_selection", std::string("TREE"),
            std::to_string(f.light_count) + " lights: the light tree favours the near, facing, bright ones"};
}

std::string value_text(const Params::Value& v) {
    if (const auto* s = std::get_if<std::string>(&v)) return *s;
    if (const auto* b = std::get_if<bool>(&v)) return *b ? "on" : "off";
    if (const auto* i = std::get_if<int64_t>(&v)) return std::to_string(*i);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", std::get<double>(v));
    return buf;
}

}  // namespace

std::string AutoSetting::describe() const { return key + " " + value_text(value) + " (" + reason + ")"; }

const std::vector<AutoSettingRule>& auto_setting_rules() {
    // BDPT, IRRADIANCE_CACHE and SPPM have no entry: no measured feature argues for a setting other than their
    // defaults yet (docs/auto.md, "Settings", says what was considered).
    static const std::vector<AutoSettingRule> rules = {
        {"PATH", "light_selection", &path_light_selection},
    };
    return rules;
}

bool flickers_in_animation(const std::string& integrator) {
    for (const char* name : {"MLT", "MMLT", "IRRADIANCE_CACHE", "PHOTON", "SPPM"})
        if (integrator == name) return true;
    return false;
}

AutoChoice choose_integrator(const SceneFeatures& f, const std::function<bool(const std::string&)>& available) {
    const AutoRule* skipped = nullptr;  // the first rule animation ruled out
    for (const AutoRule& r : auto_rules()) {
        if (!r.applies(f) || !available(r.integrator)) continue;
        if (f.animation && flickers_in_animation(r.integrator)) {
            if (skipped == nullptr) skipped = &r;
            continue;
        }
        AutoChoice choice{r.integrator, r.name, r.reason(f), {}};
        for (const AutoSettingRule& s : auto_setting_rules())
            if (choice.integrator == s.integrator) choice.settings.push_back(s.choose(f));
        if (skipped != nullptr)
            choice.reason += std::string("; animation: not ") + skipped->integrator + " (rule " + skipped->name +
                             "), whose image would flicker from frame to frame";
        return choice;
    }
    throw InvalidParameter("AUTO: no rule of the policy chose an available integrator");  // PATH always exists
}

}  // namespace candela
