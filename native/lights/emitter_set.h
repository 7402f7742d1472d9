// Everything that emits, for light-rooted integrators: the scene's lights and — where the world is a constant
// colour, which next-event estimation does not sample (LightSet::set_background) — that colour as a world light
// too, each chosen in proportion to the flux it emits (light_emitted_power: the spot's true cone integral, the
// world through the scene's bounding disk). Lights of zero power are never chosen. A textured emitter's power is
// estimated at 16 points with a floor, so a triangle whose emission averages zero at a few points still emits
// where it is bright (the choice stays unbiased: every emitter that can emit has a positive probability).
// Emitter i < lights.size() is LightSet light i; the constant world, if any, comes last.
#pragma once

#include <cstdint>
#include <optional>

#include "lights/light.h"
#include "lights/light_emission.h"
#include "sampling/distribution_1d.h"

namespace candela {

class EmitterSet {
public:
    EmitterSet(const LightSet& lights, const SceneSphere& bounds);

    size_t size() const { return m_lights->size() + (m_background ? 1 : 0); }
    bool empty() const { return size() == 0 || !(m_power.integral() > 0.f); }
    const Light& operator[](size_t i) const { return i < m_lights->size() ? (*m_lights)[i] : *m_background; }
    const SceneSphere& bounds() const { return m_bounds; }

    /// The emitter index of the world (an environment or the constant colour), or −1.
    int world() const { return m_world; }

    /// Picks an emitter ∝ emitted power: its index and probability.
    uint32_t select(float u, float* pmf) const { return uint32_t(m_power.sample_discrete(u, pmf)); }
    float pmf(uint32_t i) const { return i < m_power.size() ? m_power.pmf(i) : 0.f; }
    /// The emitted power the choice is proportional to (luminance).
    float power(uint32_t i) const { return i < m_weights.size() ? m_weights[i] : 0.f; }

    /// An emitted ray: the emitter chosen by u_select, then light_sample_le.
    EmissionSample sample_le(float u_select, Vec2 u_pos, Vec2 u_dir, float u_side, uint32_t* index, float* pmf) const;

private:
    const LightSet* m_lights;
    std::optional<Light> m_background;
    SceneSphere m_bounds;
    int m_world = -1;
    std::vector<float> m_weights;
    Distribution1D m_power;
};

}  // namespace candela
