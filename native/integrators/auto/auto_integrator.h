// The "AUTO" integrator: analyses the built scene (scene_features.h), chooses an integrator by the policy table
// (auto_policy.h), logs the features and the decision, names its choice and reason in the status line
// (RenderCounters::method) and renders with the chosen integrator built from the same params (its own settings at
// their defaults: the add-on sends AUTO only the common settings). Its image is the chosen integrator's, bit for
// bit, for the same seed. docs/auto.md.
#pragma once

#include <memory>
#include <vector>

#include "core/param_spec.h"
#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_auto_integrator(const Params& params);
/// AUTO's own settings: none yet (the chosen integrator's are its defaults).
const std::vector<ParamSpec>& auto_param_specs();

}  // namespace candela
