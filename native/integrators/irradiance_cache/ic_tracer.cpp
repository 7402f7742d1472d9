#include "integrators/irradiance_cache/ic_tracer.h"

#include <cmath>
#include <limits>
#include <new>
#include <optional>
#include <type_traits>
#include <variant>

#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "integrators/camera_hit.h"
#include "integrators/common/roulette.h"
#include "integrators/irradiance_cache/ic_hemisphere.h"
#include "integrators/ray_types.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

thread_local std::vector<IcRecord>* t_sink = nullptr;

const Bsdf& empty_bsdf() {
    static const Bsdf empty;
    return empty;
}

/// A BSDF split into its Lambertian lobes (reflectance rho_d; what the cache serves) and the others. The common
/// cases — all Lambertian, none Lambertian — refer to the BSDF itself instead of copying it; only a mixed BSDF is
/// copied (into raw storage: a default-constructed Bsdf would cost its lobe array's initialisation at every vertex).
class LobeSplit {
public:
    Color rho_d{0.f};
    const Bsdf* diffuse = nullptr;
    const Bsdf* other = nullptr;

    explicit LobeSplit(const Bsdf& b) {
        int lambert = 0;
        for (int i = 0; i < b.size(); ++i)
            if (std::holds_alternative<LambertBsdf>(b[i].lobe)) {
                ++lambert;
                rho_d += b[i].weight;
            }
        if (lambert == 0) {
            diffuse = &empty_bsdf();
            other = &b;
        } else if (lambert == b.size()) {
            diffuse = &b;
            other = &empty_bsdf();
        } else {
            Bsdf* d = new (m_storage[0]) Bsdf();
            Bsdf* o = new (m_storage[1]) Bsdf();
            for (int i = 0; i < b.size(); ++i) (std::holds_alternative<LambertBsdf>(b[i].lobe) ? d : o)->add(b[i].lobe, b[i].weight);
            diffuse = d;
            other = o;
        }
    }

private:
    static_assert(std::is_trivially_destructible_v<Bsdf>, "LobeSplit keeps BSDFs in raw storage");
    alignas(Bsdf) unsigned char m_storage[2][sizeof(Bsdf)];
};

}  // namespace

PixelFootprint PixelFootprint::of(const Camera& camera) {
    const Vec2 c{0.5f * float(camera.full_width()), 0.5f * float(camera.full_height())};
    const Ray r0 = camera.generate_ray(c), r1 = camera.generate_ray({c.x + 1.f, c.y});
    PixelFootprint f;
    f.d_origin = r1.o - r0.o;
    f.d_dir = r1.d - r0.d;
    return f;
}

void IcTracer::set_sink(std::vector<IcRecord>* sink) { t_sink = sink; }

IcTracer::IcTracer(const Scene& scene, const IcSettings& settings, const LightSampler& light_sampler,
                   const IcCache& cache, const PixelFootprint& footprint, const CancelToken& cancel,
                   const IcProbe* probe)
    : m_scene(scene), m_settings(settings), m_light_sampler(light_sampler), m_cache(cache), m_footprint(footprint),
      m_cancel(cancel), m_probe(probe), m_strata(GatherStrata::for_rays(settings.gather_rays)),
      m_rules(settings.direct), m_rules_gathered(settings.direct) {
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

void IcTracer::poll_gather() const {
    if (m_probe && m_probe->on_gather_ray) m_probe->on_gather_ray(m_stage);
    if (m_cancel.cancelled()) throw Cancelled();
}

// ---------------------------------------------------------------------------------------------------------------
// A vertex.

template <class Draw>
bool IcTracer::scatter(const SurfaceHit& hit, const ShadingPoint& sp, Ray& ray, PathState& st, int bounce,
                       CachePolicy policy, Draw&& draw, PathStats& stats, Color& L, uint64_t record_key, int px,
                       int py) const {
    const Vec3 wo = -ray.d;
    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
    const Vec3 wo_local = v.frame.to_local(wo);
    const Bsdf& bsdf = sp.bsdf();
    SpawnPoints spawn(hit.p, v.ng);
    const LightSet& lights = m_scene.lights();

    // The cache's part: the Lambertian lobes' indirect light from the records (or a new one), if this vertex uses
    // the cache at all; the other lobes are traced on.
    std::optional<LobeSplit> split_storage;  // only where the cache may serve this vertex
    if (policy != CachePolicy::Never) split_storage.emplace(bsdf);
    const LobeSplit* split = split_storage ? &*split_storage : nullptr;
    Color E(0.f);
    bool cached = false;
    if (split && !is_black(split->rho_d) && wo_local.z > 0.f) {
        if (m_cache.interpolate(hit.p, v.frame.n, &E)) {
            cached = true;
        } else if (policy == CachePolicy::Create) {
            IcRecord rec = make_record(hit, v, surface_footprint(st.distance, ray.d, hit.ng), record_key, stats);
            rec.pixel_x = px;
            rec.pixel_y = py;
            E = rec.E;  // its value at its own point: what the cache would give here once it holds it
            cached = true;
            if (t_sink) t_sink->push_back(rec);
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
    // leaves, whichever lobe it samples.
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
    if (cached && !bs.is_delta()) beta = split->other->empty() ? Color(0.f) : st.beta * split->other->f(wo_local, bs.wi) * weight;
    const float eta_scale = st.eta_scale * (bs.is_transmission() ? bs.eta * bs.eta : 1.f);
    if (roulette_here) {
        const float survive =
            continuation_survival(RouletteMode::Throughput, beta_emit, 1, eta_scale, [] { return Color(1.f); });
        if (!(survive > 0.f) || u.roulette >= survive) return false;
        beta_emit /= survive;
        beta /= survive;
    }
    if (is_black(beta_emit) || !is_finite(beta_emit) || !is_finite(beta)) return false;
    st.beta_emit = beta_emit;
    st.beta = beta;
    st.eta_scale = eta_scale;
    st.origin.specular = bs.is_delta();
    st.origin.bsdf_pdf = bs.pdf;
    st.origin.point = ctx;
    st.origin.ward_tested = ward_tested;
    st.rules = &m_rules;
    st.from = hit.primitive;
    ray = Ray{spawn.origin(cos_g > 0.f), wi, 0.f, k_inf, continuation_ray_type(bs, ray.type)};
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
void IcTracer::trace_camera(Ray ray, ConcreteSampler& sampler, PathStats& stats, Color& L, float* alpha,
                            AovSample* aov, const TracedHit* first) const {
    if (m_probe && m_probe->on_camera_path) m_probe->on_camera_path();
    PathState st;
    st.rules = &m_rules;  // a camera ray: emission counts with weight 1 (origin.specular)
    const int px = int(sampler.pixel_x()), py = int(sampler.pixel_y());
    const uint64_t key = sampler.sample_stream_key();
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
            if (bounce == 0 && m_settings.pixel.film_transparent) *alpha = 0.f;
            else add_world_emission(ray, st, L);
            return;
        }
        if (bounce == 0 && !camera_hit(m_scene, ray, hit, aov, alpha)) return;  // data passes, holdout
        const ShadingPoint sp = m_scene.shade(hit, -ray.d);
        if (!is_black(sp.emission))
            add_emission(st, sp.emission, hit.light >= 0 ? emitter_pdf(st, hit.light, ray.d, hit.t) : 0.f, L);
        if (bounce > m_settings.max_bounces || is_black(st.beta)) return;
        st.distance += hit.t;
        auto draw = [&](unsigned needs) { return draw_bounce(sampler, bounce, needs); };
        if (!scatter(hit, sp, ray, st, bounce, CachePolicy::Create, draw, stats, L,
                     hash_combine(key, uint64_t(bounce)), px, py))
            return;
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
        if (!scatter(hit, sp, ray, st, bounce, policy, draw, stats, L, 0, -1, -1)) return L;
    }
}

float IcTracer::surface_footprint(float distance, const Vec3& d, const Vec3& ng) const {
    // The pixel's extent across the surface along its steepest direction: the footprint over |cos| of the angle
    // the ray meets the surface at (at most 20 footprints, at grazing incidence).
    return m_footprint.at(distance) / std::fmax(std::fabs(dot(d, ng)), 0.05f);
}

IcRecord IcTracer::make_record(const SurfaceHit& hit, const SurfaceVertex& v, float footprint, uint64_t key,
                               PathStats& stats) const {
    HemisphereSamples hs;
    hs.strata = m_strata;
    const size_t n = size_t(m_strata.count());
    hs.dir.resize(n);
    hs.L.assign(n, Color(0.f));
    hs.r.assign(n, k_inf);
    PathState start;
    start.origin.specular = false;
    start.origin.point = LightSampleContext{hit.p, v.ns};
    start.rules = &m_rules_gathered;
    start.from = hit.primitive;
    SpawnPoints spawn(hit.p, v.ng);
    for (int j = 0; j < m_strata.M; ++j)
        for (int k = 0; k < m_strata.N; ++k) {
            poll_gather();
            const size_t i = size_t(j * m_strata.N + k);
            Pcg32 jitter(hash_combine(key, i), 0x6a6974746572ULL /* "jitter" */);
            const float u1 = jitter.next_float(), u2 = jitter.next_float();
            const Vec3 wl = gather_direction(m_strata, j, k, u1, u2);
            hs.dir[i] = wl;
            const Vec3 wi = v.frame.to_world(wl);
            const float cos_g = dot(wi, v.ng);
            if (leaks(cos_g, wl.z)) continue;  // through the surface: no light, no distance (as PATH)
            start.origin.bsdf_pdf = wl.z * k_inv_pi;
            const Ray ray{spawn.origin(cos_g > 0.f), wi, 0.f, k_inf, k_ray_diffuse};
            hs.L[i] = trace_gather(ray, start, hash_combine(key, i + (uint64_t(1) << 40)), stats, &hs.r[i]);
        }
    RecordRules rules;
    rules.a = m_settings.error;
    rules.gradients = m_settings.gradients;
    rules.footprint = footprint;
    rules.min_spacing = m_settings.min_spacing;
    rules.max_spacing = m_settings.max_spacing;
    rules.max_R = 2.f * m_scene.bounds().radius;
    return record_from_gather(estimate_gather(hs), hit.p, v.frame, rules);
}

// ---------------------------------------------------------------------------------------------------------------
// The pre-pass.

bool IcTracer::prepass_record(int fx, int fy, uint64_t key, PathStats& stats, IcRecord* record) const {
    Ray ray = m_scene.camera().generate_ray({float(fx) + 0.5f, float(fy) + 0.5f});
    PrimitiveRef from;
    float distance = 0.f;
    for (int bounce = 0; bounce <= m_settings.max_bounces; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        if (!m_scene.intersect(ray, &hit, from)) return false;
        distance += hit.t;
        const ShadingPoint sp = m_scene.shade(hit, -ray.d);
        const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, -ray.d);
        const Vec3 wo_local = v.frame.to_local(-ray.d);
        const Bsdf& bsdf = sp.bsdf();
        const LobeSplit split(bsdf);
        if (!is_black(split.rho_d) && wo_local.z > 0.f) {
            if (m_cache.covered(hit.p, v.frame.n)) return false;
            *record = make_record(hit, v, surface_footprint(distance, ray.d, hit.ng), key, stats);
            record->pixel_x = fx;
            record->pixel_y = fy;
            return true;
        }
        // Through mirrors and clear glass (the likelier side of a Fresnel choice); glossy surfaces get their
        // records while rendering.
        if (!bsdf.is_delta()) return false;
        const BsdfSample bs = bsdf.sample(wo_local, {0.5f, 0.5f}, 0.5f);
        if (!bs.valid()) return false;
        const Vec3 wi = v.frame.to_world(bs.wi);
        const float cos_g = dot(wi, v.ng);
        if (leaks(cos_g, bs.wi.z)) return false;
        ray = Ray{offset_ray_origin(hit.p, cos_g > 0.f ? v.ng : -v.ng), wi, 0.f, k_inf, continuation_ray_type(bs, ray.type)};
        from = hit.primitive;
    }
    return false;
}

}  // namespace candela
