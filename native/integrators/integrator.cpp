#include "integrators/integrator.h"

#include "core/error.h"
#include "integrators/auto/auto_integrator.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/bdpt_settings.h"
#include "integrators/generators/generator_integrator.h"
#include "integrators/generators/generator_settings.h"
#include "integrators/irradiance_cache/ic_integrator.h"
#include "integrators/irradiance_cache/ic_settings.h"
#include "integrators/light/light_integrator.h"
#include "integrators/light/light_settings.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/mlt/mlt_settings.h"
#include "integrators/path/path_integrator.h"
#include "integrators/path/path_settings.h"
#include "integrators/photon_map/photon_integrator.h"
#include "integrators/photon_map/photon_settings.h"

namespace candela {

const std::vector<IntegratorEntry>& integrator_registry() {
    static const std::vector<IntegratorEntry> registry = {
        {"PATH", "Path Tracing", "Path tracing with next-event estimation and multiple importance sampling",
         &make_path_integrator, &PathSettings::specs, nullptr, /*viewport=*/true},
        {"LIGHT", "Light Tracing",
         "Particle tracing from the lights, every vertex connected to the camera (emitters seen directly or through "
         "mirrors and glass by a camera pass; surfaces seen only through them stay dark: use BDPT)",
         &make_light_integrator, &LightSettings::specs, &light_integrator_memory, /*viewport=*/true,
         /*needs_camera_connection=*/true, /*panoramic=*/false},
        {"BDPT", "Bidirectional",
         "Bidirectional path tracing: camera and light subpaths joined by every (s, t) strategy, weighted by multiple "
         "importance sampling (Veach 1997, ch. 10)",
         &make_bdpt_integrator, &BdptSettings::specs, &bdpt_integrator_memory, /*viewport=*/true,
         /*needs_camera_connection=*/false, /*panoramic=*/false},
        {"SURFACE_SAMPLING", "Surface Sampling",
         "The course's surface-sampling generator: indirect light from a point on a light and a point on any surface, "
         "joined by two visibility checks (direct light by next-event estimation, mirrors and glass by ray tracing)",
         &make_surface_sampling_integrator, &GeneratorSettings::specs, nullptr, /*viewport=*/true},
        {"SOURCE_SHOOTING", "Source Shooting",
         "The course's source-shooting generator: indirect light from a ray shot from a light, its hits connected to "
         "the visible point (direct light by next-event estimation, mirrors and glass by ray tracing)",
         &make_source_shooting_integrator, &GeneratorSettings::specs, nullptr, /*viewport=*/true},
        {"RECEIVER_GATHERING", "Receiver Gathering",
         "The course's receiver-gathering generator: indirect light from a ray shot from the visible point, its hit "
         "connected to a point on a light (direct light by next-event estimation, mirrors and glass by ray tracing)",
         &make_receiver_gathering_integrator, &GeneratorSettings::specs, nullptr, /*viewport=*/true},
        {"MLT", "Metropolis",
         "Primary-sample-space Metropolis light transport over the bidirectional path tracer (Kelemen et al. 2002): "
         "chains of mutated paths, for light that is hard to find; Samples are mutations per pixel",
         &make_mlt_integrator, &MltSettings::specs, &mlt_integrator_memory, /*viewport=*/false,
         /*needs_camera_connection=*/false, /*panoramic=*/false},
        {"MMLT", "Multiplexed Metropolis",
         "Multiplexed Metropolis light transport (Hachisuka et al. 2014): chains over path length and one "
         "bidirectional strategy chosen per mutation; Samples are mutations per pixel",
         &make_mmlt_integrator, &MltSettings::specs, &mlt_integrator_memory, /*viewport=*/false,
         /*needs_camera_connection=*/false, /*panoramic=*/false},
        {"IRRADIANCE_CACHE", "Irradiance Cache",
         "Ward's irradiance cache with gradients: indirect diffuse light interpolated from path-traced records, "
         "direct light and glossy paths traced per sample (biased, consistent as the error a shrinks)",
         static_cast<std::unique_ptr<Integrator> (*)(const Params&)>(&make_ic_integrator), &IcSettings::specs,
         &ic_memory_bytes},
        {"PHOTON", "Photon Mapping",
         "Jensen's photon map: photons shot from the lights into a global and a caustic map; direct light by light "
         "sampling, mirrors and glass by ray tracing, caustics from the caustic map, indirect light by final "
         "gathering (biased, consistent as photons grow)",
         &make_photon_integrator, &PhotonSettings::specs, &photon_integrator_memory},
        {"SPPM", "Progressive Photon Mapping",
         "Stochastic progressive photon mapping (Hachisuka & Jensen 2009): camera visible points and a photon pass "
         "per iteration with shrinking radii; consistent, converges to the path tracer's image",
         &make_sppm_integrator, &SppmSettings::specs, &sppm_integrator_memory},
        {"AUTO", "Automatic",
         "Analyses the scene and renders with the integrator its effects call for (the choice and its reason in the "
         "status line and the log; the chosen integrator's own settings at their defaults)",
         &make_auto_integrator, &auto_param_specs},
    };
    return registry;
}

const IntegratorEntry& find_integrator(const std::string& name) {
    std::string names;
    for (const auto& e : integrator_registry()) {
        if (name == e.name) return e;
        names += (names.empty() ? "" : ", ") + std::string(e.name);
    }
    throw InvalidParameter("unknown integrator '" + name + "' (available: " + names + ")");
}

std::unique_ptr<Integrator> make_integrator(const Params& params) {
    return find_integrator(params.get<std::string>("integrator", "PATH")).create(params);
}

}  // namespace candela
