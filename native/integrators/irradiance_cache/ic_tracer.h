// The irradiance cache integrator's paths (docs/irradiance_cache.md). Outgoing radiance at a camera path's vertex x
// is split by the BSDF's lobes, f = f_D + f_O with f_D the Lambertian lobes (reflectance ρ_D: what a cache of
// irradiance can serve) and f_O the others:
//
//   L_o(x) = L_e + L_direct (next-event estimation over f_D + f_O)
//          + ρ_D/π · E_ind(x, n)     (indirect irradiance: interpolated from the cache, or a new record's gather)
//          + ∫ f_O L_ind cos         (ray tracing on: one continuation sampled from f_O, with roulette)
//
// so specular and glossy paths are traced until they reach diffuse surfaces, where the cache takes over. Direct
// light is PATH's estimate over the whole BSDF — next-event estimation and the BSDF-sampled continuation combined by
// MIS (common/direct_light.h) — and the gathers leave out every light next-event estimation samples: the
// continuation is sampled from the whole BSDF, counts the light-sampled emission it finds with the whole BSDF's
// weight, and carries everything else (emitters no light sampling reaches, such as a constant world, and all that
// lies past its hit) with only the share of the lobes the cache does not serve.
//
// A record's gather (ic_hemisphere.h) traces each of its M × N rays on as a path: at the hit its full outgoing
// radiance by path tracing — emission (except, at the first hit, that of lights next-event estimation at x samples),
// next-event estimation with MIS and BSDF-sampled continuations with Russian roulette, by the shared rules of
// integrators/common — so a record holds all indirect light, not one bounce of it. With reuse_at_bounces (Radiance's
// way) a gather path's vertex on a Lambertian surface reads the cache instead where a record is usable there.
//
// The cache a pass reads is frozen (IcCache, const here): a camera path that finds no usable record makes one,
// uses its value at once and hands it to the pass's candidate list (the calling thread's sink), which the
// integrator merges in a fixed order after the pass. Every random number a path or a gather draws is a function of
// (seed, pixel, sample) or of the pre-pass grid point: images and records are the same for any thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "film/aov_film.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/irradiance_cache/ic_cache.h"
#include "integrators/irradiance_cache/ic_hemisphere.h"
#include "integrators/irradiance_cache/ic_settings.h"
#include "integrators/render_context.h"
#include "lights/light_sampler.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

/// Which part of the render a gather runs in (for tests that cancel in each: IcProbe).
enum class IcStage { Prepass, Render };

/// Test hooks, called from worker threads: before every gather ray is traced, and before every camera path.
struct IcProbe {
    std::function<void(IcStage)> on_gather_ray;
    std::function<void()> on_camera_path;
};

/// The world size of one pixel at distance t along a camera path (the image centre's pixel, pinhole): the unit of
/// the spacing clamps.
struct PixelFootprint {
    Vec3 d_origin{0.f}, d_dir{0.f};
    float at(float t) const { return length(d_origin + d_dir * t); }
    static PixelFootprint of(const Camera& camera);
};

class IcTracer {
public:
    IcTracer(const Scene& scene, const IcSettings& settings, const LightSampler& light_sampler, const IcCache& cache,
             const PixelFootprint& footprint, const CancelToken& cancel, const IcProbe* probe = nullptr);

    /// Radiance along a camera ray (CameraTilePass's tracer interface); records it makes go to the thread's sink.
    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov = nullptr) const;
    Color Li(const Ray& camera_ray, const TracedHit& first, Sampler& sampler, PathStats& stats, float* alpha,
             AovSample* aov = nullptr) const;

    /// Pre-pass: follows the ray through the centre of full-frame pixel (fx, fy) through delta surfaces to the first
    /// surface with Lambertian lobes; if no record is usable there, makes one into *record (gather seeded by `key`).
    bool prepass_record(int fx, int fy, uint64_t key, PathStats& stats, IcRecord* record) const;

    /// The record at vertex v of `hit`: the gather, R clamped by the spacing limits (min and max times `footprint`,
    /// the world size of a pixel on the surface there; no clamp if it is 0). Throws Cancelled.
    IcRecord make_record(const SurfaceHit& hit, const SurfaceVertex& v, float footprint, uint64_t key,
                         PathStats& stats) const;
    /// A pixel's world size on a surface of geometric normal ng met along d at path length `distance`.
    float surface_footprint(float distance, const Vec3& d, const Vec3& ng) const;

    void set_stage(IcStage stage) { m_stage = stage; }

    /// Where this thread's camera paths put the records they make (null: nowhere). Set around each work item.
    static void set_sink(std::vector<IcRecord>* sink);

    /// What a ray carries to the vertex it finds (public for the implementation's helpers).
    struct PathState {
        Color beta_emit{1.f};   // throughput of light-sampled emission the ray finds (the whole BSDF at its origin)
        Color beta{1.f};        // throughput of everything else (the lobes the cache did not serve there)
        EmissionOrigin origin;  // the scattering that made the ray (MIS at an emitter it finds)
        const DirectLightRules* rules = nullptr;  // the rules emission found by it is weighed with
        float eta_scale = 1.f;                    // Π η² (roulette only)
        PrimitiveRef from;
        float distance = 0.f;  // path length from the camera (camera paths)
    };
    enum class CachePolicy { Create, ReadIfValid, Never };
    /// The emitting triangles a ray of β = 0 must meet to bring back anything (active: no other light it can find).
    struct LightFilter {
        static constexpr size_t k_max_triangles = 32;  // beyond, tracing the ray costs less than testing them
        struct Triangle {
            Vec3 p0, e1, e2;
        };
        std::vector<Triangle> triangles;
        float t_margin = 0.f;
        bool active = false;
        static LightFilter of(const Scene& scene);
        /// Whether a ray from o along d may meet one of the triangles (false only where it certainly meets none;
        /// true when inactive).
        bool may_hit(const Vec3& o, const Vec3& d) const;
    };

private:
    template <class ConcreteSampler>
    void trace_camera(Ray ray, ConcreteSampler& sampler, PathStats& stats, Color& L, float* alpha, AovSample* aov,
                      const TracedHit* first) const;
    /// The radiance a gather ray brings back, and its first hit's distance (∞ if it escaped).
    Color trace_gather(const Ray& ray, const PathState& start, uint64_t key, PathStats& stats, float* distance) const;
    /// The vertex at `hit`: next-event estimation, the cache's part, the continuation. True with `ray`/`st` set to
    /// the continuation; false when the path ends here.
    template <class Draw, class RecordKey>
    bool scatter(const SurfaceHit& hit, const ShadingPoint& sp, Ray& ray, PathState& st, int bounce, CachePolicy policy,
                 Draw&& draw, PathStats& stats, Color& L, RecordKey&& record_key, int px, int py) const;
    void add_emission(const PathState& st, const Color& Le, float light_pdf, Color& L) const;
    void add_area_light_emission(const Ray& ray, float t_surface, bool camera_ray, const PathState& st, Color& L) const;
    void add_world_emission(const Ray& ray, const PathState& st, Color& L) const;
    float emitter_pdf(const PathState& st, int32_t light, const Vec3& d, float t) const;
    /// Whether a ray of β = 0 from o along d may find a light (false only where it certainly finds none).
    bool may_find_light(const Vec3& o, const Vec3& d) const;
    /// A camera path's lookup at (x, n) in pixel (px, py), a pixel's footprint from its point: through the pixel's
    /// candidates where x is near the pixel's anchor (ic_tracer.cpp), else the octree.
    bool camera_lookup(const Vec3& x, const Vec3& n, float footprint, int px, int py, Color* E) const;
    /// Whether the ray that found `hit` can bring back nothing more from it (no light there, β = 0).
    bool only_light_emission(const PathState& st, const SurfaceHit& hit) const;
    void poll_gather() const;

    const Scene& m_scene;
    const IcSettings& m_settings;
    const LightSampler& m_light_sampler;
    const IcCache& m_cache;
    PixelFootprint m_footprint;
    const CancelToken& m_cancel;
    const IcProbe* m_probe;
    GatherStrata m_strata;
    DirectLightRules m_rules;           // next-event estimation and MIS everywhere
    DirectLightRules m_rules_gathered;  // a gather ray's first segment: LIGHT_ONLY (light sampling at x covers it)
    LightFilter m_light_filter;
    IcStage m_stage = IcStage::Prepass;
};

}  // namespace candela
