// The "PATH" integrator: progressive tile rendering with one PathTracer.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace candela {

std::unique_ptr<Integrator> make_path_integrator(const Params& params);

}  // namespace candela
