// AUTO's policy: which integrator a scene's static features call for, as one ordered table of rules (predicate →
// integrator + one-line reason) in auto_policy.cpp; the first rule whose predicate holds and whose integrator the
// build has wins, so the table names integrators that do not exist yet (SPPM, IRRADIANCE_CACHE) and keeps working
// when they arrive. A second table in the same file sets the chosen integrator's main settings from the features
// (AutoSettingRule: one entry per integrator and param, each with its reason). Each rule's evidence is in
// docs/auto.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/params.h"
#include "integrators/auto/scene_features.h"

namespace candela {

struct AutoRule {
    const char* name;        // the rule's id, as docs/auto.md's table lists it
    const char* integrator;  // a registry name
    bool (*applies)(const SceneFeatures&);
    std::string (*reason)(const SceneFeatures&);  // the one-line reason, with the figures that decided
};

/// The table, first match wins; its last rule always applies (PATH).
const std::vector<AutoRule>& auto_rules();

/// One main setting of the chosen integrator, chosen from the features: its param, value and the one-line reason.
struct AutoSetting {
    std::string key;
    Params::Value value;
    std::string reason;
    /// "key VALUE (reason)", as the log and the status line show it.
    std::string describe() const;
};

struct AutoSettingRule {
    const char* integrator;  // a registry name
    const char* key;         // the param it sets
    /// The setting and its reason for these features (always one: a rule that has nothing to go on is not listed).
    AutoSetting (*choose)(const SceneFeatures&);
};

/// The settings table (docs/auto.md, "Settings"), every entry of the chosen integrator applies.
const std::vector<AutoSettingRule>& auto_setting_rules();

struct AutoChoice {
    std::string integrator;
    std::string rule;
    std::string reason;
    std::vector<AutoSetting> settings;  // the chosen integrator's main settings (auto_setting_rules)
};

/// Integrators whose image flickers in an animation beyond its pixel noise: caches whose records or photons are
/// placed anew each frame (IRRADIANCE_CACHE, PHOTON, SPPM: low-frequency blotches that move) and Metropolis samplers
/// (MLT, MMLT: start-up bias and correlated, unevenly converged noise that changes from frame to frame).
bool flickers_in_animation(const std::string& integrator);

/// The first rule that applies to `f` and whose integrator `available(name)` says exists; in an animation
/// (f.animation) not one that flickers_in_animation, and the reason then names the rule it passed over.
AutoChoice choose_integrator(const SceneFeatures& f, const std::function<bool(const std::string&)>& available);

}  // namespace candela
