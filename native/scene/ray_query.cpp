#include "scene/ray_query.h"

namespace candela {

namespace {

void ray_query_filter(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const RayQueryContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const PrimitiveRef hit{RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i),
                               RTCHitN_instID(args->hit, args->N, i, 0)};
        if (hit == ctx->skip[0] || hit == ctx->skip[1]) {
            args->valid[i] = 0;
            continue;
        }
        if (ctx->ray_type != 0) {
            // Top-level geometry: the instance for instanced meshes, the flattened mesh otherwise.
            const uint32_t object = hit.inst != PrimitiveRef::k_none ? hit.inst : hit.geom;
            if ((ctx->object_flags[object] & ctx->ray_type) == 0) args->valid[i] = 0;
        }
    }
}

}  // namespace

void init_ray_query(RayQueryContext* c, const PrimitiveRef& skip_a, const PrimitiveRef& skip_b, uint8_t ray_type,
                    const uint8_t* object_flags, bool check_visibility) {
    rtcInitIntersectContext(&c->context);
    c->skip[0] = skip_a;
    c->skip[1] = skip_b;
    c->ray_type = check_visibility ? ray_type : 0;
    c->object_flags = object_flags;
    if (skip_a.valid() || skip_b.valid() || c->ray_type != 0) c->context.filter = &ray_query_filter;
}

}  // namespace candela
