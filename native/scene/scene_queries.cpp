// Scene queries: closest hits (one ray, or a packet of camera rays), occlusion, area-light hits, and the Embree
// filters that hide objects from ray types and break ties between coplanar surfaces. The scene is built in
// scene.cpp.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/coplanar_overlap.h"
#include "scene/scene_parts.h"
#include "scene/shutter_time.h"

namespace candela {

/// Embree's per-query context plus what filter_hits needs. It runs as the context filter (every candidate hit) for
/// ray types some object is hidden from, and otherwise as the geometry filter of the objects with a coplanar rival.
struct Scene::QueryContext {
    RTCIntersectContext context;
    PrimitiveRef skip[2];
    const Scene* scene = nullptr;           // set for closest-hit queries: coplanar ties are broken
    uint8_t ray_type = 0;                   // RayType bits checked against object_flags; 0 = no visibility check
    const uint8_t* object_flags = nullptr;  // per top-level geometry id (ObjectFlag bits)
    float origin_magnitude = 0.f, dir_length = 1.f;
    bool have_best = false;
    float best_t = 0.f, best_tolerance = 0.f;
    PrimitiveRef best;
};

namespace {

uint32_t top_level_id(const PrimitiveRef& h) { return h.inst != PrimitiveRef::k_none ? h.inst : h.geom; }

/// Marks the rays Scene shoots (RTCRay::id): their context is a QueryContext. Raw queries through embree_scene()
/// leave id 0 and pass the geometry filters untouched.
constexpr unsigned k_query_tag = 0x43414E44u;  // "CAND"
/// Area lights count up to this relative distance behind a surface: the shadow rays' margin (1 − 1e-4).
constexpr float k_light_margin = 1e-4f;

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
        const float plane_tolerance = k_coplanar_ulps * (ctx->origin_magnitude + t * ctx->dir_length + pl.magnitude);
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
    rh.ray.time = ray_time();
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
    const auto decode = [&](const Placement& pl) __attribute__((always_inline)) {
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
    };
    // placement_now, with the scratch copy declared only for a moving object: GCC 12 zero-fills an empty
    // std::optional<Placement>'s whole storage where it is declared (~25 instructions on every hit).
    const Placement& stored = m_placements[object];
    if (__builtin_expect(stored.motion < 0, 1)) {
        decode(stored);
    } else {
        std::optional<Placement> moved;
        decode(placement_now(object, moved));  // a moving object's at the ray's (thread's) shutter time
    }
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
        rh.ray.time[j] = ray_time();
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

bool Scene::occluded(const Vec3& o, const Vec3& d, float tmax, RayType type, const PrimitiveRef& skip_from,
                     const PrimitiveRef& skip_to) const {
    // The scale-aware origin offset already keeps a shadow ray off its own surface: the skipped triangles matter
    // only to the coplanar objects' geometry filter (and to the context filter for hidden objects).
    QueryContext context;
    rtcInitIntersectContext(&context.context);
    context.skip[0] = skip_from;
    context.skip[1] = skip_to;
    if (m_hidden_from & type) {
        context.ray_type = type;
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
    r.time = ray_time();
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
