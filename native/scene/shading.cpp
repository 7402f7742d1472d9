// Scene::shade: the material at a hit, with its shader program evaluated there (textures, Normal Map), and
// the world's environment light.
#include <cmath>

#include "core/parallel.h"
#include "scene/scene_parts.h"

namespace candela {

ShadingInputs Scene::shading_inputs(const SurfaceHit& hit, const Vec3& wo, const Placement& pl, bool differentials,
                                    const LightPathInfo* path) const {
    // Where on the object the hit is: UV, tangent frame, object-space position.
    const PrimitiveRef& prim = hit.primitive;
    const MeshAttributes& attr = m_shading[pl.mesh].attributes;
    ShadingInputs in;
    in.uv = attr.uv_at(prim.prim, hit.b1, hit.b2);
    in.object = pl.world_to_object.point(hit.p);
    in.generated = attr.generated(in.object);
    in.normal = hit.ns;
    const Vec3 n_object = pl.object_to_world.transpose_vector(hit.ns);
    const float n_len = length(n_object);
    in.normal_object = n_len > 0.f ? n_object / n_len : Vec3(0.f, 0.f, 1.f);
    in.incoming = wo;
    in.backfacing = dot(wo, hit.ng) < 0.f;
    in.position = hit.p - m_offset;
    in.true_normal = hit.ng;
    in.object_location = pl.object_to_world.translation() - m_offset;
    in.object_index = float(pl.pass_index);
    in.object_color = pl.color;
    in.object_alpha = pl.alpha;
    in.object_random = pl.random;
    if (path) in.path = *path;
    if (m_shaders->reads_window()) {
        const Vec2 r = m_camera.world_to_raster(hit.p);
        in.window = Vec3(r.x / float(m_camera.full_width()), r.y / float(m_camera.full_height()), 0.f);
    }
    in.attributes = attr.attribute_corners(prim.prim);
    in.attribute_slots = attr.attribute_slots;
    in.b1 = hit.b1;
    in.b2 = hit.b2;
    Vec3 tangent;
    if (attr.tangent_at(prim.prim, hit.b1, hit.b2, &tangent, &in.tangent_sign)) {
        in.tangent = pl.object_to_world.vector(tangent);
        in.has_tangent = true;
    }
    in.normal_to_world = pl.object_to_world.normal_matrix();
    if (differentials) {
        // Bump's finite differences, as Cycles 3.4 takes them: offsets of one ray footprint (a camera ray's
        // differential at the hit: docs/textures.md, "Bump") along the frame Cycles' make_orthonormals builds
        // around the geometric normal on the viewer's side. The frame matters for curved heights (the differences
        // are secants, not derivatives); a linear height gives the same normal for any frame.
        const float delta = std::fmax(m_camera.pixel_footprint(length(hit.p)), 1e-7f);
        const Vec3 n = in.backfacing ? -hit.ng : hit.ng;
        Vec3 a =
            (n.x != n.y || n.x != n.z) ? Vec3(n.z - n.y, n.x - n.z, n.y - n.x) : Vec3(n.z - n.y, n.x + n.z, -n.y - n.x);
        a = normalize(a);
        in.dp[0] = a * delta;
        in.dp[1] = cross(n, a) * delta;
        for (int k = 0; k < 2; ++k) {
            in.dobject[k] = pl.world_to_object.vector(in.dp[k]);
            in.dgenerated[k] = attr.generated(in.object + in.dobject[k]) - in.generated;
            in.duv[k] = attr.uv_offset(prim.prim, in.dobject[k]);
        }
    }
    return in;
}

ShadingPoint Scene::shade(const SurfaceHit& hit, const Vec3& wo, const LightPathInfo* path) const {
    const Material& material = m_materials[hit.material];
    ShadingPoint sp;
    sp.ns = hit.ns;
    sp.emission = material.emission;
    sp.backfacing = dot(wo, hit.ng) < 0.f;
    sp.use(&material.bsdf(sp.backfacing));
    if (material.inputs < 0) return sp;  // constant inputs: everything was built at load

    const MaterialInputs& mi = m_material_inputs[size_t(material.inputs)];
    const PrimitiveRef& prim = hit.primitive;
    std::optional<Placement>
        moved;  // a moving object's transforms at the path's shutter time (object space, Object Info)
    const ShadingInputs in =
        shading_inputs(hit, wo, placement_now(prim.inst != PrimitiveRef::k_none ? prim.inst : prim.geom, moved),
                       m_shaders->uses_differentials(mi.program), path);
    ShaderRegisters regs(m_shaders->program_size(mi.program));
    m_shaders->evaluate(mi.program, in, regs.data());
    if (mi.emission_reg >= 0) sp.emission = vmax(regs[uint32_t(mi.emission_reg)], Color(0.f));
    if (mi.normal_reg >= 0) {
        const Vec3 n = regs[uint32_t(mi.normal_reg)];
        const float len = length(n);
        if (len > 0.f && std::isfinite(len)) sp.ns = n / len;
        sp.bent = !mi.normal_is_displacement && (sp.ns.x != hit.ns.x || sp.ns.y != hit.ns.y || sp.ns.z != hit.ns.z);
    }
    // Closures whose inputs were all folded at load keep the material's own BSDF.
    if (!mi.bindings.empty()) sp.own(mi.bsdf(regs.data(), sp.backfacing));
    return sp;
}

float Scene::varying_holdout(const SurfaceHit& hit, const Vec3& wo) const {
    const MaterialInputs& mi = m_material_inputs[size_t(m_materials[hit.material].inputs)];
    const PrimitiveRef& prim = hit.primitive;
    ShaderRegisters regs(m_shaders->program_size(mi.program));
    std::optional<Placement> moved;
    m_shaders->evaluate(
        mi.program,
        shading_inputs(hit, wo, placement_now(prim.inst != PrimitiveRef::k_none ? prim.inst : prim.geom, moved)),
        regs.data());
    return holdout_weight(regs[uint32_t(mi.holdout_reg)]);
}

bool Scene::varying_emission(uint32_t k) const {
    const int32_t inputs = m_materials[k].inputs;
    return inputs >= 0 && m_material_inputs[size_t(inputs)].emission_reg >= 0;
}

Color Scene::textured_emission(const Placement& pl, uint32_t prim, const Vec3& p, const Vec3& ng, float b1, float b2,
                               const Vec3& wo) const {
    // The hit a ray reaching p would report (Scene::intersect), as far as the shader program reads it.
    const MeshShading& s = m_shading[pl.mesh];
    SurfaceHit hit;
    hit.p = p;
    hit.ng = ng;
    hit.ns = shading_normal(s, pl, prim, b1, b2, ng);
    hit.material = s.material[prim];
    hit.primitive.prim = prim;
    hit.b1 = b1;
    hit.b2 = b2;
    const MaterialInputs& mi = m_material_inputs[size_t(m_materials[hit.material].inputs)];
    ShaderRegisters regs(m_shaders->program_size(mi.program));
    m_shaders->evaluate(mi.program, shading_inputs(hit, wo, pl), regs.data());
    return vmax(regs[uint32_t(mi.emission_reg)], Color(0.f));
}

Color Scene::average_emission(const Placement& pl, uint32_t prim, const Vec3 (&v)[3], const Vec3& ng) const {
    // The centroids of the four triangles of its midpoint subdivision (equal areas), seen head-on: (b1, b2)
    // pairs. An estimate only: light sampling evaluates the exact radiance at every sampled point.
    static constexpr float k_points[4][2] = {
        {1.f / 3, 1.f / 3}, {1.f / 6, 1.f / 6}, {2.f / 3, 1.f / 6}, {1.f / 6, 2.f / 3}};
    Color sum(0.f);
    for (const auto& b : k_points) {
        const Vec3 p = v[0] * (1.f - b[0] - b[1]) + v[1] * b[0] + v[2] * b[1];
        sum += textured_emission(pl, prim, p, ng, b[0], b[1], ng);
    }
    return sum / 4.f;
}

Color Scene::emission(uint32_t id, const Vec3& p, const Vec3& ng, float b1, float b2, const Vec3& wo) const {
    const Emitter& e = m_emitters[id];
    return textured_emission(m_placements[e.placement], e.prim, p, ng, b1, b2, wo);
}

Color Scene::world_radiance(const Vec3& d, const LightPathInfo& path) const {
    ShadingInputs in = ShadingInputs::world(d);
    in.path = path;
    ShaderRegisters regs(m_shaders->program_size(uint32_t(m_world_program)));
    m_shaders->evaluate(uint32_t(m_world_program), in, regs.data());
    return vmax(regs[uint32_t(m_world_reg)], Color(0.f));
}

void Scene::add_environment() {
    const auto program = uint32_t(m_world_program), reg = uint32_t(m_world_reg);
    // A world that varies only with the path (a Light Path node: "the camera sees white, the scene is lit by
    // blue") is constant in direction, so Cycles neither light-samples it nor needs to: escaping rays evaluate it
    // with their own Light Path inputs (world_radiance), and the light set keeps the value light sampling would see.
    m_world_path_dependent = m_shaders->path_dependent(program, reg);
    if (!m_shaders->spatially_varying(program, reg)) {  // a constant after all: the background colour, not a light
        ShaderRegisters regs(m_shaders->program_size(program));
        m_shaders->evaluate(program, ShadingInputs::world(Vec3(0.f, 0.f, 1.f)), regs.data());
        m_lights.set_background(vmax(regs[reg], Color(0.f)));
        return;
    }
    auto env = std::make_shared<const EnvironmentMap>(m_shaders, program, reg, resolve_thread_count(m_threads));
    if (is_black(env->mean_radiance())) return;  // a black environment emits nothing
    m_lights.add(WorldLight{env->mean_radiance(), m_radius, env});
}

}  // namespace candela
