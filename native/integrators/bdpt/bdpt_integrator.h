// The "BDPT" integrator: bidirectional path tracing (bdpt_tracer.h) on the camera tile loop, its t = 1 splats merged
// in tile order.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_bdpt_integrator(const Params& params);
double bdpt_integrator_memory(const Params& params, double film_pixels);

}  // namespace candela
