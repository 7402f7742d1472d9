#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "bsdf/material_inputs.h"
#include "scene/coplanar_overlap.h"
#include "scene/scene_arrays.h"
#include "scene/scene_parts.h"

namespace candela {

/// Embree's per-query context plus what filter_hits needs. It runs as the context filter (every candidate hit) for
/// ray types some object is hidden from, and otherwise as the geometry filter of the objects with a coplanar rival.
struct Scene::QueryContext {
    RTCIntersectContext context;
    PrimitiveRef skip[2];
    const Scene* scene = nullptr;  // set for closest-hit queries: coplanar ties are broken
    uint8_t ray_type = 0;                   // RayType bits checked against object_flags; 0 = no visibility check
    const uint8_t* object_flags = nullptr;  // per top-level geometry id (ObjectFlag bits)
    float origin_magnitude = 0.f, dir_length = 1.f;
    bool have_best = false;
    float best_t = 0.f, best_tolerance = 0.f;
    PrimitiveRef best;
};

namespace {

Affine camera_matrix(const SceneArrays& arrays) {
    Affine m = Affine::from_rows(arrays.get("camera_to_world").data<float>());
    // Only rotation and translation are meaningful; normalise columns so a scaled camera still works.
    for (int c = 0; c < 3; ++c) {
        const Vec3 col = m.column(c);
        const float len = length(col);
        if (!(len > 0.f)) throw InvalidScene("camera_to_world is singular");
        for (int r = 0; r < 3; ++r) m.m[r][c] /= len;
    }
    return m;
}

uint32_t top_level_id(const PrimitiveRef& h) { return h.inst != PrimitiveRef::k_none ? h.inst : h.geom; }

/// Marks the rays Scene shoots (RTCRay::id): their context is a QueryContext. Raw queries through embree_scene()
/// leave id 0 and pass the geometry filters untouched.
constexpr unsigned k_query_tag = 0x43414E44u;  // "CAND"
/// Area lights count up to this relative distance behind a surface: the shadow rays' margin (1 − 1e-4).
constexpr float k_light_margin = 1e-4f;

bool progress_monitor(void* ptr, double) {
    const auto* cancel = static_cast<const CancelToken*>(ptr);
    return !(cancel && cancel->cancelled());
}

struct MeshRange {
    uint32_t tri_begin, tri_end, vert_begin, vert_end;
};

}  // namespace

void Scene::filter_hits(const RTCFilterFunctionNArguments* args) {
    auto* ctx = reinterpret_cast<QueryContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const PrimitiveRef hit{RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i),
                               RTCHitN_instID(args->hit, args->N, i, 0)};
        if (hit == ctx->skip[0] || hit == ctx->skip[1]) {
            args->valid[i] = 0;
            continue;
        }
        // Objects hidden from this ray type (Object > Visibility > Ray Visibility).
        if (ctx->ray_type != 0 && (ctx->object_flags[top_level_id(hit)] & ctx->ray_type) == 0) {
            args->valid[i] = 0;
            continue;
        }
        if (!ctx->scene) continue;  // occlusion: any hit will do
        // Closest hit: Embree has set tfar to this candidate's distance and restores it if we reject.
        float& tfar = RTCRayN_tfar(args->ray, args->N, i);
        const float t = tfar;
        // In an instance the ray and Ng are in object space; t is the same parameter in both spaces.
        const Vec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                     RTCRayN_dir_z(args->ray, args->N, i));
        const Vec3 ng(RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
                      RTCHitN_Ng_z(args->hit, args->N, i));
        const float dn = length(d) * length(ng);
        const float cos_theta = dn > 0.f ? std::fabs(dot(d, ng)) / dn : 1.f;
        const Placement& pl = ctx->scene->m_placements[top_level_id(hit)];
        const float plane_tolerance =
            k_coplanar_ulps * (ctx->origin_magnitude + t * ctx->dir_length + pl.magnitude);
        const float tolerance = plane_tolerance / (ctx->dir_length * std::max(cos_theta, 1e-3f));
        if (ctx->have_best && t > ctx->best_t - std::max(tolerance, ctx->best_tolerance) &&
            !ctx->scene->outranks(hit, ctx->best)) {
            args->valid[i] = 0;  // coplanar with the current hit, which has the priority
            continue;
        }
        ctx->have_best = true;
        ctx->best_t = t;
        ctx->best_tolerance = tolerance;
        ctx->best = hit;
        // Keep reporting hits up to the tolerance behind this one, so a coplanar rival is always compared.
        if (std::isfinite(tolerance)) tfar = t + tolerance;
    }
}

void Scene::coplanar_filter(const RTCFilterFunctionNArguments* args) {
    // With a context filter installed it does the whole job (it runs after this one, on every hit).
    if (args->context->filter != nullptr || RTCRayN_id(args->ray, args->N, 0) != k_query_tag) return;
    filter_hits(args);
}

bool Scene::outranks(const PrimitiveRef& a, const PrimitiveRef& b) const {
    auto key = [&](const PrimitiveRef& h) {
        const uint32_t top = top_level_id(h);
        const bool emissive = m_shading[m_placements[top].mesh].emissive_rank[h.prim] >= 0;
        return (uint64_t(emissive) << 63) | (uint64_t(top) << 32) | h.prim;
    };
    return key(a) > key(b);
}

Scene::Scene(const SceneArrays& arrays, const Params& params, const CancelToken* cancel)
    : m_device(params.get<int>("threads", 0)), m_camera(params, camera_matrix(arrays)) {
    m_offset = -m_camera.position();
    m_camera.translate(m_offset);
    m_materials = load_materials(arrays);
    m_shaders = ShaderLibrary::load(arrays);
    if (const Array* h = arrays.find("material_holdout"))
        m_material_holdout.assign(h->data<float>(), h->data<float>() + h->count());
    m_material_inputs = load_material_inputs(arrays, *m_shaders, m_materials, &m_world_program, &m_world_reg,
                                             &m_material_holdout);
    for (float w : m_material_holdout) m_has_holdouts |= w > 0.f;
    for (const MaterialInputs& mi : m_material_inputs) m_has_holdouts |= mi.holdout_reg >= 0;
    m_threads = params.get<int>("threads", 0);
    build(arrays, cancel);
}

Scene::~Scene() = default;

void Scene::build(const SceneArrays& arrays, const CancelToken* cancel) {
    const float* positions = arrays.get("positions").data<float>();
    const uint32_t* triangles = arrays.get("triangles").data<uint32_t>();
    const uint32_t* tri_material = arrays.get("tri_material").data<uint32_t>();
    const Array* smooth_arr = arrays.find("tri_smooth");
    const Array* normals_arr = arrays.find("normals");           // per corner (takes precedence) ...
    const Array* vertex_normals_arr = arrays.find("vertex_normals");  // ... or per vertex
    const uint32_t* mesh_start = arrays.get("mesh_tri_start").data<uint32_t>();
    const uint32_t* instance_mesh = arrays.get("instance_mesh").data<uint32_t>();
    const float* instance_xf = arrays.get("instance_transform").data<float>();
    const size_t mesh_count = arrays.rows("mesh_tri_start") - 1;
    const size_t instance_count = arrays.rows("instance_mesh");
    const Array* flags_arr = arrays.find("instance_flags");
    const Array* pass_index_arr = arrays.find("instance_pass_index");

    // Vertex range and use count of every mesh.
    std::vector<MeshRange> ranges(mesh_count);
    std::vector<uint32_t> uses(mesh_count, 0);
    for (size_t i = 0; i < instance_count; ++i) ++uses[instance_mesh[i]];
    for (size_t m = 0; m < mesh_count; ++m) {
        MeshRange r{mesh_start[m], mesh_start[m + 1], std::numeric_limits<uint32_t>::max(), 0};
        for (uint32_t t = r.tri_begin; t < r.tri_end; ++t)
            for (int k = 0; k < 3; ++k) {
                r.vert_begin = std::min(r.vert_begin, triangles[3 * t + k]);
                r.vert_end = std::max(r.vert_end, triangles[3 * t + k] + 1);
            }
        if (r.tri_begin == r.tri_end) r.vert_begin = r.vert_end = 0;
        ranges[m] = r;
    }

    // Shading data of a mesh, transformed by `xf` when flattening.
    auto make_shading = [&](uint32_t m, const Affine* normal_xf) {
        MeshShading s;
        const MeshRange& r = ranges[m];
        const size_t n = r.tri_end - r.tri_begin;
        s.material.assign(tri_material + r.tri_begin, tri_material + r.tri_end);
        s.emissive_rank.assign(n, -1);
        int32_t rank = 0;
        for (size_t t = 0; t < n; ++t)
            if (m_materials[s.material[t]].is_emissive() || varying_emission(s.material[t])) s.emissive_rank[t] = rank++;
        if (std::any_of(s.material.begin(), s.material.end(), [&](uint32_t k) { return m_materials[k].inputs >= 0; }))
            s.attributes = MeshAttributes::load(arrays, m, r.tri_begin, r.tri_end);
        bool any_smooth = false;
        if (smooth_arr && (normals_arr || vertex_normals_arr)) {
            const uint8_t* sm = smooth_arr->data<uint8_t>() + r.tri_begin;
            s.smooth.assign(sm, sm + n);
            any_smooth = std::any_of(s.smooth.begin(), s.smooth.end(), [](uint8_t v) { return v != 0; });
        }
        if (any_smooth) {
            const float* nr = normals_arr ? normals_arr->data<float>() + 9 * size_t(r.tri_begin) : nullptr;
            const float* vn = vertex_normals_arr ? vertex_normals_arr->data<float>() : nullptr;
            const uint32_t* corner_vertex = triangles + 3 * size_t(r.tri_begin);
            s.normals.resize(3 * n);
            for (size_t i = 0; i < 3 * n; ++i) {
                const float* c = nr ? nr + 3 * i : vn + 3 * size_t(corner_vertex[i]);
                Vec3 v(c[0], c[1], c[2]);
                if (normal_xf) v = normal_xf->vector(v);
                const float len = length(v);
                s.normals[i] = len > 0.f ? v / len : Vec3(0.f);
            }
        } else {
            s.smooth.clear();
        }
        return s;
    };

    // Fills an Embree triangle geometry with the mesh's vertices mapped through `to_space`; *magnitude gets the
    // largest |coordinate| of the mapped vertices.
    // `coplanar`: the geometry gets the coplanar tie-break filter.
    auto make_geometry = [&](uint32_t m, const Affine& to_space, float* magnitude, bool coplanar) {
        const MeshRange& r = ranges[m];
        RTCGeometry g = rtcNewGeometry(m_device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);  // the object's own BVH (see the top scene below)
        const size_t nv = r.vert_end - r.vert_begin, nt = r.tri_end - r.tri_begin;
        auto* vb = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
        auto* ib = static_cast<uint32_t*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
        m_device.check("allocating geometry buffers");
        for (size_t v = 0; v < nv; ++v) {
            const float* p = positions + 3 * (r.vert_begin + v);
            const Vec3 q = to_space.point(Vec3(p[0], p[1], p[2]));
            vb[3 * v] = q.x;
            vb[3 * v + 1] = q.y;
            vb[3 * v + 2] = q.z;
            *magnitude = std::max({*magnitude, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
        }
        for (size_t t = 0; t < 3 * nt; ++t) ib[t] = triangles[3 * size_t(r.tri_begin) + t] - r.vert_begin;
        if (coplanar) {
            rtcSetGeometryIntersectFilterFunction(g, &Scene::coplanar_filter);
            rtcSetGeometryOccludedFilterFunction(g, &Scene::coplanar_filter);
        }
        rtcCommitGeometry(g);
        return g;
    };

    // Emissive triangles of one placement become lights (world space).
    // A textured emitter's light evaluates its material at each sampled point (Scene::emission); its power is
    // the triangle's average radiance.
    auto add_triangle_lights = [&](uint32_t m, const Affine& to_world, const MeshShading& s, const Placement& pl,
                                   uint32_t id) -> int32_t {
        const bool mirrored = pl.mirrored;
        const MeshRange& r = ranges[m];
        int32_t base = -1;
        for (uint32_t t = r.tri_begin; t < r.tri_end; ++t) {
            const int32_t rank = s.emissive_rank[t - r.tri_begin];
            if (rank < 0) continue;
            TriangleLight tl;
            Vec3 v[3];
            for (int k = 0; k < 3; ++k) {
                const float* p = positions + 3 * size_t(triangles[3 * size_t(t) + k]);
                v[k] = to_world.point(Vec3(p[0], p[1], p[2]));
            }
            tl.p0 = v[0];
            tl.p1 = v[1];
            tl.p2 = v[2];
            const Vec3 c = cross(v[1] - v[0], v[2] - v[0]);
            tl.area = 0.5f * length(c);
            if (!is_finite(v[0]) || !is_finite(v[1]) || !is_finite(v[2]) || !std::isfinite(tl.area))
                throw InvalidScene("an emissive triangle of mesh " + std::to_string(m) +
                                   " is not finite after its object's transform (is the scale too large?)");
            tl.normal = tl.area > 0.f ? normalize(mirrored ? -c : c) : Vec3(0.f, 0.f, 1.f);
            const uint32_t k = s.material[t - r.tri_begin];
            tl.radiance = m_materials[k].emission;
            if (varying_emission(k) && tl.area > 0.f) {
                tl.radiance = average_emission(pl, t - r.tri_begin, v, tl.normal);
                tl.source = this;
                tl.source_id = uint32_t(m_emitters.size());
                m_emitters.push_back({id, t - r.tri_begin});
            }
            // Degenerate triangles keep their light slot (ranks stay dense) but have zero power, so they
            // are never selected, and a zero area never divides.
            if (!(tl.area > 0.f)) tl.radiance = Color(0.f);
            const uint32_t index = m_lights.add(tl);
            if (base < 0) base = static_cast<int32_t>(index);
            ++m_stats.emissive_triangles;
        }
        return base;
    };

    // Acceleration structure: two levels. The top scene is built with RTC_BUILD_QUALITY_LOW, which makes Embree
    // build one BVH per geometry (object) and a BVH over the objects; each object's own BVH is built with
    // RTC_BUILD_QUALITY_HIGH (spatial splits, SBVH), which pays off for large triangles such as walls and floors.
    // Against one high-quality BVH over all triangles (measured, incoherent rays, 1 thread): 1.20x the ray rate
    // on the Cornell box (8 objects, 32 triangles), equal on 400 small objects in it and on a 317k-triangle
    // scene, with 3-5x faster builds (objects build separately).
    auto set_object_flags = [&](unsigned id, uint8_t flags) {
        if (m_object_flags.size() <= id) m_object_flags.resize(id + 1, k_object_default);
        m_object_flags[id] = flags;
    };

    // Each instance's object → camera-world transform.
    auto instance_transform = [&](size_t i) {
        Affine xf = Affine::from_rows(instance_xf + 16 * i);
        for (int r = 0; r < 3; ++r) xf.m[r][3] += m_offset[r];
        return xf;
    };

    // What needs Embree filters: ray types some object is hidden from get the context filter on every hit;
    // objects with a coplanar overlapping rival in another object get the tie-break as a geometry filter (an
    // instanced mesh for all its instances if any of them has a rival). Everything else takes Embree's closest hit.
    std::vector<CoplanarObject> coplanar_objects(instance_count);
    for (size_t i = 0; i < instance_count; ++i) {
        const uint32_t m = instance_mesh[i];
        if (ranges[m].tri_begin == ranges[m].tri_end) continue;
        m_hidden_from |= ~(flags_arr ? flags_arr->data<uint8_t>()[i] : uint8_t(k_object_default)) & k_ray_all;
        coplanar_objects[i] = {ranges[m].tri_begin, ranges[m].tri_end, instance_transform(i)};
    }
    const CoplanarReport coplanar =
        find_coplanar_rivals(positions, triangles, coplanar_objects, size_t(1) << 22, cancel);  // Esc stops it too
    std::vector<uint8_t> mesh_coplanar(mesh_count, 0);
    for (size_t i = 0; i < instance_count; ++i)
        if (coplanar.flagged[i]) {
            mesh_coplanar[instance_mesh[i]] = 1;
            ++m_stats.coplanar_objects;
            m_any_coplanar = true;
        }
    const RTCSceneFlags scene_flags = m_hidden_from ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : RTC_SCENE_FLAG_NONE;

    m_top = EmbreeScene(rtcNewScene(m_device.get()));
    rtcSetSceneBuildQuality(m_top.get(), RTC_BUILD_QUALITY_LOW);  // two levels: a BVH per object, one over them
    rtcSetSceneFlags(m_top.get(), scene_flags);
    rtcSetSceneProgressMonitorFunction(m_top.get(), &progress_monitor, const_cast<CancelToken*>(cancel));
    m_shading.resize(mesh_count);
    std::vector<int32_t> mesh_scene(mesh_count, -1);

    for (size_t i = 0; i < instance_count; ++i) {
        if (cancel && cancel->cancelled()) throw Cancelled();
        const uint32_t m = instance_mesh[i];
        if (ranges[m].tri_begin == ranges[m].tri_end) continue;  // a mesh without faces draws nothing
        const Affine xf = instance_transform(i);
        if (!std::isfinite(xf.determinant3()) || std::fabs(xf.determinant3()) < 1e-30f)
            throw InvalidScene("instance " + std::to_string(i) + " has a degenerate (zero-scale) transform");
        Placement pl;
        pl.mesh = m;
        pl.pass_index = pass_index_arr ? pass_index_arr->data<uint32_t>()[i] : 0u;
        const uint8_t flags = flags_arr ? flags_arr->data<uint8_t>()[i] : uint8_t(k_object_default);
        m_has_holdouts |= (flags & k_object_holdout) != 0;
        pl.mirrored = xf.determinant3() < 0.f;
        pl.object_to_world = xf;
        pl.world_to_object = xf.inverse();
        const size_t n = ranges[m].tri_end - ranges[m].tri_begin;
        m_stats.instanced_triangles += n;
        if (uses[m] == 1) {
            // Single use: flatten into world space, no instancing indirection at render time.
            const Affine nxf = xf.normal_matrix();
            m_shading[m] = make_shading(m, &nxf);
            RTCGeometry g = make_geometry(m, xf, &pl.magnitude, coplanar.flagged[i] != 0);
            const unsigned id = rtcAttachGeometry(m_top.get(), g);
            rtcReleaseGeometry(g);
            m_stats.unique_triangles += n;
            ++m_stats.meshes;
            if (m_placements.size() <= id) m_placements.resize(id + 1);
            pl.light_base = add_triangle_lights(m, xf, m_shading[m], pl, id);
            m_placements[id] = pl;
            set_object_flags(id, flags);
        } else {
            if (mesh_scene[m] < 0) {
                m_shading[m] = make_shading(m, nullptr);
                EmbreeScene s(rtcNewScene(m_device.get()));
                rtcSetSceneBuildQuality(s.get(), RTC_BUILD_QUALITY_HIGH);
                rtcSetSceneFlags(s.get(), scene_flags);
                rtcSetSceneProgressMonitorFunction(s.get(), &progress_monitor, const_cast<CancelToken*>(cancel));
                float unused = 0.f;
                RTCGeometry g = make_geometry(m, Affine(), &unused, mesh_coplanar[m] != 0);
                rtcAttachGeometry(s.get(), g);
                rtcReleaseGeometry(g);
                rtcCommitScene(s.get());
                if (cancel && cancel->cancelled()) throw Cancelled();
                m_device.check("building a mesh BVH");
                mesh_scene[m] = static_cast<int32_t>(m_mesh_scenes.size());
                m_mesh_scenes.push_back(std::move(s));
                m_stats.unique_triangles += n;
                ++m_stats.meshes;
            }
            RTCGeometry inst = rtcNewGeometry(m_device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, m_mesh_scenes[mesh_scene[m]].get());
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &xf.m[0][0]);
            rtcCommitGeometry(inst);
            const unsigned id = rtcAttachGeometry(m_top.get(), inst);
            rtcReleaseGeometry(inst);
            pl.instanced = true;
            pl.normal_to_world = xf.normal_matrix();
            pl.light_base = add_triangle_lights(m, xf, m_shading[m], pl, id);
            // Camera-world magnitude of the instance: its object-space bounds' corners, transformed.
            RTCBounds ob;
            rtcGetSceneBounds(m_mesh_scenes[mesh_scene[m]].get(), &ob);
            for (int corner = 0; corner < 8; ++corner) {
                const Vec3 q = xf.point(Vec3(corner & 1 ? ob.upper_x : ob.lower_x, corner & 2 ? ob.upper_y : ob.lower_y,
                                             corner & 4 ? ob.upper_z : ob.lower_z));
                pl.magnitude = std::max({pl.magnitude, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
            }
            if (m_placements.size() <= id) m_placements.resize(id + 1);
            m_placements[id] = pl;
            set_object_flags(id, flags);
            ++m_stats.instances;
        }
    }
    rtcCommitScene(m_top.get());
    if (cancel && cancel->cancelled()) throw Cancelled();
    m_device.check("building the scene BVH");

    RTCBounds b;
    rtcGetSceneBounds(m_top.get(), &b);
    Vec3 lo(b.lower_x, b.lower_y, b.lower_z), hi(b.upper_x, b.upper_y, b.upper_z);
    for (const Light& l : load_blender_lights(arrays, m_offset)) {
        if (const auto* p = std::get_if<PointLight>(&l)) {
            lo = vmin(lo, p->position);
            hi = vmax(hi, p->position);
        }
        m_lights.add(l);
    }
    m_radius = (lo.x <= hi.x) ? std::max(0.5f * length(hi - lo), 1e-3f) : 1.f;
    if (const Array* w = arrays.find("world_color")) {
        const float* c = w->data<float>();
        const Color col(c[0], c[1], c[2]);
        if (min_component(col) < 0.f) throw InvalidScene("world_color must not be negative");
        if (m_world_program < 0) m_lights.set_background(col);
    }
    if (m_world_program >= 0) add_environment();
    m_lights.finalize(m_radius);

    for (const MeshShading& s : m_shading)
        m_stats.shading_bytes += s.material.capacity() * sizeof(uint32_t) + s.smooth.capacity() +
                                 s.normals.capacity() * sizeof(Vec3) + s.emissive_rank.capacity() * sizeof(int32_t);
    m_stats.shading_bytes += m_placements.capacity() * sizeof(Placement);
    m_stats.embree_bytes = size_t(std::max<int64_t>(m_device.bytes(), 0));
}

Vec3 Scene::shading_normal(const MeshShading& s, const Placement& pl, uint32_t prim, float u, float v, const Vec3& ng) {
    if (s.smooth.empty() || !s.smooth[prim]) return ng;
    Vec3 n = s.normals[3 * prim] * (1.f - u - v) + s.normals[3 * prim + 1] * u + s.normals[3 * prim + 2] * v;
    if (pl.instanced) n = pl.normal_to_world.vector(n);
    const float nl = length(n);
    if (!(nl > 0.f)) return ng;
    n = n / nl;
    return dot(n, ng) < 0.f ? -n : n;  // keep shading and geometric normal on one side
}

uint32_t Scene::pass_index(const SurfaceHit& hit) const { return m_placements[hit.object].pass_index; }

bool Scene::intersect(const Ray& ray, SurfaceHit* hit, const PrimitiveRef& skip) const {
    QueryContext context;
    rtcInitIntersectContext(&context.context);
    const bool hidden = (m_hidden_from & ray.type) != 0;
    if (hidden || m_any_coplanar) {
        context.skip[0] = skip;
        context.scene = this;
        context.origin_magnitude = std::max({std::fabs(ray.o.x), std::fabs(ray.o.y), std::fabs(ray.o.z)});
        context.dir_length = length(ray.d);
    }
    if (hidden) {
        context.context.filter = &Scene::filter_hits;
        context.ray_type = ray.type;
        context.object_flags = m_object_flags.data();
    }
    RTCRayHit rh;
    rh.ray.org_x = ray.o.x;
    rh.ray.org_y = ray.o.y;
    rh.ray.org_z = ray.o.z;
    rh.ray.dir_x = ray.d.x;
    rh.ray.dir_y = ray.d.y;
    rh.ray.dir_z = ray.d.z;
    rh.ray.tnear = ray.tmin;
    rh.ray.tfar = ray.tmax;
    rh.ray.time = 0.f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = k_query_tag;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_top.get(), &context.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    // A filter widened tfar past the hit it kept (to compare coplanar rivals): that hit's own distance is best_t.
    // A later hit on an unfiltered object within the widened range is at tfar.
    const PrimitiveRef found{rh.hit.geomID, rh.hit.primID, rh.hit.instID[0]};
    const float t = context.have_best && found == context.best ? context.best_t : rh.ray.tfar;
    decode_hit(ray, rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.hit.u, rh.hit.v,
               Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), t, hit);
    return true;
}

void Scene::decode_hit(const Ray& ray, uint32_t geom, uint32_t prim, uint32_t inst, float u, float v,
                       const Vec3& ng_embree, float t, SurfaceHit* hit) const {
    const bool via_instance = inst != RTC_INVALID_GEOMETRY_ID;
    const uint32_t object = via_instance ? inst : geom;
    const Placement& pl = m_placements[object];
    const MeshShading& s = m_shading[pl.mesh];
    hit->primitive = {geom, prim, inst};
    hit->t = t;
    hit->p = ray.o + ray.d * t;
    Vec3 ng = ng_embree;
    if (pl.instanced) ng = pl.normal_to_world.vector(ng);
    if (pl.mirrored) ng = -ng;
    const float len = length(ng);
    hit->ng = len > 0.f ? ng / len : Vec3(0.f, 0.f, 1.f);
    hit->ns = shading_normal(s, pl, prim, u, v, hit->ng);
    hit->material = s.material[prim];
    hit->object = object;
    hit->b1 = u;
    hit->b2 = v;
    const int32_t rank = s.emissive_rank[prim];
    hit->light = (rank >= 0 && pl.light_base >= 0) ? pl.light_base + rank : -1;
}

void Scene::intersect_packet(const Ray* rays, int n, TracedHit* hits) const {
    if (n < 1 || n > k_packet_size) throw InternalError("intersect_packet: 1 to 8 rays");
    // Filters (objects hidden from this ray type, coplanar tie-breaks) are written for single rays.
    if (n == 1 || (m_hidden_from & rays[0].type) != 0 || m_any_coplanar) {
        for (int j = 0; j < n; ++j) hits[j].found = intersect(rays[j], &hits[j].hit);
        return;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(32) int valid[k_packet_size];
    alignas(32) RTCRayHit8 rh;
    for (int j = 0; j < k_packet_size; ++j) {
        const Ray& ray = rays[j < n ? j : 0];
        valid[j] = j < n ? -1 : 0;
        rh.ray.org_x[j] = ray.o.x;
        rh.ray.org_y[j] = ray.o.y;
        rh.ray.org_z[j] = ray.o.z;
        rh.ray.dir_x[j] = ray.d.x;
        rh.ray.dir_y[j] = ray.d.y;
        rh.ray.dir_z[j] = ray.d.z;
        rh.ray.tnear[j] = ray.tmin;
        rh.ray.tfar[j] = ray.tmax;
        rh.ray.time[j] = 0.f;
        rh.ray.mask[j] = 0xFFFFFFFFu;
        rh.ray.id[j] = k_query_tag;
        rh.ray.flags[j] = 0;
        rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, m_top.get(), &context, &rh);
    for (int j = 0; j < n; ++j) {
        hits[j].found = rh.hit.geomID[j] != RTC_INVALID_GEOMETRY_ID;
        if (hits[j].found)
            decode_hit(rays[j], rh.hit.geomID[j], rh.hit.primID[j], rh.hit.instID[0][j], rh.hit.u[j], rh.hit.v[j],
                       Vec3(rh.hit.Ng_x[j], rh.hit.Ng_y[j], rh.hit.Ng_z[j]), rh.ray.tfar[j], &hits[j].hit);
    }
}

bool Scene::occluded(const Vec3& o, const Vec3& d, float tmax, const PrimitiveRef& skip_from,
                     const PrimitiveRef& skip_to) const {
    // The scale-aware origin offset already keeps a shadow ray off its own surface: the skipped triangles matter
    // only to the coplanar objects' geometry filter (and to the context filter for hidden objects).
    QueryContext context;
    rtcInitIntersectContext(&context.context);
    context.skip[0] = skip_from;
    context.skip[1] = skip_to;
    if (m_hidden_from & k_ray_shadow) {
        context.ray_type = k_ray_shadow;
        context.object_flags = m_object_flags.data();
        context.context.filter = &Scene::filter_hits;
    }
    RTCRay r;
    r.org_x = o.x;
    r.org_y = o.y;
    r.org_z = o.z;
    r.dir_x = d.x;
    r.dir_y = d.y;
    r.dir_z = d.z;
    r.tnear = 0.f;
    r.tfar = tmax;
    r.time = 0.f;
    r.mask = 0xFFFFFFFFu;
    r.id = k_query_tag;
    r.flags = 0;
    rtcOccluded1(m_top.get(), &context.context, &r);
    return r.tfar < 0.f;  // Embree sets tfar = −inf on a hit
}

bool Scene::intersect_area_light(const Vec3& o, const Vec3& d, float tmin, float tmax, uint32_t* light, float* t,
                                 bool camera_ray) const {
    bool found = false;
    tmax *= 1.f + k_light_margin;
    for (uint32_t i : m_lights.area_lights()) {
        float th;
        const AreaLight& area = std::get<AreaLight>(m_lights[i]);
        if (camera_ray && !area.visible_camera) continue;
        if (area.intersect(o, d, tmin, tmax, &th)) {
            tmax = th;
            *light = i;
            *t = th;
            found = true;
        }
    }
    return found;
}

}  // namespace candela
