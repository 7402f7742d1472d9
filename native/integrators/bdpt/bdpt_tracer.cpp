#include "integrators/bdpt/bdpt_tracer.h"


namespace candela {

namespace {

/// Per-thread vertex storage (a surface vertex's BSDF refers to its own hit: vertices stay where they are).
struct Scratch {
    std::vector<PathVertex> camera, light;
    std::vector<VertexNumbers> camera_numbers, light_numbers;
    std::vector<AreaLightHit> area_hits;
    void fit(const BdptContext& c) {
        if (int(camera.size()) < c.max_camera()) {
            camera = std::vector<PathVertex>(size_t(c.max_camera()));
            camera_numbers.resize(size_t(c.max_camera()));
        }
        if (int(light.size()) < c.max_light()) {
            light = std::vector<PathVertex>(size_t(c.max_light()));
            light_numbers.resize(size_t(c.max_light()));
        }
    }
};

}  // namespace

StrategyRecording& strategy_recording() {
    thread_local StrategyRecording recording;
    return recording;
}

Color BdptTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov,
                     SplatSink sink) const {
    *alpha = 1.f;
    thread_local Scratch scratch;
    Scratch& w = scratch;
    const BdptContext& c = m_context;
    w.fit(c);
    const int nz = camera_subpath(c, camera_ray, sampler, w.camera, w.camera_numbers, w.area_hits, stats, alpha, aov);
    const int ny = light_subpath(c, sampler, w.light, w.light_numbers, stats);
    const int max_depth = c.settings.max_bounces + 1;  // scattering vertices of a path: s + t − 2
    Color L(0.f);
    const StrategyRecording& rec = strategy_recording();
    auto add = [&](const StrategyResult& r, int s, int t) {
        if (rec.buffer && !is_black(r.L) && is_finite(r.L) && min_component(r.L) >= 0.f)
            rec.images->record(*rec.buffer, s, t, r.L, r.weight, r.raster, r.splat, sink.x, sink.y);
        if (is_black(r.L) || !(r.weight > 0.f)) return;
        const Color weighted = r.L * r.weight;
        if (!is_finite(weighted) || min_component(weighted) < 0.f) {
            ++stats.nan_samples;
            return;
        }
        if (r.splat) {
            if (sink.buffer) sink.buffer->add(r.raster, weighted, sink.replicate);
        } else {
            L += weighted;
        }
    };
    for (int t = 1; t <= nz; ++t)
        for (int s = 0; s <= ny; ++s) {
            const int depth = s + t - 2;
            // (1, 1), an emitter connected to the lens, is left to (0, 2), the camera ray that sees it: its weight
            // would be tiny wherever the emitter is visible, and strategy_weight counts paths of two vertices as (0, 2)'s.
            if (depth < 0 || depth > max_depth || (s == 0 && t == 1) || (s == 1 && t == 1)) continue;
            add(evaluate_strategy(c, w.light, s, w.camera, t, w.camera_numbers, w.light_numbers, nullptr, stats), s, t);
        }
    // The area lights the camera subpath passed: strategies s = 0 ending on them.
    for (const AreaLightHit& a : w.area_hits) {
        const int t = a.segment + 1;
        if (t - 2 > max_depth) continue;
        add(evaluate_strategy(c, w.light, 0, w.camera, t, w.camera_numbers, w.light_numbers, &a, stats), 0, t);
    }
    return L;
}

}  // namespace candela
