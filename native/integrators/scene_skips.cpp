#include "integrators/scene_skips.h"

#include <type_traits>
#include <variant>

#include "integrators/auto/scene_features.h"
#include "lights/light.h"

namespace candela {

namespace {

bool is_bidirectional(const std::string& integrator) {
    return integrator == "BDPT" || integrator == "MLT" || integrator == "MMLT";
}

}  // namespace

bool has_hittable_emission(const Scene& scene) {
    const LightSet& lights = scene.lights();
    if (!is_black(lights.background()) || lights.world() || scene.world_reads_light_path()) return true;
    for (size_t i = 0; i < lights.size(); ++i)
        if (!std::holds_alternative<PointLight>(lights[i]) && !std::holds_alternative<SunLight>(lights[i])) return true;
    // Emissive surfaces without a light entry (none expected: the scene lists every emitting triangle), by the
    // materials' flags as the static features read them.
    for (const Material& m : scene.materials())
        if (m.is_emissive()) return true;
    return analyse_scene(scene).emissive_area > 0.0;
}

std::string scene_skips_line(const std::vector<SceneSkip>& skips) {
    std::string out;
    for (const SceneSkip& s : skips) out += (out.empty() ? "Skipped, the scene does not need them: " : "; ") + s.line;
    return out;
}

std::vector<SceneSkip> scene_skips(const std::string& integrator, const Scene& scene) {
    const SceneFeatures f = analyse_scene(scene);
    std::vector<SceneSkip> out;
    auto n = [](int k) { return std::to_string(k); };
    // PATH's nee_here, the light subpaths' emitter choice, the photon tracer's emission: all test lights().empty().
    if (f.light_count == 0) out.push_back({"no_nee", "next-event estimation (no light to sample)"});
    // LightSet::set_background: a constant world is not a WorldLight, so no importance map is built for it.
    if (f.world == WorldKind::Constant)
        out.push_back({"constant_world",
                       "the environment importance map (the world is constant: found by escaping rays, never "
                       "light-sampled)"});
    // Zero power: probability 0 in every light selection (power, tree, emitter set), so never sampled.
    if (f.zero_power_lights > 0)
        out.push_back({"zero_power_lights", n(f.zero_power_lights) + " light(s) of zero power (never selected)"});
    // direct_light.h: a light sample with is_delta (point, spot, sun) gets weight 1, no BSDF pdf evaluated.
    if (f.unhittable_lights > 0)
        out.push_back({"delta_mis", "MIS for " + n(f.unhittable_lights) +
                                        " point/spot/sun light(s) (no ray can hit them: weight 1)"});
    // shadow_ray.h: without Transparent materials a shadow ray is one occlusion query, not a walk through surfaces.
    if (!scene.has_transparent_materials())
        out.push_back({"no_transparent_shadows",
                       "transparent shadows (no Transparent material: shadow rays stop at the first surface)"});
    // bdpt_tracer.cpp: s = 0 strategies end the camera subpath on an emitter it hit.
    if (is_bidirectional(integrator) && f.light_count > 0 && !has_hittable_emission(scene))
        out.push_back({"bdpt_no_s0",
                       "BDPT's s = 0 strategies (every light is a point, spot or sun light: nothing a ray can hit "
                       "emits)"});
    return out;
}

}  // namespace candela
