#include "integrators/integrator.h"

#include "core/error.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/bdpt/bdpt_settings.h"
#include "integrators/light/light_integrator.h"
#include "integrators/light/light_settings.h"
#include "integrators/path/path_integrator.h"
#include "integrators/path/path_settings.h"

namespace candela {

const std::vector<IntegratorEntry>& integrator_registry() {
    static const std::vector<IntegratorEntry> registry = {
        {"PATH", "Path Tracing", "Path tracing with next-event estimation and multiple importance sampling",
         &make_path_integrator, &PathSettings::specs},
        {"LIGHT", "Light Tracing",
         "Particle tracing from the lights, every vertex connected to the camera (emitters seen directly or through "
         "mirrors and glass by a camera pass; surfaces seen only through them stay dark: use BDPT)",
         &make_light_integrator, &LightSettings::specs, &light_integrator_memory},
        {"BDPT", "Bidirectional",
         "Bidirectional path tracing: camera and light subpaths joined by every (s, t) strategy, weighted by multiple "
         "importance sampling (Veach 1997, ch. 10)",
         &make_bdpt_integrator, &BdptSettings::specs, &bdpt_integrator_memory},
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
