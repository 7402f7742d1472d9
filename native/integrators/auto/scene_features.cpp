#include "integrators/auto/scene_features.h"

#include <cmath>
#include <cstdio>
#include <type_traits>
#include <variant>
#include <vector>

#include "bsdf/bsdf_sample.h"
#include "lights/light.h"

namespace candela {

const char* world_kind_name(WorldKind k) {
    switch (k) {
    case WorldKind::Constant: return "constant";
    case WorldKind::Textured: return "textured";
    default: return "none";
    }
}

namespace {

double triangle_area(const ObjectTriangles& t, uint32_t prim) {
    Vec3 v[3];
    for (int c = 0; c < 3; ++c) {
        const float* p = t.vertices + 3 * size_t(t.indices[3 * size_t(prim) + c]);
        v[c] = Vec3(p[0], p[1], p[2]);
        if (t.instanced) v[c] = t.object_to_world.point(v[c]);
    }
    return 0.5 * double(length(cross(v[1] - v[0], v[2] - v[0])));
}

// The lights that are not triangles of objects (those are counted per object in the triangle pass).
void analyse_lights(const Scene& scene, double small_area, SceneFeatures* f) {
    const LightSet& lights = scene.lights();
    f->light_count = int(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        const double power = double(light_power(l));
        f->total_power += power;
        if (!(power > 0.0)) ++f->zero_power_lights;
        std::visit(
            [&](const auto& x) {
                using T = std::decay_t<decltype(x)>;
                if constexpr (std::is_same_v<T, PointLight>) {
                    ++f->unhittable_lights;
                    f->unhittable_power += power;
                    if (x.radius <= 0.f) {
                        ++f->delta_lights;
                        f->delta_power += power;
                    }
                } else if constexpr (std::is_same_v<T, SunLight>) {
                    ++f->unhittable_lights;
                    f->unhittable_power += power;
                    if (x.tan_half_angle <= 0.f) {
                        ++f->delta_lights;
                        f->delta_power += power;
                    }
                } else if constexpr (std::is_same_v<T, AreaLight>) {
                    if (double(x.area) < small_area) {
                        ++f->small_emitters;
                        f->small_power += power;
                    } else {
                        ++f->large_emitters;
                    }
                } else if constexpr (std::is_same_v<T, WorldLight>) {
                    f->world = WorldKind::Textured;
                }
            },
            l);
    }
    if (f->world == WorldKind::None && luminance(lights.background()) > 0.f) f->world = WorldKind::Constant;
}

void analyse_surfaces(const Scene& scene, double small_area, SceneFeatures* f) {
    std::vector<bool> used(scene.materials().size(), false);
    for (uint32_t o = 0; o < scene.object_count(); ++o) {
        const ObjectTriangles t = scene.object_triangles(o);
        double emitting_area = 0.0, emitting_power = 0.0;
        for (uint32_t prim = 0; prim < t.triangle_count; ++prim) {
            const double a = triangle_area(t, prim);
            const SurfaceHit h = scene.surface_point(o, prim, 1.f / 3.f, 1.f / 3.f);
            const uint32_t flags = scene.material_flags(h.material);
            if (h.material < used.size()) used[h.material] = true;
            f->total_area += a;
            if (flags & k_bsdf_diffuse) f->diffuse_area += a;
            if (flags & k_bsdf_glossy) f->glossy_area += a;
            if (flags & k_bsdf_specular) f->specular_area += a;
            if (flags & k_bsdf_transmission) f->transmissive_area += a;
            if (h.light >= 0) {
                emitting_area += a;
                emitting_power += double(light_power(scene.lights()[size_t(h.light)]));
            }
        }
        if (emitting_area <= 0.0) continue;
        f->emissive_area += emitting_area;
        if (emitting_area < small_area) {
            ++f->small_emitters;
            f->small_power += emitting_power;
        } else {
            ++f->large_emitters;
        }
    }
    for (size_t k = 0; k < used.size(); ++k) {
        if (!used[k]) continue;
        const uint32_t flags = scene.material_flags(uint32_t(k));
        if (flags & k_bsdf_specular) ++f->specular_materials;
        if (flags & k_bsdf_transmission) ++f->transmissive_materials;
    }
}

}  // namespace

SceneFeatures analyse_scene(const Scene& scene) {
    SceneFeatures f;
    f.scene_radius = double(scene.bounds().radius);
    const double small_area = k_small_light_area_fraction * 3.14159265358979 * f.scene_radius * f.scene_radius;
    analyse_lights(scene, small_area, &f);
    analyse_surfaces(scene, small_area, &f);
    // L S+ D: a delta surface, a non-delta receiver, and a source the path tracer cannot hit (or hits rarely).
    const bool hard_sources = f.unhittable_power > 0.0 || f.small_power > 0.0;
    f.caustic_paths = f.specular_area > 0.0 && (f.diffuse_area > 0.0 || f.glossy_area > 0.0) && hard_sources;
    f.orthographic = scene.camera().orthographic();
    f.camera_connectable = scene.camera().connectable();
    f.hidden_ray_types = scene.hidden_ray_types();
    return f;
}

std::string SceneFeatures::summary() const {
    char buf[640];
    std::snprintf(buf, sizeof buf,
                  "Auto: scene features: lights %d (unhittable %d, delta %d, small %d, large %d, zero-power %d; "
                  "power share unhittable %.0f %%, small %.0f %%), world %s; area: diffuse %.0f %%, glossy %.0f %%, "
                  "specular %.0f %%, transmissive %.0f %%, emissive %.1f %%; caustic paths %s; camera %s%s; hidden "
                  "ray types 0x%x",
                  light_count, unhittable_lights, delta_lights, small_emitters, large_emitters, zero_power_lights,
                  100.0 * unhittable_power_share(), 100.0 * small_power_share(), world_kind_name(world),
                  100.0 * area_share(diffuse_area), 100.0 * area_share(glossy_area), 100.0 * area_share(specular_area),
                  100.0 * area_share(transmissive_area), 100.0 * area_share(emissive_area),
                  caustic_paths ? "yes" : "no", orthographic ? "orthographic" : "perspective",
                  camera_connectable ? "" : " (pinhole: not connectable)", unsigned(hidden_ray_types));
    return buf;
}

}  // namespace candela
