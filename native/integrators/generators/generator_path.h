// One camera sample of the path generators (generator_tracer.h): the walks and the three generators' estimates,
// accumulated into L. Private to the generators' folder.
#pragma once

#include <optional>
#include <vector>

#include "integrators/common/surface_vertex.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/generators/generator_tracer.h"

namespace candela {

class GeneratorPath {
public:
    GeneratorPath(const GeneratorTracer& tracer, Sampler& sampler, PathStats& stats)
        : m_t(tracer), m_cfg(tracer.m_settings), m_sampler(sampler), m_stats(stats) {}

    /// The radiance the camera ray brings (its alpha and data passes set as the path tracer sets them).
    Color run(const Ray& camera_ray, float* alpha, AovSample* aov);

private:
    /// A receiver: a vertex reached from the camera by delta scattering only (or through a delta chain after a
    /// generator's vertex) that scatters non-delta; `n` is its index among the path's scattering vertices.
    struct Receiver {
        const VertexBsdf* vertex;
        Vec3 wo;
        Color beta;
        int n;
    };
    /// The path y → z → x being estimated, when a ray or a light sample completes a one-bounce path in the
    /// generators_mis mode (the weight is generator's).
    struct OneBounceRef {
        const VertexBsdf* x = nullptr;
        Vec3 wo_x{0.f};
        const VertexBsdf* z = nullptr;
        PathGenerator generator = PathGenerator::ReceiverGathering;
    };
    /// What produced a ray: what the emitter it finds is weighted by.
    struct RayOrigin {
        EmissionOrigin e;         // specular (camera ray, delta scattering): weight 1; else MIS against the NEE there
        bool gathered = false;    // it left a gathered point: light-only next-event estimation happened there
        OneBounceRef one_bounce;  // set when its emitter ends a one-bounce path (generators_mis)
        PrimitiveRef from;
    };
    /// A stored vertex of the light path (source shooting).
    struct LightVertex {
        SurfaceHit hit;
        ShadingPoint sp;  // the light side's
        Vec3 w_l;
        Color beta;
        int depth;
    };

    // Walks (generator_path.cpp).
    void receiver_walk(Ray ray, Color beta, int n, RayOrigin origin, bool camera, float* alpha, AovSample* aov);
    void at_receiver(const Receiver& r, const SurfaceHit& hit, const SurfaceVertex& v, SpawnPoints& spawn,
                     const BounceSample& u, int* ward_tested);
    void passed_vertex(const Ray& ray, const Color& beta, int n, const RayOrigin& origin, const Receiver* r,
                       bool chains);
    void gather_walk(Ray ray, Color beta, int n, RayOrigin origin, const Receiver& r);
    /// Traces `ray` and adds the emission it finds (area lights on the way, the surface it hits, the world).
    /// Returns whether it hit a surface (then *hit is set).
    bool trace_emission(const Ray& ray, const Color& beta, const RayOrigin& origin, bool camera, SurfaceHit* hit,
                        ShadingPoint* sp, float* alpha, AovSample* aov);
    float emitter_weight(const RayOrigin& o, int light, int emitter, const Vec3& d, float t, const Vec3& n) const;
    /// Light-only next-event estimation at a gathered point z (one_bounce: the path's MIS weight, else 1).
    void gathered_direct(const VertexBsdf& z, const Vec3& w_c, const SurfaceVertex& v, SpawnPoints& spawn,
                         const Color& beta, const BounceSample& u, const OneBounceRef& one_bounce);

    // Source shooting (source_shooting.cpp).
    void connect_light_path(const Receiver& r, bool one_bounce_only);
    void build_light_path();
    // Surface sampling (surface_sampling.cpp).
    void surface_indirect(const VertexBsdf& from, const Vec3& wo, const Color& beta, int n, const Receiver* r,
                          bool one_bounce_only);
    void gathered_point(const VertexBsdf& z, const Vec3& w_c, const Color& beta, int n, const Receiver* r,
                        bool one_bounce_only);

    BounceSample draw(int slot, unsigned needs);
    /// The sample slot of vertex n's role: 0 its own scattering and next-event estimation, 1 a surface point drawn
    /// from it, 2 that point's scattering.
    static int slot(int n, int role) { return 3 * n + role; }
    Ray continuation_ray(const SurfaceVertex& v, SpawnPoints& spawn, const BsdfSample& bs, uint8_t previous_type) const;

    const GeneratorTracer& m_t;
    const GeneratorSettings& m_cfg;
    Sampler& m_sampler;
    PathStats& m_stats;
    Color m_L{0.f};
    bool m_light_path_built = false;
    std::vector<LightVertex> m_light_path;
    struct {
        int emitter = -1;
        Vec3 p{0.f}, n{0.f};
        bool infinite = false;
    } m_light_origin;
};

}  // namespace candela
