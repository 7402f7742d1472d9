// The "IRRADIANCE_CACHE" integrator (docs/irradiance_cache.md): Ward's irradiance cache with gradients, built by a
// pre-pass over a coarse-to-fine pixel grid and completed while rendering, each pass reading a frozen cache and
// merging its new records in a fixed order.
#pragma once

#include <memory>

#include "integrators/integrator.h"
#include "integrators/irradiance_cache/ic_tracer.h"

namespace candela {

std::unique_ptr<Integrator> make_ic_integrator(const Params& params);
/// The same with a test hook (IcProbe, called before every gather ray; it must outlive the integrator).
std::unique_ptr<Integrator> make_ic_integrator(const Params& params, const IcProbe* probe);
/// The memory the records may take for a film of `film_pixels` (the cache's capacity: IcSettings in params).
double ic_memory_bytes(const Params& params, double film_pixels);
/// Records the cache keeps at most for a film of `film_pixels`: one per min_spacing² pixels (min_spacing at least
/// half a pixel), plus 4096.
size_t ic_record_capacity(const IcSettings& settings, double film_pixels);
/// The pre-pass's sub-pass (0 … 3) of full-frame pixel (fx, fy) at grid stride s (coarsest: `top`, a power of two),
/// or −1 if the pixel is not a point first visited at that stride (docs/irradiance_cache.md, "Record placement").
int ic_prepass_sub_pass(int fx, int fy, int s, int top);

}  // namespace candela
