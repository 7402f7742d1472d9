#include "integrators/mlt/mlt_settings.h"

#include <string>

#include "core/error.h"
#include "integrators/common/path_specs.h"

namespace candela {

const std::vector<ParamSpec>& MltSettings::specs() {
    static const std::vector<ParamSpec> specs = {
        max_bounces_spec(),
        BdptSettings::mis_spec(),
        float_param("mlt_large_step", "Large Step Probability", 0.3, 0.0, 1.0,
                    "Probability that a mutation proposes an independent path (1: plain Monte Carlo)", "Metropolis"),
        float_param("mlt_sigma", "Small Step Size", 0.01, 1e-5, 1.0,
                    "Standard deviation of a small step of each primary sample (Kelemen et al. 2002)", "Metropolis"),
        int_param("mlt_bootstrap", "Bootstrap Paths", 100000, 1, 100000000,
                  "Independent paths that estimate the image brightness b and seed the chains (multiplexed: per path "
                  "length)",
                  "Metropolis"),
        int_param("mlt_chains", "Chains", 1000, 2, 1000000,
                  "Markov chains; the two halves are independent populations for the noise estimate", "Metropolis"),
    };
    return specs;
}

MltSettings MltSettings::from_params(const Params& params, bool multiplexed) {
    const ParamReader read(params, specs());
    MltSettings s;
    s.bdpt.pixel = PixelSampling::from_params(params);
    s.bdpt.max_bounces = read.get_int("max_bounces");
    // The chain's target is a fixed function of the primary samples; roulette would only add variance to it (the
    // paths end at Max Bounces, as in pbrt's and Mitsuba's MLT).
    s.bdpt.rr_mode = RouletteMode::Off;
    s.bdpt.heuristic = read.get_enum("bdpt_mis") == "BALANCE" ? MisHeuristic::Balance : MisHeuristic::Power;
    s.large_step = read.get_float("mlt_large_step");
    s.sigma = read.get_float("mlt_sigma");
    s.bootstrap = read.get_int("mlt_bootstrap");
    s.chains = read.get_int("mlt_chains");
    const char* name = multiplexed ? "MMLT" : "MLT";
    if (s.chains % 2 != 0)
        throw InvalidParameter(std::string("integrator ") + name + ": parameter 'mlt_chains' (Chains) = " +
                               std::to_string(s.chains) + " must be even (two independent chain populations)");
    return s;
}

}  // namespace candela
