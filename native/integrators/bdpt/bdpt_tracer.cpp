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

namespace {

/// The t = 1 strategy's unweighted splat, or the camera sample's own, handed on checked (non-finite or negative
/// contributions are dropped and counted).
template <class Emit>
void emit_checked(const StrategyResult& r, PathStats& stats, Emit&& emit) {
    if (is_black(r.L) || !(r.weight > 0.f)) return;
    const Color weighted = r.L * r.weight;
    if (!is_finite(weighted) || min_component(weighted) < 0.f) {
        ++stats.nan_samples;
        return;
    }
    emit(weighted, r);
}

/// Every strategy (s, t) of the subpaths in `w` (nz camera and ny light vertices), weighted, to `emit`; each
/// evaluated strategy, unweighted and unchecked, to `record(result, s, t)` first (strategy images).
struct NoRecord {
    void operator()(const StrategyResult&, int, int) const {}
};
template <class Emit, class Record = NoRecord>
void all_strategies(const BdptContext& c, Scratch& w, int nz, int ny, PathStats& stats, Emit&& emit,
                    Record&& record = Record{}) {
    const int max_depth = c.settings.max_bounces + 1;  // scattering vertices of a path: s + t − 2
    for (int t = 1; t <= nz; ++t)
        for (int s = 0; s <= ny; ++s) {
            const int depth = s + t - 2;
            if (depth < 0 || depth > max_depth || (s == 0 && t == 1)) continue;
            if (s == 0 && !c.s0_strategies) continue;  // nothing a ray can hit emits: zero, not evaluated
            // (1, 1), the emitter point joined to the lens: only for emitters a camera ray can hit (strategy.h).
            if (s == 1 && t == 1 && !lens_strategy(c, w.light[0])) continue;
            const StrategyResult r =
                evaluate_strategy(c, w.light, s, w.camera, t, w.camera_numbers, w.light_numbers, nullptr, stats);
            record(r, s, t);
            emit_checked(r, stats, emit);
        }
    // The area lights the camera subpath passed: strategies s = 0 ending on them.
    for (const AreaLightHit& a : w.area_hits) {
        const int t = a.segment + 1;
        if (t - 2 > max_depth) continue;
        const StrategyResult r =
            evaluate_strategy(c, w.light, 0, w.camera, t, w.camera_numbers, w.light_numbers, &a, stats);
        record(r, 0, t);
        emit_checked(r, stats, emit);
    }
}

}  // namespace

Color BdptTracer::Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov,
                     SplatSink sink) const {
    *alpha = 1.f;
    thread_local Scratch scratch;
    Scratch& w = scratch;
    const BdptContext& c = m_context;
    w.fit(c);
    const int nz = camera_subpath(c, camera_ray, sampler, w.camera, w.camera_numbers, w.area_hits, stats, alpha, aov);
    const int ny = light_subpath(c, sampler, w.light, w.light_numbers, stats);
    Color L(0.f);
    const StrategyRecording& rec = strategy_recording();
    auto record = [&](const StrategyResult& r, int s, int t) {
        if (rec.buffer && !is_black(r.L) && is_finite(r.L) && min_component(r.L) >= 0.f)
            rec.images->record(*rec.buffer, s, t, r.L, r.weight, r.raster, r.splat, sink.x, sink.y);
    };
    all_strategies(
        c, w, nz, ny, stats,
        [&](const Color& weighted, const StrategyResult& r) {
            if (r.splat) {
                if (sink.buffer) sink.buffer->add(r.raster, weighted, sink.replicate);
            } else {
                L += weighted;
            }
        },
        record);
    return L;
}

void BdptTracer::sample_all(const Ray& camera_ray, PrimarySampleSampler& u, PathStats& stats,
                            std::vector<Contribution>& out) const {
    thread_local Scratch scratch;
    Scratch& w = scratch;
    const BdptContext& c = m_context;
    w.fit(c);
    const int nz = camera_subpath(c, camera_ray, u, w.camera, w.camera_numbers, w.area_hits, stats, c.max_camera());
    const int ny = light_subpath(c, u, w.light, w.light_numbers, stats, c.max_light());
    all_strategies(c, w, nz, ny, stats, [&](const Color& weighted, const StrategyResult& r) {
        out.push_back({weighted, r.splat, r.raster});
    });
}

void BdptTracer::sample_strategy(const Ray& camera_ray, PrimarySampleSampler& u, int s, int t, PathStats& stats,
                                 std::vector<Contribution>& out) const {
    thread_local Scratch scratch;
    Scratch& w = scratch;
    const BdptContext& c = m_context;
    w.fit(c);
    if (s + t - 2 > c.settings.max_bounces + 1 || t < 1 || s < 0 || (t == 1 && s == 0)) return;
    const int nz = camera_subpath(c, camera_ray, u, w.camera, w.camera_numbers, w.area_hits, stats, t);
    // s = 1 with t ≥ 2 needs no light subpath (it samples its emitter point from the camera vertex's numbers);
    // (1, 1) joins the light subpath's origin to the lens.
    const bool needs_light = s >= 2 || (s == 1 && t == 1);
    const int ny = needs_light ? light_subpath(c, u, w.light, w.light_numbers, stats, s) : s;
    if (ny < s) return;
    if (s == 1 && t == 1 && !lens_strategy(c, w.light[0])) return;
    auto emit = [&](const Color& weighted, const StrategyResult& r) { out.push_back({weighted, r.splat, r.raster}); };
    if (nz == t)
        emit_checked(evaluate_strategy(c, w.light, s, w.camera, t, w.camera_numbers, w.light_numbers, nullptr, stats),
                     stats, emit);
    if (s == 0)
        for (const AreaLightHit& a : w.area_hits)
            if (a.segment + 1 == t)
                emit_checked(
                    evaluate_strategy(c, w.light, 0, w.camera, t, w.camera_numbers, w.light_numbers, &a, stats), stats,
                    emit);
}

}  // namespace candela
