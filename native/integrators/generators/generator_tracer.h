// The course's indirect path generators (CS680, "Indirect paths"; Dutré, Bekaert & Bala, "Advanced Global
// Illumination", §5.4): estimators of the pixel integral of the measurement equation that differ only in how they
// find the indirect light at a visible point. A camera path is followed through delta (specular) scattering by ray
// tracing; every vertex it reaches that scatters non-delta is a *receiver* x, whose reflected light toward the
// camera is split by the first scattering after x:
//     L_r(x) = D(x)             direct light (y → x): next-event estimation with MIS against the BSDF ray
//                               (integrators/common/direct_light.h, the path tracer's rule)
//            + S(x)             x scatters by a delta lobe, or its BSDF ray's hit z scatters by one: the delta chain
//                               is ray traced and the next non-delta vertex is a receiver again
//            + I(x)             x and the next vertex z both scatter non-delta: the generator's job —
//   SURFACE_SAMPLING    z uniform over all surfaces by area; L_r(z → x) by a light point (light-only next-event
//                       estimation) and, for longer paths, a further surface point — two visibility checks per
//                       bounce:  I = f_x · G(x, z) · V(x, z) · L_r(z → x) / p_A(z);
//   SOURCE_SHOOTING     a light path (emission ∝ power, continued by light-side BSDF sampling; common/light_walk.h)
//                       whose non-delta vertices z_k are each connected to x:  I = Σ_k β_k · f_z · f_x · G · V;
//   RECEIVER_GATHERING  x's BSDF ray finds z, whose light is a light point's (light-only next-event estimation),
//                       continued by BSDF sampling for longer paths (a path tracer without MIS beyond x).
// With generators_mis, the one-bounce term (y → z → x) is estimated by all three and weighted by multiple importance
// sampling (one_bounce.h); longer paths stay the chosen generator's. Path lengths are the path tracer's (at most
// max_bounces + 1 scattering vertices), so all four estimate the same image.
#pragma once

#include "film/aov_film.h"
#include "integrators/generators/generator_settings.h"
#include "integrators/generators/one_bounce.h"
#include "integrators/render_context.h"
#include "lights/emitter_set.h"
#include "lights/light_sampler.h"
#include "sampling/sampler.h"
#include "scene/scene.h"
#include "scene/surface_sampler.h"

namespace candela {

class GeneratorTracer {
public:
    /// `surfaces` is needed for SURFACE_SAMPLING and generators_mis (else it may be null).
    GeneratorTracer(const Scene& scene, const GeneratorSettings& settings, const LightSampler& light_sampler,
                    const EmitterSet& emitters, const SurfaceSampler* surfaces);

    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov) const;

private:
    friend class GeneratorPath;

    const Scene& m_scene;
    const GeneratorSettings& m_settings;
    const LightSampler& m_light_sampler;
    const EmitterSet& m_emitters;
    const SurfaceSampler* m_surfaces;
    OneBounceWeights m_weights;
    DirectLightRules m_light_only;      // next-event estimation at gathered points
    bool m_any_delta = false;           // some material has a delta lobe: delta chains can start anywhere
    bool m_unsampled_emission = false;  // a constant world: emission next-event estimation does not sample
    int m_source_slot = 0;              // the light path's first sample slot (source shooting)
};

}  // namespace candela
