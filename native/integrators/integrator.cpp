#include "integrators/integrator.h"

#include "core/error.h"
#include "integrators/path/path_integrator.h"

namespace candela {

const std::vector<IntegratorEntry>& integrator_registry() {
    static const std::vector<IntegratorEntry> registry = {
        {"PATH", "Path tracing with next-event estimation and multiple importance sampling", &make_path_integrator},
    };
    return registry;
}

std::unique_ptr<Integrator> make_integrator(const Params& params) {
    const std::string name = params.get<std::string>("integrator", "PATH");
    std::string names;
    for (const auto& e : integrator_registry()) {
        if (name == e.name) return e.create(params);
        names += (names.empty() ? "" : ", ") + std::string(e.name);
    }
    throw InvalidParameter("unknown integrator '" + name + "' (available: " + names + ")");
}

}  // namespace candela
