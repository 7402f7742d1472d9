#include "integrators/bdpt/strategy.h"

#include <cmath>

#include "integrators/shadow_ray.h"
#include "scene/ray_offset.h"

namespace candela {

namespace {

/// Unit direction from vertex a toward vertex b (a distant b: toward its light; a distant a: along its light).
Vec3 direction(const PathVertex& a, const PathVertex& b) {
    if (b.infinite) return b.w;
    if (a.infinite) return -a.w;
    return normalize(b.p - a.p);
}

/// Light vertex `v`'s emitter point, for the emission functions (the side its normal takes: the one toward d).
EmitterPoint emitter_point(const PathVertex& v, const Vec3& d) {
    EmitterPoint e;
    e.p = v.p;
    e.n = dot(v.ng, d) < 0.f ? -v.ng : v.ng;
    e.delta_pos = PathVertex::is_zero(v.ng) && !v.infinite;
    e.infinite = v.infinite;
    e.omega = v.w;
    e.Le = v.Le;
    e.b1 = v.hit.b1;
    e.b2 = v.hit.b2;
    return e;
}

/// The emitter index of an emitting vertex (a light vertex, or a surface whose triangle emits), or −1.
int32_t emitter_of(const PathVertex& v) {
    if (v.kind == VertexKind::Light) return v.emitter;
    if (v.kind == VertexKind::Surface) return v.hit.light;
    return -1;
}

float remap0(float p) { return p != 0.f ? p : 1.f; }

float heuristic(MisHeuristic h, float r) { return h == MisHeuristic::Power ? r * r : r; }

}  // namespace

float Densities::light_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next) const {
    return light_side(cur, prev, next, prev ? direction(cur, *prev) : Vec3(0.f), direction(cur, next));
}
float Densities::light_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, const Vec3& w_prev,
                            const Vec3& w_next) const {
    if (cur.kind == VertexKind::Light || (cur.kind == VertexKind::Surface && !prev)) return emission(cur, next, w_next);
    if (cur.kind != VertexKind::Surface || !prev) return 0.f;
    return solid_angle_to_area(cur, next, cur.bsdf->pdf_light(w_prev, w_next));
}
float Densities::camera_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next) const {
    return camera_side(cur, prev, next, prev ? direction(cur, *prev) : Vec3(0.f), direction(cur, next));
}
float Densities::camera_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, const Vec3& w_prev,
                             const Vec3& w_next) const {
    if (cur.kind == VertexKind::Camera) {
        float pos = 0.f, dir = 0.f;
        const Ray ray{cur.p, w_next};
        m_c.scene.camera().pdf_we(ray, &pos, &dir);
        return solid_angle_to_area(cur, next, dir);
    }
    if (cur.kind != VertexKind::Surface || !prev) return 0.f;
    return solid_angle_to_area(cur, next, cur.bsdf->pdf_camera(w_prev, w_next));
}
void Densities::camera_step(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, float* next_fwd,
                            float* prev_rev) const {
    const Vec3 w_next = direction(cur, next), w_prev = prev ? direction(cur, *prev) : Vec3(0.f);
    *next_fwd = camera_side(cur, prev, next, w_prev, w_next);
    if (prev) *prev_rev = light_side(cur, &next, *prev, w_next, w_prev);
}
void Densities::light_step(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, float* next_fwd,
                           float* prev_rev) const {
    const Vec3 w_next = direction(cur, next), w_prev = prev ? direction(cur, *prev) : Vec3(0.f);
    *next_fwd = light_side(cur, prev, next, w_prev, w_next);
    if (prev) *prev_rev = camera_side(cur, &next, *prev, w_next, w_prev);
}
float Densities::emission(const PathVertex& light, const PathVertex& next) const {
    return emission(light, next, direction(light, next));
}
float Densities::emission(const PathVertex& light, const PathVertex& next, const Vec3& d) const {
    const int32_t e = emitter_of(light);
    if (e < 0) return 0.f;
    const Light& l = m_c.emitters[size_t(e)];
    // Point and spot lights (any radius): from their centre, as a point (see light_center_direction_pdf).
    if (std::holds_alternative<PointLight>(l))
        return solid_angle_to_area(light, next, light_center_direction_pdf(l, d));
    const EmitterPoint pt = emitter_point(light, d);
    float pos = 0.f, dir = 0.f;
    light_pdf_le(l, light.infinite ? next.p : light.p, pt.n, d, m_c.emitters.bounds(), &pos, &dir);
    if (light.infinite) return pos * (next.on_surface() ? std::fabs(dot(next.ng, d)) : 1.f);  // parallel rays
    return solid_angle_to_area(light, next, dir);
}
float Densities::origin(const PathVertex& v, const PathVertex& toward) const {
    const int32_t e = emitter_of(v);
    if (e < 0) return 0.f;
    if (std::holds_alternative<PointLight>(m_c.emitters[size_t(e)])) return m_c.emitters.pmf(uint32_t(e));
    const Vec3 d = direction(v, toward);
    const EmitterPoint pt = emitter_point(v, d);
    float pos = 0.f, dir = 0.f;
    light_pdf_le(m_c.emitters[size_t(e)], v.p, pt.n, d, m_c.emitters.bounds(), &pos, &dir);
    return m_c.emitters.pmf(uint32_t(e)) * (v.infinite ? dir : pos);
}

bool lens_strategy(const BdptContext& c, const PathVertex& light_end) {
    if (light_end.infinite || !c.s0_strategies || !c.scene.camera().connectable()) return false;
    const int32_t e = emitter_of(light_end);
    if (e < 0) return false;
    const Light& l = c.emitters[size_t(e)];
    if (const auto* area = std::get_if<AreaLight>(&l)) return area->visible_camera;
    if (std::holds_alternative<TriangleLight>(l))
        return !(c.scene.hidden_ray_types() & k_ray_camera) && !c.scene.has_holdouts();
    return false;  // point, spot and sun lights and the world: no camera ray hits them at a point
}

float strategy_weight(const BdptContext& c, const std::vector<PathVertex>& y, int s, const std::vector<PathVertex>& z,
                      int t, const PathVertex* sampled, const PathVertex* area, const KnownConnection& known) {
    // A two-vertex path: (0, 2) and (1, 1) where lens_strategy allows both, else (0, 2) alone.
    if (s + t == 2 && !lens_strategy(c, s == 0 ? (area ? *area : z[1]) : y[0])) return 1.f;
    const Densities d(c);
    // `sampled` is the fresh vertex of the connection: the camera's for t = 1, else the light's for s = 1.
    auto Y = [&](int i) -> const PathVertex& {
        return (t != 1 && s == 1 && i == 0 && sampled) ? *sampled : y[size_t(i)];
    };
    auto Z = [&](int i) -> const PathVertex& {
        if (t == 1 && i == 0 && sampled) return *sampled;
        if (area && i == t - 1) return *area;
        return z[size_t(i)];
    };
    const PathVertex* qs = s > 0 ? &Y(s - 1) : nullptr;
    const PathVertex* qs_minus = s > 1 ? &Y(s - 2) : nullptr;
    const PathVertex& pt = Z(t - 1);
    const PathVertex* pt_minus = t > 1 ? &Z(t - 2) : nullptr;
    // The reverse densities the connection changes, from the three unit directions they need (each made once:
    // direction(b, a) = −direction(a, b) exactly, as no connection joins two distant vertices).
    const Vec3 w_conn = !qs ? Vec3(0.f) : known.w ? *known.w : direction(*qs, pt);  // light side → camera side
    const Vec3 w_qs_prev = qs_minus ? direction(*qs, *qs_minus) : Vec3(0.f);
    const Vec3 w_pt_prev = pt_minus ? direction(pt, *pt_minus) : Vec3(0.f);
    const float pt_rev = qs ? d.light_side(*qs, qs_minus, pt, w_qs_prev, w_conn) : d.origin(pt, *pt_minus);
    const float pt_minus_rev = !pt_minus ? 0.f
                               : qs      ? d.light_side(pt, qs, *pt_minus, -w_conn, w_pt_prev)
                                         : d.emission(pt, *pt_minus, w_pt_prev);
    const float qs_rev = !qs                                   ? 0.f
                         : t == 1 && known.lens_pdf_dir >= 0.f ? solid_angle_to_area(pt, *qs, known.lens_pdf_dir)
                                                               : d.camera_side(pt, pt_minus, *qs, w_pt_prev, -w_conn);
    const float qs_minus_rev = qs_minus ? d.camera_side(*qs, &pt, *qs_minus, w_conn, w_qs_prev) : 0.f;
    const MisHeuristic h = c.settings.heuristic;
    const bool connectable = c.scene.camera().connectable();
    float sum = 0.f, ri = 1.f;
    for (int i = t - 1; i > 0; --i) {
        const float rev = i == t - 1 ? pt_rev : i == t - 2 ? pt_minus_rev : Z(i).pdf_rev;
        ri *= remap0(rev) / remap0(Z(i).pdf_fwd);
        const bool delta_i = i == t - 1 ? false : Z(i).delta;
        const bool delta_prev = i - 1 == t - 1 ? false : Z(i - 1).delta;
        if (!delta_i && !delta_prev && (i != 1 || connectable)) sum += heuristic(h, ri);
    }
    ri = 1.f;
    for (int i = s - 1; i >= 0; --i) {
        const float rev = i == s - 1 ? qs_rev : i == s - 2 ? qs_minus_rev : Y(i).pdf_rev;
        ri *= remap0(rev) / remap0(Y(i).pdf_fwd);
        const bool delta_i = i == s - 1 ? false : Y(i).delta;
        const bool delta_prev = i > 0 ? (i - 1 == s - 1 ? false : Y(i - 1).delta) : Y(0).delta_light;
        if (!delta_i && !delta_prev) sum += heuristic(h, ri);
    }
    return 1.f / (1.f + sum);
}

namespace {

Vec3 leave(const PathVertex& v, const Vec3& w) {
    if (!v.on_surface()) return v.p;
    return offset_ray_origin(v.p, dot(w, v.ng) > 0.f ? v.ng : -v.ng);
}

/// Whether the segment between two finite vertices (or toward a distant one) is unblocked for rays of `type`;
/// w = direction(a, b).
bool visible(const Scene& scene, const PathVertex& a, const PathVertex& b, const Vec3& w, uint8_t type,
             PathStats& stats) {
    ++stats.rays;
    const PrimitiveRef pa = a.kind == VertexKind::Surface ? a.hit.primitive : PrimitiveRef{};
    const PrimitiveRef pb = b.kind == VertexKind::Surface ? b.hit.primitive : PrimitiveRef{};
    const Vec3 o = leave(a, w);
    if (b.infinite) return !scene.occluded(o, w, std::numeric_limits<float>::infinity(), RayType(type), pa);
    const Vec3 target = b.on_surface() ? leave(b, -w) : b.p;
    const Vec3 seg = target - o;
    if (!(length_squared(seg) > 0.f)) return true;
    return !scene.occluded(o, seg, 1.f - k_shadow_epsilon, RayType(type), pa, pb);
}

/// Densities::camera_side's direction density for the lens vertex of connection `conn` (Camera::pdf_we of the ray
/// from the lens point toward the connected point, without a margin: 0 outside the frame), from what connect()
/// already computed — the same quantity (1/(A_img·cos³θ), or f²/(lens_area·cos³θ) for an orthographic lens)
/// evaluated from the same points, equal to it up to rounding.
float lens_direction_pdf(const Camera& camera, const CameraConnection& conn) {
    const Vec2 r = conn.raster;
    const bool in_frame =
        r.x >= 0.f && r.x <= float(camera.full_width()) && r.y >= 0.f && r.y <= float(camera.full_height());
    return in_frame ? conn.pdf_dir : 0.f;
}

/// The radiance an emitting camera vertex sends back along its path (s = 0).
Color emitted(const BdptContext& c, const PathVertex& v) {
    if (v.infinite) {
        const Light& l = c.emitters[size_t(v.emitter)];
        if (const auto* w = std::get_if<WorldLight>(&l)) return w->Le(v.w);
        return Color(0.f);
    }
    if (v.kind == VertexKind::Light) return v.Le;  // an area light hit (its radiance, set by the caller)
    return v.bsdf ? v.bsdf->shading(v.w).emission : Color(0.f);
}

/// Strategy (1, t) toward a soft point or spot light: the point next-event estimation samples — on the disk through
/// the light's centre facing camera vertex t − 1 (lights/point_light.h: the path tracer's and Cycles 3.4's model of
/// the light) — weighted as a path through the centre (Densities, light_center_direction_pdf).
StrategyResult connect_soft_point(const BdptContext& c, const std::vector<PathVertex>& y,
                                  const std::vector<PathVertex>& z, int t, const PathVertex& pt,
                                  const PointLight& light, uint32_t e, float pmf, Vec2 u_point, PathStats& stats) {
    StrategyResult r;
    const LightSample ls = light.sample_li(LightSampleContext{pt.p}, u_point);
    if (!(ls.pdf > 0.f) || is_black(ls.Li)) return r;
    const Color f = pt.bsdf->f(pt.w, ls.wi);
    if (is_black(f)) return r;
    PathVertex on_disk;  // for the shadow ray
    on_disk.kind = VertexKind::Light;
    on_disk.p = pt.p + ls.wi * ls.dist;
    PathVertex centre;  // for the weight
    centre.kind = VertexKind::Light;
    centre.p = light.position;
    centre.emitter = int32_t(e);
    centre.delta_light = true;
    centre.pdf_fwd = pmf;
    r.L = pt.beta * f * ls.Li * (pt.bsdf->camera_cosine(pt.w, ls.wi) / (pmf * ls.pdf));
    if (is_black(r.L) || !visible(c.scene, pt, on_disk, direction(pt, on_disk), k_ray_shadow, stats))
        return StrategyResult();
    r.weight = strategy_weight(c, y, 1, z, t, &centre, nullptr);
    return r;
}

}  // namespace

StrategyResult evaluate_strategy(const BdptContext& c, const std::vector<PathVertex>& y, int s,
                                 const std::vector<PathVertex>& z, int t,
                                 const std::vector<VertexNumbers>& camera_numbers,
                                 const std::vector<VertexNumbers>& light_numbers, const AreaLightHit* area,
                                 PathStats& stats) {
    StrategyResult r;
    const Scene& scene = c.scene;
    if (s == 0) {
        // The camera subpath's own end: an emitter it hit (or an area light it passed on segment t − 1).
        PathVertex area_vertex;
        const PathVertex* end = area ? nullptr : &z[size_t(t - 1)];
        if (area) {
            const AreaLight& al = std::get<AreaLight>(scene.lights()[area->light]);
            area_vertex.kind = VertexKind::Light;
            area_vertex.p = area->p;
            area_vertex.ng = al.normal;
            area_vertex.emitter = int32_t(area->light);
            area_vertex.Le = al.radiance;
            area_vertex.beta = area->beta;
            area_vertex.pdf_fwd = area->pdf_fwd;
            end = &area_vertex;
        }
        if (emitter_of(*end) < 0) return r;
        r.L = end->beta * emitted(c, *end);
        if (is_black(r.L)) return r;
        r.weight = strategy_weight(c, y, 0, z, t, nullptr, area ? &area_vertex : nullptr);
        return r;
    }
    if (t == 1) {
        // A connection from light vertex s − 1 to a fresh lens point, splatted where it lands.
        const PathVertex& qs = y[size_t(s - 1)];
        if (qs.infinite || (qs.kind == VertexKind::Surface && !scene.visible_to(qs.hit, k_ray_camera))) return r;
        CameraConnection conn;
        if (!scene.camera().connect(qs.p, light_numbers[size_t(s - 1)].u_point, &conn, c.camera_margin())) return r;
        PathVertex cam;
        cam.kind = VertexKind::Camera;
        cam.p = conn.lens_point;
        cam.pdf_fwd = conn.pdf_pos;
        Color f;
        float cosine;
        if (qs.kind == VertexKind::Light) {
            f = light_radiance(c.emitters[size_t(qs.emitter)], emitter_point(qs, conn.wi), conn.wi);
            cosine = qs.on_surface() ? std::fabs(dot(conn.wi, qs.ng)) : 1.f;
        } else {
            f = qs.bsdf->f(conn.wi, qs.w);
            cosine = std::fabs(dot(conn.wi, qs.ng)) * qs.bsdf->adjoint_factor(conn.wi, qs.w);
            if (scene.has_holdouts()) cosine *= 1.f - scene.holdout(qs.hit, conn.wi);
        }
        r.L = qs.beta * f * (cosine * conn.importance);
        const Vec3 w = direction(qs, cam);
        if (is_black(r.L) || !visible(scene, qs, cam, w, k_ray_camera, stats)) return StrategyResult();
        r.splat = true;
        r.raster = conn.raster;
        r.weight = strategy_weight(c, y, s, z, 1, &cam, nullptr, {&w, lens_direction_pdf(scene.camera(), conn)});
        return r;
    }
    const PathVertex& pt = z[size_t(t - 1)];
    if (pt.kind != VertexKind::Surface) return r;
    if (s == 1) {
        // A fresh point on an emitter, connected to camera vertex t − 1 (next-event estimation in area measure).
        const VertexNumbers& u = camera_numbers[size_t(t - 1)];
        float pmf = 0.f;
        if (c.emitters.empty()) return r;
        const uint32_t e = c.emitters.select(u.u_select, &pmf);
        if (!(pmf > 0.f)) return r;
        const Light& light = c.emitters[e];
        if (const auto* point = std::get_if<PointLight>(&light); point && point->radius > 0.f)
            return connect_soft_point(c, y, z, t, pt, *point, e, pmf, u.u_point, stats);
        const EmitterPoint ep = light_sample_point(light, u.u_point, u.u_point, 0.5f);
        if (!ep.valid()) return r;
        PathVertex lv;
        lv.kind = VertexKind::Light;
        lv.emitter = int32_t(e);
        lv.infinite = ep.infinite;
        lv.p = ep.infinite ? Vec3(0.f) : ep.p;
        lv.ng = ep.n;
        lv.w = ep.omega;
        lv.Le = ep.Le;
        lv.hit.b1 = ep.b1;
        lv.hit.b2 = ep.b2;
        lv.delta_light = !light_hittable(light);
        lv.pdf_fwd = pmf * ep.pdf_pos;
        const Vec3 w_l = direction(pt, lv);
        const Color f = pt.bsdf->f(pt.w, w_l);
        if (is_black(f)) return r;
        const Color Le = light_radiance(light, ep, -w_l);
        if (is_black(Le)) return r;
        float g = pt.bsdf->camera_cosine(pt.w, w_l);
        if (!ep.infinite) {
            const float d2 = length_squared(lv.p - pt.p);
            g /= d2;
            if (!ep.delta_pos) g *= std::fabs(dot(ep.n, w_l));
        }
        r.L = pt.beta * f * Le * (g / (pmf * ep.pdf_pos));
        if (!visible(scene, pt, lv, w_l, k_ray_shadow, stats)) return StrategyResult();
        const Vec3 w_conn = -w_l;  // direction(lv, pt) exactly: negation and normalize commute
        r.weight = strategy_weight(c, y, 1, z, t, &lv, nullptr, {&w_conn});
        return r;
    }
    // s ≥ 2, t ≥ 2: join light vertex s − 1 and camera vertex t − 1.
    const PathVertex& qs = y[size_t(s - 1)];
    if (qs.kind != VertexKind::Surface) return r;
    const Vec3 w = normalize(pt.p - qs.p);  // from the light vertex toward the camera vertex
    const Color f_light = qs.bsdf->f(w, qs.w);
    if (is_black(f_light)) return r;
    const Color f_camera = pt.bsdf->f(pt.w, -w);
    if (is_black(f_camera)) return r;
    const float d2 = length_squared(pt.p - qs.p);
    const float g = std::fabs(dot(w, qs.ng)) * qs.bsdf->adjoint_factor(w, qs.w) * pt.bsdf->camera_cosine(pt.w, -w) / d2;
    r.L = qs.beta * f_light * f_camera * pt.beta * g;
    if (is_black(r.L) || !visible(scene, qs, pt, w, k_ray_shadow, stats)) return StrategyResult();
    r.weight = strategy_weight(c, y, s, z, t, nullptr, nullptr, {&w});
    return r;
}

}  // namespace candela
