#include "integrators/mlt/path_space.h"

#include <algorithm>
#include <optional>

#include "scene/shutter_time.h"

namespace candela {

// Depth 0 counts (1, 1) too: where a path's emitter has no lens strategy (bdpt/strategy.h) it gives nothing and
// (0, 2) keeps the weight 1, so the estimate, divided by the pmf 1/2, stays unbiased.
int mmlt_strategy_count(int depth) { return depth + 2; }

StrategyChoice mmlt_choose_strategy(int depth, float u) {
    const int n = mmlt_strategy_count(depth);
    return {std::min(int(u * float(n)), n - 1), 1.f / float(n)};
}

float mmlt_strategy_pmf(int depth, int s) {
    const int n = mmlt_strategy_count(depth);
    return s >= 0 && s < n ? 1.f / float(n) : 0.f;
}

PathSpace::PathSpace(const Scene& scene, const BdptSettings& settings, const EmitterSet& emitters)
    : m_tracer(scene, settings, emitters),
      m_camera(scene.camera()),
      m_margin(m_tracer.context().camera_margin()),
      m_motion(scene.has_motion()) {
    const double w = m_camera.full_width(), h = m_camera.full_height();
    m_frame_area = w * h;
    m_area = (w + 2.0 * m_margin) * (h + 2.0 * m_margin);
}

uint32_t PathSpace::strategy_dim() const {
    const BdptContext& c = m_tracer.context();
    // The light subpath's bounces start at light_dim_bounce() and take at most max_light() of them.
    return dimension_index(Dim::LightSelect, c.light_dim_bounce() + c.max_light() + 1);
}

uint32_t PathSpace::shutter_dim() const { return strategy_dim() + 1; }

void PathSpace::evaluate(PrimarySampleSampler& u, int depth, PathStats& stats, MltSample& out) const {
    out.clear();
    // Motion blur: the shutter time is one more coordinate of the state (read only when the scene moves, so a
    // still scene's chains draw exactly the coordinates they did), seen by the whole bidirectional path.
    std::optional<ShutterScope> scope;
    if (m_motion) scope.emplace(u.sample_1d(shutter_dim()));
    const Vec2 uf = u.sample_2d(dimension_index(Dim::Filter));
    const float w = float(m_camera.full_width()), h = float(m_camera.full_height());
    const Vec2 raster{-m_margin + uf.x * (w + 2.f * m_margin), -m_margin + uf.y * (h + 2.f * m_margin)};
    const Vec2 u_lens = m_camera.has_aperture() ? u.sample_2d(dimension_index(Dim::Lens)) : Vec2{0.5f, 0.5f};
    const Ray ray = m_camera.generate_ray(raster, u_lens);
    ++stats.paths;
    float scale = 1.f;
    if (depth < 0) {
        m_tracer.sample_all(ray, u, stats, out.contributions);
    } else {
        // Strategy s of the k + 2 with s + t − 2 = k, its contribution divided by the probability of choosing it.
        const StrategyChoice c = mmlt_choose_strategy(depth, u.sample_1d(strategy_dim()));
        m_tracer.sample_strategy(ray, u, c.s, depth + 2 - c.s, stats, out.contributions);
        scale = float(mmlt_strategy_count(depth));  // 1 / c.pmf, exactly
    }
    const float splat_scale = float(m_frame_area / m_area);
    Color sum(0.f);
    for (BdptTracer::Contribution& c : out.contributions) {
        c.L *= c.splat ? scale * splat_scale : scale;
        if (!c.splat) c.raster = raster;
        sum += c.L;
    }
    const float I = luminance(sum);
    out.importance = is_finite(sum) && I > 0.f ? I : 0.f;
    if (!(out.importance > 0.f)) out.contributions.clear();
}

}  // namespace candela
