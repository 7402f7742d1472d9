#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "bsdf/material_inputs.h"
#include "scene/coplanar_overlap.h"
#include "scene/mesh_bvh_cache.h"
#include "input/scene_arrays.h"
#include "scene/scene_parts.h"

namespace candela {

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

bool progress_monitor(void* ptr, double) {
    const auto* cancel = static_cast<const CancelToken*>(ptr);
    return !(cancel && cancel->cancelled());
}

struct MeshRange {
    uint32_t tri_begin, tri_end, vert_begin, vert_end;
};

}  // namespace

Scene::Scene(const SceneArrays& arrays, const Params& params, const CancelToken* cancel, MeshBvhCache* cache)
    : m_device(cache ? cache->device() : std::make_shared<EmbreeDevice>(params.get<int>("threads", 0))),
      m_camera(params, camera_matrix(arrays)) {
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
    build(arrays, cancel, cache);
}

void Scene::set_camera(const Params& params, const Affine& camera_to_world) {
    Camera camera(params, camera_to_world);
    camera.translate(m_offset);  // into the camera-world space the scene was built in
    m_camera = camera;
}

Scene::~Scene() = default;

void Scene::build(const SceneArrays& arrays, const CancelToken* cancel, MeshBvhCache* cache) {
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
        RTCGeometry g = rtcNewGeometry(m_device->get(), RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);  // the object's own BVH (see the top scene below)
        const size_t nv = r.vert_end - r.vert_begin, nt = r.tri_end - r.tri_begin;
        auto* vb = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
        auto* ib = static_cast<uint32_t*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
        m_device->check("allocating geometry buffers");
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

    m_top = EmbreeScene(rtcNewScene(m_device->get()));
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
        if (uses[m] == 1 && !cache) {
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
                // What the BVH depends on besides the vertices and triangles: the filters set on it.
                const uint32_t bvh_flags = uint32_t(scene_flags) << 1 | uint32_t(mesh_coplanar[m] != 0);
                const MeshRange& r = ranges[m];
                const MeshBvhCache::Key key =
                    cache ? MeshBvhCache::key(positions + 3 * size_t(r.vert_begin), r.vert_end - r.vert_begin,
                                              triangles + 3 * size_t(r.tri_begin), r.tri_end - r.tri_begin,
                                              r.vert_begin, bvh_flags)
                          : MeshBvhCache::Key{};
                std::shared_ptr<EmbreeScene> s = cache ? cache->find(key) : nullptr;
                if (!s) {
                    s = std::make_shared<EmbreeScene>(rtcNewScene(m_device->get()));
                    rtcSetSceneBuildQuality(s->get(), RTC_BUILD_QUALITY_HIGH);
                    rtcSetSceneFlags(s->get(), scene_flags);
                    rtcSetSceneProgressMonitorFunction(s->get(), &progress_monitor, const_cast<CancelToken*>(cancel));
                    float unused = 0.f;
                    RTCGeometry g = make_geometry(m, Affine(), &unused, mesh_coplanar[m] != 0);
                    rtcAttachGeometry(s->get(), g);
                    rtcReleaseGeometry(g);
                    rtcCommitScene(s->get());
                    // The cancel token belongs to this build: a kept BVH must not point at it.
                    rtcSetSceneProgressMonitorFunction(s->get(), nullptr, nullptr);
                    if (cancel && cancel->cancelled()) throw Cancelled();
                    m_device->check("building a mesh BVH");
                    if (cache) cache->insert(key, s);
                }
                mesh_scene[m] = static_cast<int32_t>(m_mesh_scenes.size());
                m_mesh_scenes.push_back(std::move(s));
                m_stats.unique_triangles += n;
                ++m_stats.meshes;
            }
            RTCGeometry inst = rtcNewGeometry(m_device->get(), RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, m_mesh_scenes[mesh_scene[m]]->get());
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &xf.m[0][0]);
            rtcCommitGeometry(inst);
            const unsigned id = rtcAttachGeometry(m_top.get(), inst);
            rtcReleaseGeometry(inst);
            pl.instanced = true;
            pl.normal_to_world = xf.normal_matrix();
            pl.light_base = add_triangle_lights(m, xf, m_shading[m], pl, id);
            // Camera-world magnitude of the instance: its object-space bounds' corners, transformed.
            RTCBounds ob;
            rtcGetSceneBounds(m_mesh_scenes[mesh_scene[m]]->get(), &ob);
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
    m_device->check("building the scene BVH");

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
    m_stats.embree_bytes = size_t(std::max<int64_t>(m_device->bytes(), 0));
}

}  // namespace candela
