#include "integrators/irradiance_cache/ic_tracer.h"

#include <cmath>
#include <limits>
#include <new>
#include <type_traits>
#include <variant>

#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "integrators/camera_hit.h"
#include "integrators/common/roulette.h"
#include "integrators/irradiance_cache/ic_hemisphere.h"
#include "integrators/irradiance_cache/ic_lobe_split.h"
#include "integrators/ray_types.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

thread_local std::vector<IcRecord>* t_sink = nullptr;

// In-pass reuse: the records the current pixel's samples made in this pass, which its later samples of the pass
// read where the frozen cache has none (a pass's samples of one pixel run in a fixed order on one thread, so what
// a sample sees depends neither on the threads nor on the tiles). Without it every sample of a pass that lands in
// a gap between the cache's records would gather its own record there, and the merge keep one.
//
// The same pixel's samples mostly meet the same surface within a few pixel footprints: a lookup of a pixel (in a
// pass) that is near none of the pixel's anchors makes its point an anchor — it collects the records whose spheres
// come within two footprints of it — and the later lookups closer than that to an anchor test only its candidates:
// the records and the order a full query would visit, so the same value, for a fraction of the octree walk. Two
// anchors, the older replaced by a third, serve a pixel that sees two surfaces (a silhouette, an edge).
struct PixelAnchor {
    Vec3 at{0.f};
    float range = -1.f;  // < 0: unused
    std::vector<uint32_t> candidates;
};
struct PixelRecords {
    static constexpr int k_anchors = 2;
    int px = -1, py = -1;
    std::vector<IcRecord> records;
    PixelAnchor anchors[k_anchors];
    int next = 0;  // the anchor a new one replaces
    void reset(int x, int y) {
        px = x;
        py = y;
        records.clear();
        for (PixelAnchor& a : anchors) a.range = -1.f;
        next = 0;
    }
};
thread_local PixelRecords t_pixel;

}  // namespace

void IcTracer::set_sink(std::vector<IcRecord>* sink) {
    t_sink = sink;
    t_pixel.reset(-1, -1);
}

bool IcTracer::camera_lookup(const Vec3& x, const Vec3& n, float footprint, int px, int py, Color* E) const {
    if (t_pixel.px != px || t_pixel.py != py) t_pixel.reset(px, py);
    // 0.99: a margin against rounding in the candidates' own distance test.
    for (const PixelAnchor& a : t_pixel.anchors)
        if (a.range > 0.f && length_squared(x - a.at) < sqr(0.99f * a.range))
            return m_cache.interpolate_among(a.candidates, x, n, E);
    if (!(footprint > 0.f) || !std::isfinite(footprint)) return m_cache.interpolate(x, n, E);
    PixelAnchor& a = t_pixel.anchors[t_pixel.next];
    t_pixel.next = (t_pixel.next + 1) % PixelRecords::k_anchors;
    a.at = x;
    a.range = 2.f * footprint;
    a.candidates.clear();
    m_cache.candidates_near(x, a.range, &a.candidates);
    return m_cache.interpolate_among(a.candidates, x, n, E);
}

IcTracer::IcTracer(const Scene& scene, const IcSettings& settings, const LightSampler& light_sampler,
                   const IcCache& cache, const PixelFootprint& footprint, const CancelToken& cancel,
                   const IcProbe* probe)
    : m_scene(scene),
      m_settings(settings),
      m_light_sampler(light_sampler),
      m_cache(cache),
      m_footprint(footprint),
      m_cancel(cancel),
      m_probe(probe),
      m_strata(GatherStrata::for_rays(settings.gather_rays)),
      m_rules(settings.direct),
      m_rules_gathered(settings.direct),
      m_light_filter(LightFilter::of(scene)) {
    m_rules_gathered.light_sampling = LightSampling::LightOnly;
}

// ---------------------------------------------------------------------------------------------------------------
// Emission found by a ray (the shared MIS rules, with the ray's own rule set: a gather ray's first segment weighs
// the lights next-event estimation samples with 0).

float IcTracer::emitter_pdf(const PathState& st, int32_t light, const Vec3& d, float t) const {
    return nee_density(*st.rules, m_light_sampler, m_scene.lights(), st.origin, uint32_t(light), d, t);
}

void IcTracer::add_emission(const PathState& st, const Color& Le, float light_pdf, Color& L) const {
    // A light next-event estimation samples (light_pdf > 0) is direct light of the whole BSDF at the ray's origin,
    // MIS-weighted; any other emitter (a constant world, a never-selected triangle) is indirect light to the gathers
    // there, which already hold the Lambertian lobes' share of it: the ray counts only the rest's (β).
    L += (light_pdf > 0.f ? st.beta_emit : st.beta) * Le * emission_weight(*st.rules, st.origin, light_pdf);
}

void IcTracer::add_area_light_emission(const Ray& ray, float t_surface, bool camera_ray, const PathState& st,
                                       Color& L) const {
    const LightSet& lights = m_scene.lights();
    if (lights.area_lights().empty()) return;
    uint32_t li;
    float tl;
    if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, t_surface, &li, &tl, camera_ray)) {
        const auto& area = std::get<AreaLight>(lights[li]);
        add_emission(st, area.radiance, emitter_pdf(st, int32_t(li), ray.d, tl), L);
    }
}

void IcTracer::add_world_emission(const Ray& ray, const PathState& st, Color& L) const {
    const LightSet& lights = m_scene.lights();
    if (const WorldLight* world = lights.world())
        add_emission(st, world->Le(ray.d), emitter_pdf(st, int32_t(lights.world_light()), ray.d, k_inf), L);
    else if (!is_black(lights.background()))
        add_emission(st, lights.background(), 0.f, L);  // a constant world: never light-sampled, weight 1
}

bool IcTracer::only_light_emission(const PathState& st, const SurfaceHit& hit) const {
    // With β = 0 (the cache served every lobe at the ray's origin) the ray counts only the emission of a light
    // next-event estimation samples (β_emit, add_emission); a surface that is no light adds β·L_e = 0 and the path
    // ends there, so its shading need not be evaluated.
    return hit.light < 0 && is_black(st.beta);
}

IcTracer::LightFilter IcTracer::LightFilter::of(const Scene& scene) {
    // Only where every light a ray can find is one of a few emitting triangles: no world light (an escaping ray
    // would find it), no analytic area light (found by its own intersection), no motion (the triangles move).
    LightFilter f;
    if (scene.has_motion()) return f;
    for (size_t i = 0; i < scene.lights().size(); ++i) {
        const Light& light = scene.lights()[uint32_t(i)];
        if (std::holds_alternative<AreaLight>(light) || std::holds_alternative<WorldLight>(light)) return f;
        if (const auto* tri = std::get_if<TriangleLight>(&light)) {
            if (f.triangles.size() == k_max_triangles) return f;
            f.triangles.push_back({tri->p0, tri->p1 - tri->p0, tri->p2 - tri->p0});
        }
    }
    f.active = true;
    f.t_margin = 1e-3f * std::max(scene.bounds().radius, 1e-6f);
    return f;
}

bool IcTracer::LightFilter::may_hit(const Vec3& o, const Vec3& d) const {
    // A ray of β = 0 can bring back only the emission of a light next-event estimation samples (add_emission): if
    // it meets none of the emitting triangles — the Möller–Trumbore test, widened by a margin in the barycentrics
    // and the distance so that no hit the scene's own intersection finds is missed — it brings back nothing and
    // need not be traced. (Whether something occludes the light is left to the traced ray.)
    if (!active) return true;
    constexpr float tol = 1e-3f;
    for (const Triangle& tri : triangles) {
        const Vec3 pv = cross(d, tri.e2);
        const float det = dot(tri.e1, pv);
        if (!(std::fabs(det) > 1e-20f)) return true;  // edge-on or degenerate: leave it to the scene
        const float inv = 1.f / det;
        const Vec3 tv = o - tri.p0;
        const float u = dot(tv, pv) * inv;
        if (!(u >= -tol && u <= 1.f + tol)) continue;
        const Vec3 qv = cross(tv, tri.e1);
        const float v = dot(d, qv) * inv;
        if (!(v >= -tol && u + v <= 1.f + tol)) continue;
        if (dot(tri.e2, qv) * inv > -t_margin) return true;
    }
    return false;
}

bool IcTracer::may_find_light(const Vec3& o, const Vec3& d) const { return m_light_filter.may_hit(o, d); }

void IcTracer::poll_gather() const {
    if (m_probe && m_probe->on_gather_ray) m_probe->on_gather_ray(m_stage);
    if (m_cancel.cancelled()) throw Cancelled();
}

// ---------------------------------------------------------------------------------------------------------------
// A vertex.

template <class Draw, class RecordKey>
bool IcTracer::scatter(const SurfaceHit& hit, const ShadingPoint& sp, Ray& ray, PathState& st, int bounce,
                       CachePolicy policy, Draw&& draw, PathStats& stats, Color& L, RecordKey&& record_key, int px,
                       int py) const {
    const Vec3 wo = -ray.d;
    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
    const Vec3 wo_local = v.frame.to_local(wo);
    const Bsdf& bsdf = sp.bsdf();
    SpawnPoints spawn(hit.p, v.ng);
    const LightSet& lights = m_scene.lights();

    // The cache's part: the Lambertian lobes' indirect light from the records (or a new one), if this vertex uses
    // the cache at all; the other lobes are traced on.
    // Only where the cache may serve this vertex; in raw storage, since GCC's std::optional zeroes all of its
    // ~1 KB at construction (the BSDF copies a mixed split needs), a sixth of a camera vertex's own instructions.
    static_assert(std::is_trivially_destructible_v<LobeSplit>);
    alignas(LobeSplit) unsigned char split_storage[sizeof(LobeSplit)];
    const LobeSplit* split = policy != CachePolicy::Never ? new (split_storage) LobeSplit(bsdf) : nullptr;
    Color E(0.f);
    bool cached = false;
    if (split && !is_black(split->rho_d) && wo_local.z > 0.f) {
        const bool camera = policy == CachePolicy::Create && t_sink;
        if (camera ? camera_lookup(hit.p, v.frame.n, m_footprint.at(st.distance), px, py, &E)
                   : m_cache.interpolate(hit.p, v.frame.n, &E)) {
            cached = true;
        } else if (policy == CachePolicy::Create) {
            if (t_pixel.px != px || t_pixel.py != py) t_pixel.reset(px, py);
            if (IcCache::interpolate_list(t_pixel.records, m_cache.rules(), hit.p, v.frame.n, &E)) {
                cached = true;
            } else {
                IcRecord rec = make_record(hit, v, surface_footprint(st.distance, ray.d, hit.ng), record_key(), stats);
                rec.pixel_x = px;
                rec.pixel_y = py;
                E = rec.E;  // its value at its own point: what the cache would give here once it holds it
                cached = true;
                if (t_sink) {
                    t_sink->push_back(rec);
                    t_pixel.records.push_back(rec);
                }
            }
        }
    }

    const bool nee_here = !lights.empty() && bsdf.has_non_delta();
    const bool roulette_here = bounce + 1 >= m_settings.rr_start_bounce;
    const bool discrete_here = bsdf.size() > 1 || (bsdf.flags() & k_bsdf_transmission);
    const unsigned needs = (nee_here && !m_light_sampler.exhaustive() ? k_need_light_select : 0u) |
                           (nee_here ? k_need_light : 0u) | (roulette_here ? k_need_roulette : 0u) |
                           (discrete_here ? k_need_lobe : 0u);
    const BounceSample u = draw(needs);

    // Direct light over the whole BSDF, next-event estimation and BSDF sampling combined by MIS exactly as PATH
    // (common/direct_light.h); the BSDF-sampled half is the continuation ray below, which therefore always
    // leaves, whichever lobe it samples. (Next-event estimation alone where the cache served every lobe would save
    // that ray, but doubled the Cornell box's relative RMSE at 256 samples: the ceiling beside the light, where
    // light sampling alone is poor, carries most of the squared error.)
    const LightSampleContext ctx{hit.p, v.ns};
    int ward_tested = 0;
    if (nee_here) {
        ward_tested = next_event_estimation(
            m_rules, m_light_sampler, lights, ctx, u.light_select, u.light, [&](uint32_t li, float pmf, Vec2 u_li) {
                const DirectLightSample d = sample_direct_light(
                    m_scene, m_rules, hit, v, spawn, ctx, bsdf, wo_local, st.beta, li, pmf, u_li,
                    [&](const Vec3& wi) { return bsdf.pdf(wo_local, wi); }, stats.rays);
                L += d.contribution;
                return d.visible;
            });
    }
    if (cached) L += st.beta * split->rho_d * E * k_inv_pi;

    // The continuation, sampled from the whole BSDF (density p): the emission it finds carries β·f·|cos|/p (direct
    // light's BSDF-sampled estimate); everything past it only f_O's share, β·f_O·|cos|/p, where the cache served
    // the Lambertian lobes' indirect light (both estimates unbiased: p > 0 wherever f_O > 0).
    const BsdfSample bs = bsdf.sample(wo_local, u.bsdf, u.lobe);
    if (!bs.valid() || is_black(bs.f)) return false;
    const Vec3 wi = v.frame.to_world(bs.wi);
    const float cos_g = dot(wi, v.ng);
    if (leaks(cos_g, bs.wi.z)) return false;
    const float weight = std::fabs(bs.wi.z) / bs.pdf;
    Color beta_emit = st.beta * bs.f * weight;
    Color beta = beta_emit;
    if (cached && !bs.is_delta())
        beta = split->other->empty() ? Color(0.f) : st.beta * split->other->f(wo_local, bs.wi) * weight;
    const float eta_scale = st.eta_scale * (bs.is_transmission() ? bs.eta * bs.eta : 1.f);
    if (roulette_here) {
        const float survive =
            continuation_survival(RouletteMode::Throughput, beta_emit, 1, eta_scale, [] { return Color(1.f); });
        if (!(survive > 0.f) || u.roulette >= survive) return false;
        beta_emit /= survive;
        beta /= survive;
    }
    if (is_black(beta_emit) || !is_finite(beta_emit) || !is_finite(beta)) return false;
    const Vec3 origin = spawn.origin(cos_g > 0.f);
    if (is_black(beta) && !bs.is_delta() && !may_find_light(origin, wi)) return false;
    st.beta_emit = beta_emit;
    st.beta = beta;
    st.eta_scale = eta_scale;
    st.origin.specular = bs.is_delta();
    st.origin.bsdf_pdf = bs.pdf;
    st.origin.point = ctx;
    st.origin.ward_tested = ward_tested;
    st.rules = &m_rules;
    st.from = hit.primitive;
    ray = Ray{origin, wi, 0.f, k_inf, continuation_ray_type(bs, ray.type)};
    return true;
}

// ---------------------------------------------------------------------------------------------------------------
// Camera paths.

Color IcTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov) const {
    Color L(0.f);
    *alpha = 1.f;
    std::visit([&](auto& concrete) { trace_camera(camera_ray, concrete, stats, L, alpha, aov, nullptr); }, sampler);
    return L;
}

Color IcTracer::Li(const Ray& camera_ray, const TracedHit& first, Sampler& sampler, PathStats& stats, float* alpha,
                   AovSample* aov) const {
    Color L(0.f);
    *alpha = 1.f;
    std::visit([&](auto& concrete) { trace_camera(camera_ray, concrete, stats, L, alpha, aov, &first); }, sampler);
    return L;
}

template <class ConcreteSampler>
void IcTracer::trace_camera(Ray ray, ConcreteSampler& sampler, PathStats& stats, Color& L, float* alpha, AovSample* aov,
                            const TracedHit* first) const {
    if (m_probe && m_probe->on_camera_path) m_probe->on_camera_path();
    PathState st;
    st.rules = &m_rules;  // a camera ray: emission counts with weight 1 (origin.specular)
    const int px = int(sampler.pixel_x()), py = int(sampler.pixel_y());
    for (int bounce = 0;; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        bool found;
        if (first) {
            found = first->found;
            if (found) hit = first->hit;
            first = nullptr;
        } else {
            found = m_scene.intersect(ray, &hit, st.from);
        }
        add_area_light_emission(ray, found ? hit.t : ray.tmax, bounce == 0, st, L);
        if (!found) {
            if (bounce == 0 && m_settings.pixel.film_transparent)
                *alpha = 0.f;
            else
                add_world_emission(ray, st, L);
            return;
        }
        if (bounce == 0 && !camera_hit(m_scene, ray, hit, aov, alpha)) return;  // data passes, holdout
        if (only_light_emission(st, hit)) return;
        const ShadingPoint sp = m_scene.shade(hit, -ray.d);
        if (!is_black(sp.emission))
            add_emission(st, sp.emission, hit.light >= 0 ? emitter_pdf(st, hit.light, ray.d, hit.t) : 0.f, L);
        if (bounce > m_settings.max_bounces || is_black(st.beta)) return;
        st.distance += hit.t;
        auto draw = [&](unsigned needs) { return draw_bounce(sampler, bounce, needs); };
        // The record key (seed, pixel, sample, bounce) is hashed only if the vertex makes a record.
        const auto record_key = [&] { return hash_combine(sampler.sample_stream_key(), uint64_t(bounce)); };
        if (!scatter(hit, sp, ray, st, bounce, CachePolicy::Create, draw, stats, L, record_key, px, py)) return;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Gathers.

Color IcTracer::trace_gather(const Ray& first_ray, const PathState& start, uint64_t key, PathStats& stats,
                             float* distance) const {
    Pcg32 rng(key, 0x676174686572ULL /* "gather" */);
    Ray ray = first_ray;
    PathState st = start;
    Color L(0.f);
    *distance = k_inf;
    const CachePolicy policy = m_settings.reuse_at_bounces ? CachePolicy::ReadIfValid : CachePolicy::Never;
    for (int bounce = 1;; ++bounce) {  // the record's vertex is bounce 0
        SurfaceHit hit;
        ++stats.rays;
        const bool found = m_scene.intersect(ray, &hit, st.from);
        add_area_light_emission(ray, found ? hit.t : ray.tmax, false, st, L);
        if (!found) {
            add_world_emission(ray, st, L);
            return L;
        }
        if (bounce == 1) *distance = hit.t;
        if (only_light_emission(st, hit)) return L;
        const ShadingPoint sp = m_scene.shade(hit, -ray.d);
        if (!is_black(sp.emission))
            add_emission(st, sp.emission, hit.light >= 0 ? emitter_pdf(st, hit.light, ray.d, hit.t) : 0.f, L);
        if (bounce > m_settings.max_bounces || is_black(st.beta)) return L;
        auto draw = [&](unsigned) {
            BounceSample b;
            b.light_select = rng.next_float();
            b.light = {rng.next_float(), rng.next_float()};
            b.bsdf = {rng.next_float(), rng.next_float()};
            b.roulette = rng.next_float();
            b.lobe = rng.next_float();
            return b;
        };
        if (!scatter(
                hit, sp, ray, st, bounce, policy, draw, stats, L, [] { return uint64_t(0); }, -1, -1))
            return L;
    }
}

}  // namespace candela
