// Source shooting (generator_tracer.h): the camera sample's light path — one per camera sample, shared by all its
// receivers — and the connection of its non-delta vertices z_k to a receiver x. With the light path's throughput
// β_k (common/light_walk.h: E[Σ_k β_k h(z_k, w_l)] = ∫∫ h L_in |w_l·ng| dω dA), the light z sends toward x is
// estimated by β_k·f_z(w_c, w_l)·|w_l·n|/|w_l·ng| (Veach's adjoint factor, common/vertex_bsdf.h), so
//     I(x) ≈ β_x · f_x(wo, ω) · |ω·n_x| · Σ_k β_k · f_z(−ω, w_l) · c(−ω, w_l) · |ω·ng_z| / d² · V(x, z_k),
// ω the unit direction x → z_k and d its length. Path lengths: x's n + 1 camera-side vertices and k light-side ones
// make at most max_bounces + 1.
#include <cmath>

#include "integrators/common/connection.h"
#include "integrators/common/light_walk.h"
#include "integrators/generators/generator_path.h"

namespace candela {

void GeneratorPath::build_light_path() {
    m_light_path_built = true;
    const GeneratorSettings& cfg = m_cfg;
    if (cfg.max_bounces < 1 || m_t.m_emitters.empty()) return;
    const LightWalkRules rules{cfg.max_bounces, cfg.rr_mode, cfg.rr_start_bounce};  // a receiver takes one vertex
    std::visit(
        [&](auto& s) {
            walk_light_path(
                m_t.m_scene, m_t.m_emitters, rules, s, m_t.m_source_slot, m_stats,
                [&](const EmissionSample& es, uint32_t emitter) {
                    m_light_origin.emitter = int(emitter);
                    m_light_origin.p = es.p;
                    m_light_origin.n = es.n;
                    m_light_origin.infinite = es.infinite;
                },
                [&](const VertexBsdf& vb, const Vec3& w_l, const Color& beta, int depth, const BounceSample&) {
                    if (vb.has_non_delta(w_l)) m_light_path.push_back({vb.hit(), vb.shading(w_l), w_l, beta, depth});
                });
        },
        m_sampler);
}

void GeneratorPath::connect_light_path(const Receiver& r, bool one_bounce_only) {
    if (!m_light_path_built) build_light_path();
    const Scene& scene = m_t.m_scene;
    const SurfaceHit& x = r.vertex->hit();
    for (const LightVertex& lv : m_light_path) {
        if (one_bounce_only && lv.depth != 1) continue;
        if (r.n + 1 + lv.depth > m_cfg.max_bounces + 1) break;  // depths increase along the path
        const Vec3 xz = lv.hit.p - x.p;
        const float d2 = length_squared(xz);
        if (!(d2 > 0.f)) continue;
        const Vec3 w = xz / std::sqrt(d2);
        const Color f_x = r.vertex->f(r.wo, w);
        if (is_black(f_x)) continue;
        const VertexBsdf z(scene, lv.hit, lv.w_l, lv.sp);
        const Color f_z = z.f(-w, lv.w_l);
        if (is_black(f_z)) continue;
        const float g =
            r.vertex->camera_cosine(r.wo, w) * z.adjoint_factor(-w, lv.w_l) * std::fabs(dot(w, lv.hit.ng)) / d2;
        if (!(g > 0.f)) continue;
        ++m_stats.rays;
        if (!surfaces_connect(scene, x, lv.hit)) continue;
        float weight = 1.f;
        if (m_cfg.combine && lv.depth == 1) {
            OneBounceLight y;
            y.emitter = m_light_origin.emitter;
            y.light = size_t(y.emitter) < scene.lights().size() ? y.emitter : -1;
            y.w = lv.w_l;
            y.dist =
                m_light_origin.infinite ? std::numeric_limits<float>::infinity() : length(m_light_origin.p - lv.hit.p);
            y.n = m_light_origin.n;
            weight = m_t.m_weights.weight(PathGenerator::SourceShooting, *r.vertex, r.wo, z, y);
        }
        const Color c = r.beta * f_x * lv.beta * f_z * (g * weight);
        if (!is_finite(c)) {
            ++m_stats.nan_samples;
            continue;
        }
        m_L += c;
    }
}

}  // namespace candela
