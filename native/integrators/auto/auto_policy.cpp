// The policy table (docs/auto.md, "Policy"). Thresholds marked "guess" there are not tuned by measurement yet.
#include "integrators/auto/auto_policy.h"

#include <cstdio>

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
// The pilot's thresholds (docs/auto.md, "Pilot"): guesses, to be tuned by the acceptance measurement.
constexpr double k_caustic_variance_share = 0.5;  // measured caustic variance share that calls for BDPT

bool measured_caustics(const SceneFeatures& f) {
    return f.pilot_measured && f.pilot.variance_share(PathClass::Caustic) >= k_caustic_variance_share;
}
bool caustics(const SceneFeatures& f) { return f.caustic_paths; }
bool specular_large_lights(const SceneFeatures& f) { return f.specular_area > 0.0 && !f.caustic_paths; }
bool always(const SceneFeatures&) { return true; }

std::string caustic_reason(const SceneFeatures& f) {
    return "caustic paths (L S+ D): delta surfaces " + percent(f.area_share(f.specular_area)) + " of the area, " +
           percent(f.unhittable_power_share() + f.small_power_share()) +
           " of the light power from lights a path tracer cannot hit or rarely hits";
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
        {"default", "PATH", &always,
         [](const SceneFeatures&) -> std::string {
             return "diffuse and glossy surfaces, no caustic paths: path tracing with light sampling";
         }},
    };
    return rules;
}

AutoChoice choose_integrator(const SceneFeatures& f, const std::function<bool(const std::string&)>& available) {
    for (const AutoRule& r : auto_rules())
        if (r.applies(f) && available(r.integrator)) return {r.integrator, r.name, r.reason(f)};
    throw InvalidParameter("AUTO: no rule of the policy chose an available integrator");  // PATH always exists
}

}  // namespace candela
