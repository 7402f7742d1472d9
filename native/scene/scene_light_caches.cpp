// What the scene derives from its lights for the integrators and keeps (Scene::light_sampler, Scene::emitters):
// the light-selection strategies and the emitter set. They depend on the lights and the bounds only, which a
// camera change (Scene::set_camera) leaves alone, so the 3D viewport builds them once per scene instead of once
// per view change and coarse level. Each is built on first use by whichever render thread asks first
// (std::call_once), exactly as the integrator would have built it, so the images are the same.
#include "scene/scene.h"

namespace candela {

const LightSampler& Scene::light_sampler(LightSelection kind) const {
    const size_t k = size_t(kind);
    std::call_once(m_light_sampler_once[k],
                   [&] { m_light_samplers[k] = std::make_unique<LightSampler>(make_light_sampler(kind, m_lights)); });
    return *m_light_samplers[k];
}

const EmitterSet& Scene::emitters() const {
    std::call_once(m_emitters_once, [&] { m_emitter_set = std::make_unique<EmitterSet>(m_lights, m_bounds); });
    return *m_emitter_set;
}

}  // namespace candela
