// Static scene analysis for AUTO (docs/auto.md, "Features"): what the built scene can do, read once after the
// BVH is built and before any ray is traced — the lights by kind, size and power, the materials' lobes weighted by
// the surface area that carries them, whether light can reach a diffuse surface through a delta lobe from a source
// a path tracer cannot hit (L S+ D), the camera and the ray types objects are hidden from. One pass over the
// lights and one over the triangles: no rays, so it costs far less than a sample per pixel.
#pragma once

#include <cstdint>
#include <string>

#include "integrators/auto/pilot.h"
#include "scene/scene.h"

namespace candela {

/// A hittable emitter (area light, emissive object) is small when its area is under this fraction of the scene's
/// bounding-sphere cross-section πR²: a BSDF ray from a typical surface then hits it rarely, so paths that reach it
/// only after a delta bounce are noisy for a path tracer. A guess (docs/auto.md): the glass caustic's light is
/// 0.0022 πR², the Cornell box's 0.027 πR².
constexpr double k_small_light_area_fraction = 0.01;

enum class WorldKind { None, Constant, Textured };
const char* world_kind_name(WorldKind k);

struct SceneFeatures {
    // Lights (the LightSet: zero-strength Blender lights are already dropped at load; emissive triangles count one
    // per object here, the LightSet has one per triangle).
    int light_count = 0;                // entries of the LightSet
    int unhittable_lights = 0;          // point, spot and sun lights (soft or not): no ray ever hits them
    int delta_lights = 0;               // of those, the ones of zero radius/angle (a delta in position or direction)
    int small_emitters = 0;             // area lights and emissive objects under k_small_light_area_fraction·πR²
    int large_emitters = 0;             // the other area lights and emissive objects
    int zero_power_lights = 0;          // LightSet entries of zero power (a black emissive triangle, say)
    double total_power = 0.0;           // Σ light_power over the LightSet (luminance-weighted W, as selection sees it)
    double unhittable_power = 0.0;      // the point/spot/sun share of it
    double small_power = 0.0;           // the small emitters' share of it
    double delta_power = 0.0;           // the delta lights' (zero radius/angle) share of it
    WorldKind world = WorldKind::None;  // constant: a background colour (not a light); textured: a WorldLight

    // Surfaces: area of the triangles whose material can have each lobe (a material with several lobes counts in
    // each). Specular = a delta lobe (Scene::material_flags' k_bsdf_specular).
    double total_area = 0.0;
    double diffuse_area = 0.0, glossy_area = 0.0, specular_area = 0.0, transmissive_area = 0.0;
    double emissive_area = 0.0;
    int specular_materials = 0, transmissive_materials = 0;  // materials used by some triangle

    /// An L S+ D path can exist: a delta surface, a surface with a non-delta lobe to receive it, and a light a path
    /// tracer cannot hit or hits rarely (unhittable or small). Static: it does not know whether the light actually
    /// reaches the delta surface, only that nothing rules it out.
    bool caustic_paths = false;

    // Camera and visibility.
    bool orthographic = false;
    bool camera_connectable = true;  // Camera::connectable(): false for a pinhole orthographic camera
    uint32_t hidden_ray_types = 0;   // Scene::hidden_ray_types(): k_ray_* bits some object is hidden from

    double scene_radius = 0.0;  // bounds().radius

    /// The pilot render's measurements (pilot.h), when AUTO ran one (analyse_scene does not).
    bool pilot_measured = false;
    PilotResult pilot;
    /// The render is one frame of an animation (the add-on's "animation" param to AUTO: Blender's is_animation): the
    /// policy skips integrators whose image would flicker from frame to frame (auto_policy.cpp).
    bool animation = false;

    double unhittable_power_share() const { return total_power > 0.0 ? unhittable_power / total_power : 0.0; }
    double small_power_share() const { return total_power > 0.0 ? small_power / total_power : 0.0; }
    double delta_power_share() const { return total_power > 0.0 ? delta_power / total_power : 0.0; }
    double area_share(double a) const { return total_area > 0.0 ? a / total_area : 0.0; }
    /// One line for the log: every feature, names as the fields'.
    std::string summary() const;
};

/// Computes the features of a built scene (deterministic: sums in object and triangle order).
SceneFeatures analyse_scene(const Scene& scene);

}  // namespace candela
