// The course's indirect path generators as integrators (generator_tracer.h): SURFACE_SAMPLING, SOURCE_SHOOTING and
// RECEIVER_GATHERING.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_surface_sampling_integrator(const Params& params);
std::unique_ptr<Integrator> make_source_shooting_integrator(const Params& params);
std::unique_ptr<Integrator> make_receiver_gathering_integrator(const Params& params);

}  // namespace candela
