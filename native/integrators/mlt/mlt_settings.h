// Settings of the Metropolis integrators MLT and MMLT (plain struct, read once from params). Names are the add-on's.
// The common `samples` is the budget: Metropolis mutations per pixel of the full frame.
#pragma once

#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/bdpt/bdpt_settings.h"

namespace candela {

struct MltSettings {
    BdptSettings bdpt;        // the bidirectional sampler the chains drive (no Russian roulette: see from_params)
    float large_step = 0.3f;  // p_large: probability of an independent proposal
    float sigma = 0.01f;      // the small step's standard deviation per primary coordinate
    int bootstrap = 100000;   // independent paths estimating b (MMLT: per path depth)
    int chains = 1000;        // Markov chains (even: two independent populations for the noise estimate)

    /// `multiplexed`: MMLT's settings (the same keys; MMLT's bootstrap is per depth).
    static MltSettings from_params(const Params& params, bool multiplexed);
    static const std::vector<ParamSpec>& specs();
};

}  // namespace candela
