#include "integrators/camera_hit.h"

#include "core/frame.h"

namespace candela {

bool record_camera_hit(const Scene& scene, const Ray& ray, const SurfaceHit& hit, AovSample* aov, float* alpha) {
    if (aov) {
        const Camera& camera = scene.camera();
        const Vec3 wo = -ray.d;
        // Cycles flips the normals of a surface seen from behind toward the viewer.
        const bool backfacing = dot(wo, hit.ng) < 0.f;
        const Vec3 n = backfacing ? -hit.ns : hit.ns;
        aov->hit = true;
        aov->depth = dot(hit.p - camera.position(), camera.forward());
        aov->normal = n;
        aov->albedo = scene.materials()[hit.material].bsdf(backfacing).albedo(Frame(n).to_local(wo));
        aov->object_index = float(scene.pass_index(hit));
    }
    const float w = scene.holdout(hit);
    if (w > 0.f) {
        *alpha = w >= 1.f ? 0.f : 1.f - w;
        if (w >= 1.f) return false;
    }
    return true;
}

}  // namespace candela
