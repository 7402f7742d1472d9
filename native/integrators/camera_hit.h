// What happens at the first surface a camera ray sees, besides shading (Cycles 3.4: film_write_data_passes and
// integrate_surface_holdout): the data passes (Depth, Normal, Albedo, IndexOB) are recorded, and a holdout takes
// its weight out of alpha — alpha = 1 − w, the surface's remaining closures (weight 1 − w) shade as usual, and a
// full holdout (a holdout object, or a material that is all Holdout) ends the path with no radiance. Cycles does
// this whether or not the film is transparent. The data passes are recorded before the holdout, so a holdout
// object still has its depth and index for compositing.
#pragma once

#include "film/aov_film.h"
#include "scene/scene.h"

namespace candela {

/// Records `aov` (if given) and applies holdout to *alpha; false when the path ends here.
bool record_camera_hit(const Scene& scene, const Ray& ray, const SurfaceHit& hit, AovSample* aov, float* alpha);

/// The integrators' hook: free when no data pass is written and the scene has no holdout.
inline bool camera_hit(const Scene& scene, const Ray& ray, const SurfaceHit& hit, AovSample* aov, float* alpha) {
    if (!aov && !scene.has_holdouts()) return true;
    return record_camera_hit(scene, ray, hit, aov, alpha);
}

}  // namespace candela
