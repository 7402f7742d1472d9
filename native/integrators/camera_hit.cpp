#include "integrators/camera_hit.h"

#include <type_traits>

#include "core/frame.h"

namespace candela {

namespace {

/// Cycles' albedo of a closure list (the denoising albedo of kernel/film/denoising_passes.h): the sum of the
/// closures' colour weights, a Fresnel-tinted microfacet lobe (Principled specular, clearcoat) times its
/// Fresnel colour at wo, and Transparent closures left out (they show what lies behind). Candela records it
/// at the first surface even when that surface is partly transparent.
Color closure_albedo(const Bsdf& bsdf, const Vec3& wo_local) {
    Color sum(0.f);
    for (int i = 0; i < bsdf.size(); ++i) {
        const WeightedLobe& wl = bsdf[i];
        sum += std::visit(
            [&](const auto& lobe) -> Color {
                using T = std::decay_t<decltype(lobe)>;
                if constexpr (std::is_same_v<T, TransparentBsdf>)
                    return Color(0.f);
                else if constexpr (std::is_same_v<T, MicrofacetReflection>)
                    return wl.weight * lobe.fresnel.eval(wo_local.z);
                else if constexpr (std::is_same_v<T, ClearcoatBsdf>)
                    return wl.weight * lobe.albedo(wo_local);
                else
                    return wl.weight;
            },
            wl.lobe);
    }
    return sum;
}

}  // namespace

bool record_camera_hit(const Scene& scene, const Ray& ray, const SurfaceHit& hit, AovSample* aov, float* alpha) {
    if (aov) {
        const Camera& camera = scene.camera();
        const Vec3 wo = -ray.d;
        // The material as the path tracer sees it here: textures and the Normal Map evaluated at the hit.
        const ShadingPoint sp = scene.shade(hit, wo);
        // Cycles writes the closures' shading normal (after any Normal Map), flipped toward the viewer on a
        // surface seen from behind.
        const Vec3 n = sp.backfacing ? -sp.ns : sp.ns;
        aov->hit = true;
        aov->depth = dot(hit.p - camera.position(), camera.forward());
        aov->normal = n;
        aov->albedo = closure_albedo(sp.bsdf(), Frame(n).to_local(wo));
        aov->object_index = float(scene.pass_index(hit));
    }
    const float w = scene.holdout(hit, -ray.d);
    if (w > 0.f) {
        *alpha = w >= 1.f ? 0.f : 1.f - w;
        if (w >= 1.f) return false;
    }
    return true;
}

}  // namespace candela
