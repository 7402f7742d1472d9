// The Metropolis integrators: "MLT", primary-sample-space MLT over the bidirectional path tracer (Kelemen et al.
// 2002), and "MMLT", multiplexed MLT (Hachisuka et al. 2014). Both: two chain populations, each with its own bootstrap
// of independent paths that estimates the image brightness b and seeds its chains by stratified resampling ∝ I
// (bootstrap.h); the chains (markov_chain.h) render a fixed number of mutations per pass each, merged in chain order,
// so the image is the same for any thread count. docs/metropolis.md.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_mlt_integrator(const Params& params);
std::unique_ptr<Integrator> make_mmlt_integrator(const Params& params);
double mlt_integrator_memory(const Params& params, double film_pixels);

/// What the bootstrap found (for tests and the log): b, and per depth b_k (MMLT; PSSMLT: one entry), each the mean
/// of the two chain populations' independent estimates (bootstrap.h), and each population's b.
struct MltBootstrap {
    double b = 0.0;
    std::vector<double> b_depth;
    std::vector<double> b_population;
};
/// The bootstrap alone (no chains): b from `params` (integrator MLT or MMLT) on `scene`.
MltBootstrap mlt_bootstrap(const Scene& scene, const Params& params, int threads);

}  // namespace candela
