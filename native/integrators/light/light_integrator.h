// The "LIGHT" integrator: light tracing (light_tracer.h) on the progressive driver.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_light_integrator(const Params& params);
double light_integrator_memory(const Params& params, double film_pixels);

}  // namespace candela
