// Settings of the photon mappers PHOTON (Jensen's two passes) and SPPM (stochastic progressive photon mapping),
// read once from params. Names are the add-on's identifiers; docs/photon-mapping.md, "Settings", explains each and
// its default. Photon counts and radii of 0 mean "automatic": they then scale with the image and the scene
// (resolve_*), so a bigger image gets more photons and a bigger scene a bigger radius.
#pragma once

#include <cstdint>
#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "integrators/common/lobe_classes.h"
#include "integrators/photon_map/density_kernel.h"
#include "integrators/pixel_sampling.h"

namespace candela {

struct PhotonSettings {
    PixelSampling pixel;          // samples: camera samples per pixel
    int max_bounces = 12;         // scatterings of photon and camera paths
    int64_t global_photons = 0;   // emitted photon paths for the global map; 0 = automatic
    int64_t caustic_photons = 0;  // emitted (aimed) photon paths for the caustic map; 0 = automatic
    int k = 50;                   // photons per density estimate
    float max_radius = 0.f;       // of a density estimate (scene units); 0 = automatic
    int final_gather_rays = 16;   // per camera sample at its first estimated vertex
    float gather_distance = 2.f;  // a gather hit closer than this × max_radius is path traced one bounce further
    DensityKernel kernel = DensityKernel::Cone;
    float traced_roughness = k_default_traced_roughness;

    static PhotonSettings from_params(const Params& params);
    static const std::vector<ParamSpec>& specs();

    /// The automatic counts: 4 photon paths per pixel of the frame, at least 200 000 (global); the same (caustic).
    int64_t resolve_global(double frame_pixels) const;
    int64_t resolve_caustic(double frame_pixels) const;
    /// The automatic radius: 2 % of the scene's bounding-sphere radius.
    float resolve_radius(float scene_radius) const { return max_radius > 0.f ? max_radius : 0.02f * scene_radius; }
    float alpha_threshold() const { return traced_roughness * traced_roughness; }
};

struct SppmSettings {
    PixelSampling pixel;  // samples: iterations
    int max_bounces = 12;
    int64_t photons_per_iteration = 0;  // 0 = automatic: one per pixel of the frame, at least 100 000
    float initial_radius = 0.f;         // 0 = automatic: 1 % of the scene's bounding-sphere radius
    float alpha = 2.f / 3.f;            // radius reduction (Hachisuka & Jensen 2009)
    float traced_roughness = 0.f;       // only delta lobes traced: glossy ones are estimated and converge too

    static SppmSettings from_params(const Params& params);
    static const std::vector<ParamSpec>& specs();
    int64_t resolve_photons(double frame_pixels) const;
    float resolve_radius(float scene_radius) const {
        return initial_radius > 0.f ? initial_radius : 0.01f * scene_radius;
    }
    float alpha_threshold() const { return traced_roughness * traced_roughness; }
};

}  // namespace candela
