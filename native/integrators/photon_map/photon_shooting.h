// Pass 1 of the photon mappers (docs/photon-mapping.md, "Pass 1"): `paths` photon paths traced by PhotonTracer and
// the arrivals a map keeps stored as Photons, with progress ("Tracing photons 3.2 M / 10 M") and cancel.
//
// Determinism: path i is sample i of a Sobol' sampler keyed by (seed, stream), whatever batch or thread traces it;
// batches of k_photon_batch paths run in parallel and their photons are appended in batch order
// (core/parallel_ordered.h), so the photon array — and every map and estimate built from it — is the same for every
// thread count. The stochastic rounding of a photon's flux (photon.h) draws from a hash of (stream, path, arrival).
//
// Flux: a stored photon's flux is its path's β on arrival (a flux per emitted path); the map's flux_scale is the
// emitters' total power (photons of power-proportional emission carry about that much), and emitted_paths the
// number of paths, so a density estimate divides by it.
#pragma once

#include <cstdint>
#include <vector>

#include "integrators/photon_map/photon_map.h"
#include "integrators/photon_map/photon_tracer.h"
#include "integrators/render_context.h"

namespace candela {

inline constexpr int64_t k_photon_batch = 4096;

/// Which arrivals a map keeps.
enum class PhotonStore {
    Global,    // every arrival that is not a caustic one (PHOTON's global map)
    Caustic,   // caustic arrivals (L S⁺ D: PHOTON's caustic map, from the aimed emission)
    Indirect,  // every arrival after at least one scattering (SPPM: direct light is estimated at visible points)
};

struct PhotonShot {
    std::vector<Photon> photons;
    float flux_scale = 1.f;
    double emitted_paths = 0.0;
};

/// Traces photon paths [0, paths) of stream `stream` (PhotonPaths::CausticOnly for Caustic), keeping what `store`
/// says; the stage shows `stage_name` and counts paths. Throws Cancelled if ctx.cancel fires.
PhotonShot shoot_photons(const PhotonTracer& tracer, const EmitterSet& emitters, PhotonStore store, int64_t paths,
                         uint64_t seed, uint32_t stream, RenderContext& ctx, const char* stage_name);

/// A photon map built from a shot (stage "Building photon map"); throws Cancelled if ctx.cancel fires.
PhotonMap build_photon_map(PhotonShot shot, RenderContext& ctx, const char* stage_name);

}  // namespace candela
