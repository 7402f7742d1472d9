// The "PHOTON" (Jensen's photon map: photon_camera.h) and "SPPM" (sppm.h) integrators on the progressive driver.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_photon_integrator(const Params& params);
double photon_integrator_memory(const Params& params, double film_pixels);

std::unique_ptr<Integrator> make_sppm_integrator(const Params& params);
double sppm_integrator_memory(const Params& params, double film_pixels);

/// Bytes a stored photon takes in a built map, index included (photon.h, photon_map.h), and the photons a path
/// stores on average for the memory estimate (a diffuse interior of albedo ~0.6 stores ~2.5; 3 is the budget).
inline constexpr double k_photon_bytes = 23.0;
inline constexpr double k_stored_per_path = 3.0;

}  // namespace candela
