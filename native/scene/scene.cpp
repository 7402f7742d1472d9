#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bsdf/material_inputs.h"
#include "core/error.h"
#include "input/scene_arrays.h"
#include "scene/mesh_bvh_cache.h"
#include "scene/scene_parts.h"

namespace candela {

namespace {

Affine camera_matrix(const float* rows16) {
    Affine m = Affine::from_rows(rows16);
    // Only rotation and translation are meaningful; normalise columns so a scaled camera still works.
    for (int c = 0; c < 3; ++c) {
        const Vec3 col = m.column(c);
        const float len = length(col);
        if (!(len > 0.f)) throw InvalidScene("camera_to_world is singular");
        for (int r = 0; r < 3; ++r) m.m[r][c] /= len;
    }
    return m;
}
Affine camera_matrix(const SceneArrays& arrays) { return camera_matrix(arrays.get("camera_to_world").data<float>()); }

/// The camera with its motion over the shutter (camera_motion), if it moves.
Camera make_camera(const SceneArrays& arrays, const Params& params) {
    Camera camera(params, camera_matrix(arrays));
    if (const Array* m = arrays.find("camera_motion")) {
        std::vector<Affine> steps;
        for (size_t i = 0; i < m->shape[0]; ++i) steps.push_back(camera_matrix(m->data<float>() + 16 * i));
        camera.set_motion(steps);
    }
    return camera;
}

/// Every BSDF flag a closure of this type can produce for some input (bsdf/bsdf_sample.h).
uint32_t closure_flags(ClosureType type) {
    constexpr uint32_t R = k_bsdf_reflection, T = k_bsdf_transmission, D = k_bsdf_diffuse, G = k_bsdf_glossy,
                       S = k_bsdf_specular;
    switch (type) {
    case ClosureType::Diffuse: return R | D;
    case ClosureType::Translucent: return T | D;
    case ClosureType::Glossy: return R | G | S;
    case ClosureType::Glass: return R | T | G | S;
    case ClosureType::Refraction: return T | G | S;
    case ClosureType::Transparent: return T | S | k_bsdf_transparent;
    default: return R | T | D | G | S;  // Principled: every lobe
    }
}

}  // namespace

Scene::Scene(const SceneArrays& arrays, const Params& params, const CancelToken* cancel, MeshBvhCache* cache)
    : m_device(cache ? cache->device() : std::make_shared<EmbreeDevice>(params.get<int>("threads", 0))),
      m_camera(make_camera(arrays, params)) {
    m_offset = -m_camera.position();  // a moving camera's at the shutter's middle
    m_has_motion = m_camera.moves();
    m_camera.translate(m_offset);
    m_materials = load_materials(arrays);
    m_shaders = ShaderLibrary::load(arrays);
    if (const Array* h = arrays.find("material_holdout"))
        m_material_holdout.assign(h->data<float>(), h->data<float>() + h->count());
    m_material_inputs =
        load_material_inputs(arrays, *m_shaders, m_materials, &m_world_program, &m_world_reg, &m_material_holdout);
    for (float w : m_material_holdout) m_has_holdouts |= w > 0.f;
    for (const MaterialInputs& mi : m_material_inputs) {
        m_has_holdouts |= mi.holdout_reg >= 0;
        m_any_bent_normal |= mi.normal_reg >= 0 && !mi.normal_is_displacement;
    }
    m_threads = params.get<int>("threads", 0);
    m_material_flags.resize(m_materials.size(), 0u);
    for (size_t k = 0; k < m_materials.size(); ++k)
        m_material_flags[k] = m_materials[k].front.flags() | m_materials[k].back.flags();
    if (const Array* cm = arrays.find("closure_material")) {  // textured materials: what their closures allow
        const uint32_t* mat = cm->data<uint32_t>();
        const uint32_t* type = arrays.get("closure_type").data<uint32_t>();
        for (size_t i = 0; i < cm->count(); ++i)
            if (mat[i] < m_materials.size() && m_materials[mat[i]].inputs >= 0)
                m_material_flags[mat[i]] |= closure_flags(ClosureType(type[i]));
    }
    for (uint32_t f : m_material_flags) m_any_transparent |= (f & k_bsdf_transparent) != 0;
    build(arrays, cancel, cache);
}

void Scene::set_camera(const Params& params, const Affine& camera_to_world) {
    Camera camera(params, camera_to_world);
    camera.translate(m_offset);  // into the camera-world space the scene was built in
    m_camera = camera;
}

const Scene::Placement& Scene::moved_placement(const Placement& pl, std::optional<Placement>& scratch) const {
    Placement& moved = scratch.emplace(pl);
    moved.object_to_world = m_motions[size_t(pl.motion)].at(shutter_time());
    moved.world_to_object = moved.object_to_world.inverse();
    moved.normal_to_world = moved.object_to_world.normal_matrix();
    moved.mirrored = moved.object_to_world.determinant3() < 0.f;
    return moved;
}

Scene::~Scene() = default;

}  // namespace candela
