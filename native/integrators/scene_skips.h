// What the scene does not need, decided once after it is built (docs/auto.md, "Skips"): each decision the
// integrators act on — no next-event estimation without lights, no environment importance map for a constant world,
// zero-power lights never selected, MIS left out for lights no ray can hit, shadow rays that stop at the first
// surface when nothing is Transparent, BDPT's s = 0 strategies when nothing a ray can hit emits — with the line the
// session logs for it. The integrators test the same conditions where they act (the code path named in each entry);
// this list is what makes the decisions visible, and what the tests count.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace candela {

struct SceneSkip {
    const char* id;    // as docs/auto.md's table names it
    std::string line;  // what is skipped and why, for the log line
};

/// The skips that apply to `scene` for `integrator` (a registry name), in a fixed order.
std::vector<SceneSkip> scene_skips(const std::string& integrator, const Scene& scene);

/// The one log line for `skips` ("" if none): "Skipped, the scene does not need them: …; …".
std::string scene_skips_line(const std::vector<SceneSkip>& skips);

/// Whether any emitter a ray can hit exists (area lights, emissive triangles, a world): without one, strategies that
/// end a camera path on an emitter (BDPT's s = 0, PATH's emission found by its rays) carry no energy.
bool has_hittable_emission(const Scene& scene);

}  // namespace candela
