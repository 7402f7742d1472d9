// Lights: a closed family of value types behind std::variant, and the set of all lights of a scene with
// the probabilities with which next-event estimation picks them.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "lights/area_light.h"
#include "lights/point_light.h"
#include "lights/sun_light.h"
#include "lights/triangle_light.h"
#include "lights/world_light.h"
#include "sampling/distribution_1d.h"

namespace candela {

class SceneArrays;

using Light = std::variant<PointLight, SunLight, AreaLight, TriangleLight, WorldLight>;

inline LightSample light_sample_li(const Light& l, const LightSampleContext& ctx, Vec2 u) {
    return std::visit([&](const auto& x) { return x.sample_li(ctx, u); }, l);
}
inline float light_power(const Light& l) { return std::visit([](const auto& x) { return x.power(); }, l); }

/// Column names of the `lights` array and names of `light_type` values (Blender's light types).
const std::vector<std::string>& light_columns();
const std::vector<std::string>& light_type_names();

/// Converts Blender lights (Blender's quantities, Cycles 3.4 units) to Candela lights; positions are
/// moved by `offset` (camera-world space). Zero-strength lights are dropped.
std::vector<Light> load_blender_lights(const SceneArrays& arrays, const Vec3& offset);

class LightSet {
public:
    /// Adds a light; returns its index.
    uint32_t add(Light light);
    /// Builds the selection distribution (∝ power) once every light is added.
    void finalize(float scene_radius);

    size_t size() const { return m_lights.size(); }
    bool empty() const { return m_lights.empty(); }
    const Light& operator[](size_t i) const { return m_lights[i]; }

    /// Picks one light ∝ power: returns its index and probability.
    uint32_t select(float u, float* pmf) const {
        return static_cast<uint32_t>(m_selection.sample_discrete(u, pmf));
    }
    float selection_pmf(uint32_t i) const { return m_selection.pmf(i); }

    const std::vector<uint32_t>& area_lights() const { return m_area_lights; }
    int world_light() const { return m_world; }
    const WorldLight* world() const {
        return m_world < 0 ? nullptr : &std::get<WorldLight>(m_lights[m_world]);
    }

private:
    std::vector<Light> m_lights;
    std::vector<uint32_t> m_area_lights;
    int m_world = -1;
    Distribution1D m_selection;
};

}  // namespace candela
