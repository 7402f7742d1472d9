// The integrator interface and its registry. Registry names are the add-on's `integrator` enum
// identifiers; unknown names throw InvalidParameter listing the valid ones.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/params.h"
#include "film/film.h"
#include "integrators/render_context.h"
#include "scene/scene.h"

namespace candela {

class Integrator {
public:
    virtual ~Integrator() = default;
    /// Renders into the film until done or cancelled (returns normally on cancel, keeping the partial
    /// image). Must not depend on thread count or scheduling for a given seed.
    virtual void render(const Scene& scene, Film& film, RenderContext& ctx) = 0;
    /// Samples per pixel the render will take (for progress).
    virtual int samples_per_pixel() const = 0;
};

struct IntegratorEntry {
    const char* name;
    const char* description;
    std::unique_ptr<Integrator> (*create)(const Params&);
};

const std::vector<IntegratorEntry>& integrator_registry();
std::unique_ptr<Integrator> make_integrator(const Params& params);

}  // namespace candela
