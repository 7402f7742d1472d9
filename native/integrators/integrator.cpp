#include "integrators/integrator.h"

#include "core/error.h"
#include "integrators/irradiance_cache/ic_integrator.h"
#include "integrators/irradiance_cache/ic_settings.h"
#include "integrators/path/path_integrator.h"
#include "integrators/path/path_settings.h"

namespace candela {

const std::vector<IntegratorEntry>& integrator_registry() {
    static const std::vector<IntegratorEntry> registry = {
        {"PATH", "Path Tracing", "Path tracing with next-event estimation and multiple importance sampling",
         &make_path_integrator, &PathSettings::specs},
        {"IRRADIANCE_CACHE", "Irradiance Cache",
         "Ward's irradiance cache with gradients: indirect diffuse light interpolated from path-traced records, "
         "direct light and glossy paths traced per sample (biased, consistent as the error a shrinks)",
         static_cast<std::unique_ptr<Integrator> (*)(const Params&)>(&make_ic_integrator), &IcSettings::specs,
         &ic_memory_bytes},
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
