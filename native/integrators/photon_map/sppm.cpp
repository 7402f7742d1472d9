#include "integrators/photon_map/sppm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "integrators/camera_hit.h"
#include "integrators/common/direct_light.h"
#include "integrators/common/light_path.h"
#include "integrators/common/lobe_classes.h"
#include "integrators/common/surface_vertex.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/photon_map/photon_shooting.h"
#include "integrators/photon_map/sppm_gather.h"
#include "integrators/photon_map/visible_point_grid.h"
#include "integrators/progressive_driver.h"
#include "lights/light_sampler.h"
#include "scene/shutter_time.h"

namespace candela {

namespace {

constexpr float k_inf = std::numeric_limits<float>::infinity();

struct SppmPixel {
    Color direct{0.f};  // Σ over iterations of emission + direct light
    Color tau{0.f};
    double alpha_sum = 0.0;
    float n = 0.f;  // N
    float radius = 0.f;
    Color shown{0.f};  // the estimate the film holds (L_(i−1))
    float shown_alpha = 0.f;
    float vp_alpha = 1.f;
};

class Sppm {
public:
    Sppm(const SppmSettings& s, const Scene& scene, Film& film, RenderContext& ctx)
        : m_s(s),
          m_scene(scene),
          m_film(film),
          m_ctx(ctx),
          m_emitters(scene.lights(), scene.bounds()),
          m_light_sampler(make_light_sampler("TREE", scene.lights())),
          m_pixels(size_t(film.width()) * film.height()),
          m_points(m_pixels.size()) {
        m_rules.light_sampling = LightSampling::LightOnly;
        m_photon_rules.max_bounces = s.max_bounces;
        m_photon_rules.alpha_threshold = s.alpha_threshold();
        const float r0 = s.resolve_radius(scene.bounds().radius);
        for (SppmPixel& p : m_pixels) p.radius = r0;
        m_photons = s.resolve_photons(double(scene.camera().full_width()) * scene.camera().full_height());
    }

    void run() {
        ProgressivePlan plan;
        plan.total = m_s.pixel.samples;
        plan.max_pass = 1;
        plan.time_limit = m_s.pixel.time_limit;
        plan.noise_threshold = m_s.pixel.noise_threshold;
        run_progressive(
            m_ctx, plan,
            [&](int64_t begin, int64_t end) {
                for (int64_t i = begin; i < end && !m_ctx.cancel.cancelled(); ++i) iteration(uint32_t(i));
            },
            NoiseSource());
    }

private:
    /// Step 1 for pixel (fx, fy): the camera path to its visible point; returns emission + direct light.
    Color camera_path(int fx, int fy, uint32_t it, Sampler& sampler, VisiblePoint& vp, float* alpha,
                      PathStats& stats) const {
        const LightSet& lights = m_scene.lights();
        const float alpha_t = m_s.alpha_threshold();
        *alpha = 1.f;
        vp.valid = false;
        const Vec2 u_pixel = std::visit(
            [&](auto& c) {
                c.start_pixel_sample(uint32_t(fx), uint32_t(fy), index_in_replicate(it));
                return c.sample_2d(dimension_index(Dim::Filter));
            },
            sampler);
        const Vec2 offset = m_s.pixel.filter.sample(u_pixel);
        const Camera& camera = m_scene.camera();
        const Vec2 u_lens = camera.has_aperture() ? get_2d(sampler, Dim::Lens) : Vec2{0.5f, 0.5f};
        Ray ray = camera.generate_ray({fx + 0.5f + offset.x, fy + 0.5f + offset.y}, u_lens);
        Color L(0.f), beta(1.f);
        PrimitiveRef from;
        for (int bounce = 0;; ++bounce) {
            SurfaceHit hit;
            ++stats.rays;
            const bool found = m_scene.intersect(ray, &hit, from);
            // Emission found by the camera ray or after delta scatterings: nothing else estimates it (weight 1).
            if (!lights.area_lights().empty()) {
                uint32_t li;
                float tl;
                if (m_scene.intersect_area_light(ray.o, ray.d, ray.tmin, found ? hit.t : ray.tmax, &li, &tl,
                                                 bounce == 0))
                    L += beta * std::get<AreaLight>(lights[li]).radiance;
            }
            if (!found) {
                if (bounce == 0 && m_s.pixel.film_transparent)
                    *alpha = 0.f;
                else if (const WorldLight* world = lights.world())
                    L += beta * world->Le(ray.d);
                else
                    L += beta * lights.background();
                return L;
            }
            if (bounce == 0 && !camera_hit(m_scene, ray, hit, nullptr, alpha)) return L;
            const Vec3 wo = -ray.d;
            const ShadingPoint sp = m_scene.shade(hit, wo);
            L += beta * sp.emission;
            if (bounce > m_s.max_bounces) return L;
            const Bsdf& bsdf = sp.bsdf();
            const uint32_t traced = traced_lobe_mask(bsdf, alpha_t);
            const bool has_estimated = bsdf.size() > __builtin_popcount(traced);
            const BounceSample u = std::visit(
                [&](auto& c) {
                    return draw_bounce(c, bounce, k_need_light_select | k_need_light | k_need_lobe | k_need_roulette);
                },
                sampler);
            // A vertex with both parts: the visible point with probability ∝ E's albedo, else on through T.
            float p_estimated = has_estimated ? 1.f : 0.f;
            if (has_estimated && traced != 0) {
                const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
                const Vec3 wl = v.frame.to_local(wo);
                const float a_t = luminance(lobe_subset(bsdf, traced, true).albedo(wl));
                const float a_e = luminance(lobe_subset(bsdf, traced, false).albedo(wl));
                p_estimated = a_t + a_e > 0.f ? a_e / (a_t + a_e) : 0.5f;
            }
            if (u.roulette < p_estimated) {
                beta /= p_estimated;
                const Bsdf part = lobe_subset(bsdf, traced, false);
                if (!lights.empty() && part.has_non_delta()) {
                    const SurfaceVertex v = SurfaceVertex::at(hit, sp.ns, wo);
                    const Vec3 wo_local = v.frame.to_local(wo);
                    SpawnPoints spawn(hit.p, v.ng);
                    const LightSampleContext lc{hit.p, v.ns};
                    next_event_estimation(m_rules, m_light_sampler, lights, lc, u.light_select, u.light,
                                          [&](uint32_t li, float pmf, Vec2 ul) {
                                              const DirectLightSample d = sample_direct_light(
                                                  m_scene, m_rules, hit, v, spawn, lc, part, wo_local, beta, li, pmf,
                                                  ul, [&](const Vec3& wi) { return part.pdf(wo_local, wi); },
                                                  stats.rays);
                                              L += d.contribution;
                                              return d.visible;
                                          });
                }
                vp.hit = hit;
                vp.wo = wo;
                vp.beta = beta;
                vp.valid = true;
                vp.transmits = (part.flags() & k_bsdf_transmission) != 0;
                return L;
            }
            beta /= 1.f - p_estimated;
            const LobeSubset traced_part{alpha_t, true};
            const VertexBsdf vb(m_scene, hit, wo, sp, has_estimated ? &traced_part : nullptr);
            // The lobe choice reuses u.lobe; the part choice above used u.roulette.
            const VertexBsdf::Sample s = vb.sample_camera(wo, u.bsdf, u.lobe);
            if (!s.valid()) return L;
            beta *= s.weight;
            if (is_black(beta) || !is_finite(beta)) return L;
            Ray next = ray_leaving(hit, s.w);
            ray = next;
            from = hit.primitive;
        }
    }

    void iteration(uint32_t it) {
        const Film& film = m_film;
        const auto& tiles = film.tiles();
        // Motion blur: the iteration's one shutter time (a hash of the seed and iteration, no sampler dimension),
        // seen by its camera pass, its photons and its statistics, so each iteration's visible points and photons
        // meet at one time and the progressive average over iterations is the time average.
        const float time =
            m_scene.has_motion() ? shutter_time_of(hash_combine(m_s.pixel.seed, 0x7370706dULL + it)) : k_shutter_middle;
        // 1. Visible points and direct light.
        parallel_for(
            m_ctx.threads, tiles.size(),
            [&](size_t t) {
                const ShutterScope scope(time);
                const Tile& tile = tiles[t];
                Sampler sampler = m_s.pixel.replicate_sampler(noise_replicate_of(it));
                PathStats stats;
                for (int y = tile.y0; y < tile.y1; ++y)
                    for (int x = tile.x0; x < tile.x1; ++x) {
                        SppmPixel& p = m_pixels[size_t(y) * film.width() + x];
                        float alpha = 1.f;
                        Color L = camera_path(film.origin_x() + x, film.origin_y() + y, it, sampler,
                                              m_points[size_t(y) * film.width() + x], &alpha, stats);
                        ++stats.paths;
                        if (!is_finite(L) || min_component(L) < 0.f) {
                            ++stats.nan_samples;
                            L = Color(0.f);
                        }
                        p.direct += L;
                        p.alpha_sum += alpha;
                    }
                stats.flush(m_ctx.counters);
            },
            &m_ctx.cancel);
        if (m_ctx.cancel.cancelled()) return;

        // 2. Photons.
        PhotonShot shot;
        try {
            const ShutterScope scope(time);  // shoot_photons traces at the caller's time
            const PhotonTracer tracer(m_scene, m_emitters, m_photon_rules);
            shot = shoot_photons(tracer, m_emitters, PhotonStore::Indirect, m_photons, m_s.pixel.seed, 2 + it, m_ctx,
                                 "Tracing photons");
        } catch (const Cancelled&) {
            m_ctx.counters.stage.end();
            return;
        }
        m_ctx.counters.stage.end();
        m_emitted += double(m_photons);

        // 3. Each photon's visible points (the grid), then per pixel its photons' flux and the statistics.
        std::vector<float> radii(m_pixels.size());
        for (size_t i = 0; i < m_pixels.size(); ++i) radii[i] = m_pixels[i].radius;
        const PixelFlux flux = gather_flux(m_scene, m_points, radii, shot, m_s.alpha_threshold(), time, m_ctx);
        if (m_ctx.cancel.cancelled()) return;
        update_pixels(it, flux);
    }

    void update_pixels(uint32_t it, const PixelFlux& flux) {
        const Film& film = m_film;
        const auto& tiles = film.tiles();
        const float alpha = m_s.alpha;
        parallel_for(m_ctx.threads, tiles.size(), [&](size_t t) {
            const Tile& tile = tiles[t];
            std::vector<PixelAccum> out(size_t(tile.width()) * tile.height());
            for (int y = tile.y0; y < tile.y1; ++y)
                for (int x = tile.x0; x < tile.x1; ++x) {
                    const size_t idx = size_t(y) * film.width() + x;
                    SppmPixel& p = m_pixels[idx];
                    if (flux.found[idx] > 0) {
                        // The sphere, not Jensen's flattened disc: a sphere of radius r cuts a curved surface of
                        // radius R in a cap of area πr² exactly, so uniform irradiance has no bias at any radius.
                        const Color phi = flux.phi[idx];
                        const float m = float(flux.found[idx]);
                        const float n_new = p.n + alpha * m;
                        const float r_new = p.radius * std::sqrt(n_new / (p.n + m));
                        const float shrink = (r_new * r_new) / (p.radius * p.radius);
                        if (is_finite(phi))
                            p.tau = (p.tau + m_points[idx].beta * phi) * shrink;
                        else
                            p.tau = p.tau * shrink;
                        p.n = n_new;
                        p.radius = r_new;
                    }
                    const double iters = double(it) + 1.0;
                    const Color L =
                        p.direct / float(iters) + p.tau / float(double(k_pi) * double(p.radius) * p.radius * m_emitted);
                    const float a = float(p.alpha_sum / iters);
                    // The film's mean of it + 1 entries becomes L: add (i+1)·L − i·L_prev.
                    PixelAccum& acc = out[size_t(y - tile.y0) * tile.width() + (x - tile.x0)];
                    const Color entry = L * float(iters) - p.shown * float(iters - 1.0);
                    acc.r = entry.x;
                    acc.g = entry.y;
                    acc.b = entry.z;
                    acc.a = a * iters - p.shown_alpha * (iters - 1.0);
                    acc.n = 1;
                    acc.rep_n[noise_replicate_of(it)] = 1;
                    p.shown = L;
                    p.shown_alpha = a;
                }
            m_film.add_tile(t, out);
        });
    }

    const SppmSettings& m_s;
    const Scene& m_scene;
    Film& m_film;
    RenderContext& m_ctx;
    EmitterSet m_emitters;
    LightSampler m_light_sampler;
    DirectLightRules m_rules;
    PhotonRules m_photon_rules;
    std::vector<SppmPixel> m_pixels;
    std::vector<VisiblePoint> m_points;  // the pixels' visible points of the current iteration
    int64_t m_photons = 0;
    double m_emitted = 0.0;
};

}  // namespace

void render_sppm(const SppmSettings& settings, const Scene& scene, Film& film, RenderContext& ctx) {
    Sppm(settings, scene, film, ctx).run();
}

double sppm_bytes_per_pixel() {
    // The pixel, its grid point, up to 8 cells' entries and its bucket start, its flux sums and its pair start.
    return double(sizeof(SppmPixel) + sizeof(VisiblePoint) + sizeof(float) + sizeof(GridPoint) + 9 * sizeof(uint32_t) +
                  sizeof(Color) + 2 * sizeof(uint32_t));
}

}  // namespace candela
