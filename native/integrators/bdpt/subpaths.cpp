#include "integrators/bdpt/subpaths.h"

#include "integrators/bdpt/strategy.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "integrators/camera_hit.h"
#include "integrators/common/roulette.h"
#include "integrators/ray_types.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

Vec3 leave(const SurfaceHit& hit, const Vec3& w) {
    return offset_ray_origin(hit.p, dot(w, hit.ng) > 0.f ? hit.ng : -hit.ng);
}

/// The surface vertex at `hit`, reached along `ray` (its `w` points back along the ray).
void make_surface(PathVertex& v, const Scene& scene, const SurfaceHit& hit, const Ray& ray, const Color& beta) {
    v.clear();
    v.kind = VertexKind::Surface;
    v.hit = hit;
    v.p = hit.p;
    v.ng = hit.ng;
    v.w = -ray.d;
    v.beta = beta;
    v.bsdf.emplace(scene, v.hit, v.w, scene.shade(v.hit, v.w));
}

/// The densities that camera vertex z[n] (just made) fixes: its own forward one and z[n − 2]'s reverse one.
void camera_densities(const Densities& d, std::vector<PathVertex>& z, int n) {
    PathVertex* prev = n >= 2 ? &z[size_t(n - 2)] : nullptr;
    if (z[size_t(n - 1)].delta) {
        z[size_t(n)].pdf_fwd = 0.f;
        if (prev) prev->pdf_rev = 0.f;
        return;
    }
    d.camera_step(z[size_t(n - 1)], prev, z[size_t(n)], &z[size_t(n)].pdf_fwd, prev ? &prev->pdf_rev : nullptr);
}

template <class S>
int camera_walk(const BdptContext& c, Ray ray, S& sampler, std::vector<PathVertex>& z,
                std::vector<VertexNumbers>& numbers, std::vector<AreaLightHit>& area_hits, PathStats& stats,
                float* alpha, AovSample* aov, int limit) {
    const Scene& scene = c.scene;
    const BdptSettings& cfg = c.settings;
    const LightSet& lights = scene.lights();
    z[0].clear();
    z[0].kind = VertexKind::Camera;
    z[0].p = ray.o;
    z[0].beta = Color(1.f);
    float pdf_pos = 0.f, pdf_dir = 0.f;
    scene.camera().pdf_we(ray, &pdf_pos, &pdf_dir, c.camera_margin());
    z[0].pdf_fwd = pdf_pos;
    z[0].delta = false;
    const Densities d(c);
    Color beta(1.f);
    float eta_scale = 1.f;
    PrimitiveRef from;
    int n = 1;
    for (int bounce = 0; n < limit; ++bounce) {
        SurfaceHit hit;
        ++stats.rays;
        const bool found = scene.intersect(ray, &hit, from);
        // The closest emitting side of an area light before the surface: an end for s = 0 (the path goes on).
        uint32_t li;
        float tl;
        if (!lights.area_lights().empty() &&
            scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit.t : ray.tmax, &li, &tl, bounce == 0)) {
            AreaLightHit a;
            a.segment = n;
            a.light = li;
            a.p = ray.o + ray.d * tl;
            PathVertex probe;
            probe.kind = VertexKind::Light;
            probe.p = a.p;
            probe.ng = std::get<AreaLight>(lights[li]).normal;
            a.pdf_fwd = z[n - 1].delta ? 0.f : d.camera_side(z[n - 1], n >= 2 ? &z[n - 2] : nullptr, probe);
            a.beta = beta;
            area_hits.push_back(a);
        }
        if (!found) {
            if (bounce == 0 && cfg.pixel.film_transparent) {
                *alpha = 0.f;
                return n;
            }
            if (c.emitters.world() < 0) return n;
            PathVertex& v = z[n];
            v.clear();
            v.kind = VertexKind::Light;
            v.infinite = true;
            v.w = ray.d;  // toward the sky
            v.beta = beta;
            v.emitter = c.emitters.world();
            // Solid angle: a distant vertex.
            camera_densities(d, z, n);
            return n + 1;
        }
        if (bounce == 0 && !camera_hit(scene, ray, hit, aov, alpha)) return n;  // data passes, holdout
        PathVertex& v = z[n];
        make_surface(v, scene, hit, ray, beta);
        // The densities MIS uses, from the vertices' positions (the connections recompute theirs so too: the
        // weights of a path's strategies then sum to 1 exactly, ray-origin offsets and all).
        camera_densities(d, z, n);
        ++n;
        if (n >= c.max_camera()) return n;
        const bool roulette_here = cfg.rr_mode != RouletteMode::Off && bounce + 1 >= cfg.rr_start_bounce;
        const BounceSample u = draw_bounce(
            sampler, bounce, k_need_light_select | k_need_light | k_need_lobe | (roulette_here ? k_need_roulette : 0u));
        VertexNumbers& num = numbers[n - 1];
        num.u_select = u.light_select;
        num.u_point = u.light;
        if (n >= limit) return n;  // a subpath of `limit` vertices (its last one keeps its connection numbers)
        const VertexBsdf::Sample s = v.bsdf->sample_camera(v.w, u.bsdf, u.lobe);
        if (!s.valid()) return n;
        v.delta = s.delta;
        beta *= s.weight;
        if (s.bsdf.is_transmission()) eta_scale *= s.bsdf.eta * s.bsdf.eta;
        if (roulette_here) {
            const float q = cfg.rr_mode == RouletteMode::Albedo ? min_num(1.f, max_component(s.weight))
                            : cfg.rr_mode == RouletteMode::SqrtThroughput
                                ? arrival_survival(beta, eta_scale)
                                : min_num(1.f, max_component(beta) * eta_scale);
            if (!(q > 0.f) || u.roulette >= q) return n;
            beta /= q;
        }
        if (is_black(beta) || !is_finite(beta)) return n;
        ray = Ray{leave(hit, s.w), s.w, 0.f, k_inf, continuation_ray_type(s.bsdf, ray.type)};
        from = hit.primitive;
    }
    return n;
}

template <class S>
int light_walk(const BdptContext& c, S& sampler, std::vector<PathVertex>& y, std::vector<VertexNumbers>& numbers,
               PathStats& stats, int limit) {
    const Scene& scene = c.scene;
    const BdptSettings& cfg = c.settings;
    const int dim = c.light_dim_bounce();
    const BounceSample u0 = draw_bounce(sampler, dim, k_need_light_select | k_need_light | k_need_lobe);
    uint32_t index = 0;
    float pmf = 0.f;
    const EmissionSample es = c.emitters.sample_le(u0.light_select, u0.light, u0.bsdf, u0.lobe, &index, &pmf);
    if (!es.valid() || !(pmf > 0.f)) return 0;
    const Light& light = c.emitters[index];
    // A point or spot light's vertex is its centre, whatever its radius: the strategies reach a soft one at
    // different points of it (emission's sphere, next-event estimation's disk), and MIS weighs them all as if it
    // were a point there (Densities, light_center_direction_pdf). The ray leaves the sampled point.
    const PointLight* point = std::get_if<PointLight>(&light);
    PathVertex& y0 = y[0];
    y0.clear();
    y0.kind = VertexKind::Light;
    y0.p = point ? point->position : es.p;
    y0.ng = (point || es.delta_pos || es.infinite) ? Vec3(0.f) : es.n;
    y0.emitter = int32_t(index);
    y0.infinite = es.infinite;
    y0.delta_light = !light_hittable(light);
    y0.w = es.infinite ? -es.d : Vec3(0.f);  // a distant light: the direction toward it
    y0.Le = es.Le;
    y0.hit.b1 = es.b1;  // a textured triangle's emission toward a connection
    y0.hit.b2 = es.b2;
    // A distant light's origin is its direction (solid-angle density); a finite one's its point.
    const float origin_pdf = es.infinite ? es.pdf_dir : point ? 1.f : es.pdf_pos;
    y0.pdf_fwd = pmf * origin_pdf;
    y0.beta = Color(1.f / (pmf * origin_pdf));
    Color beta = es.weight() / pmf;
    if (!is_finite(beta) || limit <= 1) return 1;
    Ray ray{(es.delta_pos || es.infinite) ? es.p : offset_ray_origin(es.p, es.n), es.d, 0.f, k_inf, k_ray_all};
    const Densities d(c);
    float beta_ref = 0.f, eta_scale = 1.f;
    PrimitiveRef from;
    int n = 1;
    for (int depth = 1; n < limit; ++depth) {
        SurfaceHit hit;
        ++stats.rays;
        if (!scene.intersect(ray, &hit, from)) return n;
        // A soft point light lights its first receiver through the disk that faces it (lights/light_emission.h).
        if (n == 1 && !emission_arrives(light, hit.p, ray.d)) return n;
        PathVertex& v = y[n];
        make_surface(v, scene, hit, ray, beta);
        // From the positions, as the connections recompute them (see camera_walk).
        if (n == 1)
            v.pdf_fwd = d.emission(y[0], v);  // a distant light: the disk's density across the rays
        else if (y[n - 1].delta)
            v.pdf_fwd = y[n - 2].pdf_rev = 0.f;
        else
            d.light_step(y[n - 1], &y[n - 2], v, &v.pdf_fwd, &y[n - 2].pdf_rev);
        if (depth == 1) beta_ref = max_component(beta);
        ++n;
        const bool last = n >= limit;
        const bool roulette_here = !last && cfg.rr_mode != RouletteMode::Off && depth >= cfg.rr_start_bounce;
        const BounceSample u =
            draw_bounce(sampler, dim + depth, k_need_light | k_need_lobe | (roulette_here ? k_need_roulette : 0u));
        numbers[n - 1].u_point = u.light;  // the lens sample of a connection to the camera (t = 1)
        if (last) return n;
        const VertexBsdf::Sample s = v.bsdf->sample_light(v.w, u.bsdf, u.lobe);
        if (!s.valid()) return n;
        v.delta = s.delta;
        beta *= s.weight;
        if (s.bsdf.is_transmission() && s.bsdf.eta > 0.f) eta_scale /= s.bsdf.eta * s.bsdf.eta;
        if (roulette_here) {
            const Color relative = beta * (eta_scale / beta_ref);
            const float q = cfg.rr_mode == RouletteMode::Albedo           ? min_num(1.f, max_component(s.weight))
                            : cfg.rr_mode == RouletteMode::SqrtThroughput ? arrival_survival(relative, 1.f)
                                                                          : min_num(1.f, max_component(relative));
            if (!(q > 0.f) || u.roulette >= q) return n;
            beta /= q;
        }
        if (is_black(beta) || !is_finite(beta)) return n;
        ray = Ray{leave(hit, s.w), s.w, 0.f, k_inf, k_ray_all};
        from = hit.primitive;
    }
    return n;
}

}  // namespace

int camera_subpath(const BdptContext& c, const Ray& ray, Sampler& sampler, std::vector<PathVertex>& z,
                   std::vector<VertexNumbers>& numbers, std::vector<AreaLightHit>& area_hits, PathStats& stats,
                   float* alpha, AovSample* aov) {
    area_hits.clear();
    return std::visit(
        [&](auto& s) { return camera_walk(c, ray, s, z, numbers, area_hits, stats, alpha, aov, c.max_camera()); },
        sampler);
}

int light_subpath(const BdptContext& c, Sampler& sampler, std::vector<PathVertex>& y,
                  std::vector<VertexNumbers>& numbers, PathStats& stats) {
    return std::visit([&](auto& s) { return light_walk(c, s, y, numbers, stats, c.max_light()); }, sampler);
}

int camera_subpath(const BdptContext& c, const Ray& ray, PrimarySampleSampler& sampler, std::vector<PathVertex>& z,
                   std::vector<VertexNumbers>& numbers, std::vector<AreaLightHit>& area_hits, PathStats& stats,
                   int max_vertices) {
    area_hits.clear();
    float alpha = 1.f;
    return camera_walk(c, ray, sampler, z, numbers, area_hits, stats, &alpha, nullptr,
                       std::min(max_vertices, c.max_camera()));
}

int light_subpath(const BdptContext& c, PrimarySampleSampler& sampler, std::vector<PathVertex>& y,
                  std::vector<VertexNumbers>& numbers, PathStats& stats, int max_vertices) {
    return light_walk(c, sampler, y, numbers, stats, std::min(max_vertices, c.max_light()));
}

}  // namespace candela
