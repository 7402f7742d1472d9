// Lights: a closed family of value types behind std::variant, and the set of all lights of a scene with
// the probabilities with which next-event estimation picks them.
#pragma once

#include <string>
#include <type_traits>
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
/// Samples light `l` from ctx with the `light_pdf` mode (only emissive triangles and area lights depend on it).
/// `mis_compensated`: an environment samples its MIS-compensated map (next-event estimation combined with BSDF
/// sampling by MIS: lights/environment_bake.h); every other light ignores it.
inline LightSample light_sample_li(const Light& l, const LightSampleContext& ctx, Vec2 u, LightPdfMode mode,
                                   bool mis_compensated = false) {
    return std::visit(
        [&](const auto& x) -> LightSample {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, AreaLight> || std::is_same_v<T, TriangleLight>)
                return x.sample_li(ctx, u, mode);
            else if constexpr (std::is_same_v<T, WorldLight>)
                return x.sample_li(ctx, u, mis_compensated);
            else
                return x.sample_li(ctx, u);
        },
        l);
}
/// Solid-angle density with which light_sample_li(l, ctx, ·, mode) produces direction wi reaching the light at
/// distance t (for MIS on BSDF-sampled hits). 0 for lights BSDF rays never hit (point, spot, sun).
inline float light_pdf_li(const Light& l, const LightSampleContext& ctx, const Vec3& wi, float t, LightPdfMode mode,
                          bool mis_compensated = false) {
    return std::visit(
        [&](const auto& x) -> float {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, AreaLight> || std::is_same_v<T, TriangleLight>)
                return x.pdf_li(ctx, wi, t, mode);
            else if constexpr (std::is_same_v<T, WorldLight>)
                return x.pdf_li(wi, mis_compensated);
            else
                return 0.f;
        },
        l);
}
/// Emitting area (world units): area lights and triangles; a point light with radius r its disk πr²; 0 for
/// point, spot, sun and world (the AREA selection strategy substitutes a stand-in for those).
inline float light_area(const Light& l) {
    return std::visit(
        [](const auto& x) -> float {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, AreaLight> || std::is_same_v<T, TriangleLight>)
                return x.area;
            else
                return 0.f;
        },
        l);
}
inline float light_power(const Light& l) {
    return std::visit([](const auto& x) { return x.power(); }, l);
}

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

    /// The `light_pdf` mode of sample_li()/pdf_li() below (default SOLID_ANGLE). The mode-less
    /// light_sample_li(light, ctx, u) and Light::pdf_li(d, t) stay AREA.
    void set_pdf_mode(LightPdfMode mode) { m_pdf_mode = mode; }
    LightPdfMode pdf_mode() const { return m_pdf_mode; }
    LightSample sample_li(uint32_t i, const LightSampleContext& ctx, Vec2 u) const {
        return light_sample_li(m_lights[i], ctx, u, m_pdf_mode);
    }
    /// MIS density for a BSDF ray from ctx.p (the previous vertex, the same point NEE sampled from) that reached
    /// light i at distance t along wi.
    float pdf_li(uint32_t i, const LightSampleContext& ctx, const Vec3& wi, float t) const {
        return light_pdf_li(m_lights[i], ctx, wi, t, m_pdf_mode);
    }

    /// Picks one light ∝ power: returns its index and probability.
    uint32_t select(float u, float* pmf) const { return static_cast<uint32_t>(m_selection.sample_discrete(u, pmf)); }
    float selection_pmf(uint32_t i) const { return m_selection.pmf(i); }

    const std::vector<uint32_t>& area_lights() const { return m_area_lights; }

    /// A constant world colour is not a light: next-event estimation never samples it, and rays that escape find
    /// it with weight 1. Uniform directions (its light sampling) would spend shadow rays on every direction,
    /// below the horizon too, while BSDF sampling already importance-samples a uniform environment by the
    /// BSDF; and every shadow ray spent on a dim sky is taken from the lights that matter (Blender's default world
    /// is a constant grey). Cycles 3.4 does the same: it turns background MIS off for a background without
    /// spatial variation. A varying world (an environment map) is a WorldLight and is light-sampled.
    void set_background(const Color& radiance) { m_background = radiance; }
    const Color& background() const { return m_background; }

    /// The light-sampled world (an environment map), if any.
    int world_light() const { return m_world; }
    const WorldLight* world() const { return m_world < 0 ? nullptr : &std::get<WorldLight>(m_lights[m_world]); }

private:
    std::vector<Light> m_lights;
    std::vector<uint32_t> m_area_lights;
    int m_world = -1;
    Color m_background{0.f};
    Distribution1D m_selection;
    LightPdfMode m_pdf_mode = LightPdfMode::SolidAngle;
};

}  // namespace candela
