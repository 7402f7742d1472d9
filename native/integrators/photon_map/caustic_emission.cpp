#include "integrators/photon_map/caustic_emission.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/frame.h"
#include "integrators/common/lobe_classes.h"
#include "sampling/warp.h"

namespace candela {

namespace {

bool is_distant(const Light& l) { return std::holds_alternative<SunLight>(l) || std::holds_alternative<WorldLight>(l); }

/// Where a finite emitter sits (its targets' probabilities are the solid angles seen from here).
Vec3 emitter_center(const Light& light) {
    return std::visit(
        [](const auto& l) -> Vec3 {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight>)
                return l.position;
            else if constexpr (std::is_same_v<T, AreaLight>)
                return l.center;
            else if constexpr (std::is_same_v<T, TriangleLight>)
                return (l.p0 + l.p1 + l.p2) / 3.f;
            else
                return Vec3(0.f);
        },
        light);
}

/// The cone sphere t subtends from y: its axis, cos of its half-angle and 1 − that (computed without cancellation);
/// false if y is inside the sphere (every direction).
bool target_cone(const CausticTarget& t, const Vec3& y, Vec3* axis, float* cos_max, float* one_minus_cos) {
    const Vec3 to = t.center - y;
    const float d2 = length_squared(to);
    const float r2 = t.radius * t.radius;
    if (!(d2 > r2)) return false;
    const float s2 = r2 / d2;  // sin² of the half-angle
    const float c = std::sqrt(1.f - s2);
    *axis = to / std::sqrt(d2);
    *cos_max = c;
    *one_minus_cos = s2 / (1.f + c);
    return true;
}

float solid_angle(const CausticTarget& t, const Vec3& y) {
    Vec3 axis;
    float c, omc;
    return target_cone(t, y, &axis, &c, &omc) ? 2.f * k_pi * omc : 4.f * k_pi;
}

/// Whether the material may have a traced lobe anywhere: its constant BSDFs' lobes, or for a textured material
/// any delta or glossy closure.
bool material_may_trace(const Scene& scene, uint32_t k, float alpha_threshold) {
    const Material& m = scene.materials()[k];
    if (m.inputs >= 0) return (scene.material_flags(k) & (k_bsdf_specular | k_bsdf_glossy)) != 0;
    return traced_lobe_mask(m.front, alpha_threshold) != 0 || traced_lobe_mask(m.back, alpha_threshold) != 0;
}

}  // namespace

CausticAnalysis analyse_caustics(const Scene& scene, float alpha_threshold) {
    CausticAnalysis out;
    const size_t materials = scene.materials().size();
    std::vector<uint8_t> traced(materials, 0);
    for (uint32_t k = 0; k < materials; ++k) {
        traced[k] = material_may_trace(scene, k, alpha_threshold);
        out.any_traced_material |= traced[k] != 0;
    }
    if (!out.any_traced_material) return out;
    for (uint32_t o = 0; o < scene.object_count(); ++o) {
        const ObjectTriangles t = scene.object_triangles(o);
        Vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
        std::vector<Vec3> points;
        for (uint32_t prim = 0; prim < t.triangle_count; ++prim) {
            const SurfaceHit h = scene.surface_point(o, prim, 1.f / 3.f, 1.f / 3.f);
            if (h.material >= materials || !traced[h.material]) continue;
            for (int c = 0; c < 3; ++c) {
                const float* v = t.vertices + 3 * size_t(t.indices[3 * size_t(prim) + c]);
                Vec3 p(v[0], v[1], v[2]);
                if (t.instanced) p = t.object_to_world.point(p);
                lo = vmin(lo, p);
                hi = vmax(hi, p);
                points.push_back(p);
            }
        }
        if (points.empty()) continue;
        out.moving |= scene.object_moves(o);
        CausticTarget target;
        target.center = (lo + hi) * 0.5f;
        for (const Vec3& p : points) target.radius = std::max(target.radius, length(p - target.center));
        target.radius *= 1.0001f;  // the vertices' rounding: the sphere must contain every traced point
        out.targets.push_back(target);
    }
    if (out.targets.size() > k_max_caustic_targets) {
        Vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
        for (const CausticTarget& t : out.targets) {
            lo = vmin(lo, t.center - Vec3(t.radius));
            hi = vmax(hi, t.center + Vec3(t.radius));
        }
        CausticTarget all;
        all.center = (lo + hi) * 0.5f;
        for (const CausticTarget& t : out.targets)
            all.radius = std::max(all.radius, length(t.center - all.center) + t.radius);
        out.targets = {all};
        out.merged = true;
    }
    return out;
}

CausticEmission::CausticEmission(const EmitterSet& emitters, const std::vector<CausticTarget>& targets)
    : m_emitters(emitters), m_targets(targets) {
    const size_t n = emitters.size(), m = m_targets.size();
    if (m == 0 || n == 0) return;
    const SceneSphere& bounds = emitters.bounds();
    m_target_probs.assign(n * m, 0.f);
    std::vector<float> weights(n, 0.f);
    double power = 0.0, caught = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const Light& l = emitters[i];
        std::vector<float> s(m);
        float coverage = 0.f;
        if (is_distant(l)) {
            for (size_t j = 0; j < m; ++j) s[j] = m_targets[j].radius * m_targets[j].radius;
            float sum = 0.f;
            for (float v : s) sum += v;
            coverage = std::min(1.f, sum / (bounds.radius * bounds.radius));
        } else {
            const Vec3 c = emitter_center(l);
            for (size_t j = 0; j < m; ++j) s[j] = solid_angle(m_targets[j], c);
            float sum = 0.f;
            for (float v : s) sum += v;
            coverage = std::min(1.f, sum / (4.f * k_pi));
        }
        float total = 0.f;
        for (float v : s) total += v;
        for (size_t j = 0; j < m; ++j) m_target_probs[i * m + j] = total > 0.f ? s[j] / total : 1.f / float(m);
        m_target_select.emplace_back(
            std::vector<float>(m_target_probs.begin() + long(i * m), m_target_probs.begin() + long((i + 1) * m)));
        const float p = emitters.power(uint32_t(i));
        weights[i] = p > 0.f ? p * std::max(coverage, 1e-4f) : 0.f;
        power += p;
        caught += double(p) * coverage;
    }
    m_select = Distribution1D(weights);
    m_coverage = power > 0.0 ? float(caught / power) : 0.f;
}

float CausticEmission::direction_pdf(const float* s, const Vec3& y, const Vec3& w) const {
    float p = 0.f;
    for (size_t j = 0; j < m_targets.size(); ++j) {
        if (!(s[j] > 0.f)) continue;
        Vec3 axis;
        float c, omc;
        if (!target_cone(m_targets[j], y, &axis, &c, &omc))
            p += s[j] * k_inv_four_pi;
        else if (dot(w, axis) >= c)
            p += s[j] / (2.f * k_pi * omc);
    }
    return p;
}

float CausticEmission::area_pdf(const float* s, const Vec3& origin, const Vec3& d) const {
    float p = 0.f;
    for (size_t j = 0; j < m_targets.size(); ++j) {
        if (!(s[j] > 0.f)) continue;
        const Vec3 to = m_targets[j].center - origin;
        const Vec3 across = to - d * dot(to, d);  // from the ray to the centre, across the direction
        const float r2 = m_targets[j].radius * m_targets[j].radius;
        if (length_squared(across) <= r2) p += s[j] / (k_pi * r2);
    }
    return p;
}

LightPathStart CausticEmission::sample(float u_select, Vec2 u_pos, Vec2 u_dir, float u_target) const {
    LightPathStart out;
    if (empty()) return out;
    float pmf = 0.f;
    const uint32_t i = uint32_t(m_select.sample_discrete(u_select, &pmf));
    if (!(pmf > 0.f)) return out;
    const Light& light = m_emitters[i];
    const size_t m = m_targets.size();
    const float* s = m_target_probs.data() + size_t(i) * m;
    const CausticTarget& target = m_targets[m_target_select[i].sample_discrete(u_target)];
    out.emitter = i;
    if (is_distant(light)) {
        const EmitterPoint pt = light_sample_point(light, u_pos, u_dir, 0.5f);
        if (!pt.valid()) return out;
        // A point on the target's disc across the direction, moved back along it outside the scene.
        const Frame f(pt.omega);
        const Vec2 q = sample_uniform_disk_concentric(u_pos);
        const Vec3 on_disc = target.center + (f.s * q.x + f.t * q.y) * target.radius;
        const SceneSphere& bounds = m_emitters.bounds();
        const float back = std::max(0.f, dot(bounds.center - on_disc, pt.omega)) + bounds.radius;
        const Vec3 origin = on_disc + pt.omega * back;
        const Vec3 d = -pt.omega;
        const float p_area = area_pdf(s, origin, d);
        if (!(p_area > 0.f)) return out;
        out.beta = pt.Le / (pt.pdf_pos * p_area * pmf);
        out.ray = Ray{origin, d, 0.f, std::numeric_limits<float>::infinity(), k_ray_all};
    } else {
        const EmitterPoint pt = light_sample_point(light, u_pos, u_dir, 0.5f);
        if (!pt.valid()) return out;
        Vec3 axis, d;
        float c, omc;
        if (target_cone(target, pt.p, &axis, &c, &omc))
            d = Frame(axis).to_world(sample_uniform_cone(u_dir, c));
        else
            d = sample_uniform_sphere(u_dir);
        const float p_dir = direction_pdf(s, pt.p, d);
        if (!(p_dir > 0.f)) return out;
        const Color Le = light_radiance(light, pt, d);
        if (is_black(Le)) return out;
        const float cos_y = pt.delta_pos ? 1.f : std::fabs(dot(pt.n, d));
        out.beta = Le * (cos_y / (pt.pdf_pos * p_dir * pmf));
        const Vec3 origin = pt.delta_pos ? pt.p : offset_ray_origin(pt.p, dot(pt.n, d) > 0.f ? pt.n : -pt.n);
        out.ray = Ray{origin, d, 0.f, std::numeric_limits<float>::infinity(), k_ray_all};
    }
    out.valid = is_finite(out.beta) && !is_black(out.beta);
    return out;
}

}  // namespace candela
