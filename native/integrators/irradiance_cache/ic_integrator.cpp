#include "integrators/irradiance_cache/ic_integrator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel_ordered.h"
#include "core/rng.h"
#include "integrators/camera_tiles.h"
#include "integrators/irradiance_cache/ic_cache.h"
#include "integrators/progressive_driver.h"
#include "lights/light_sampler.h"
#include "scene/shutter_time.h"

namespace candela {

size_t ic_record_capacity(const IcSettings& s, double film_pixels) {
    const double spacing = std::max(double(s.min_spacing), 0.5);
    return size_t(std::ceil(film_pixels / (spacing * spacing))) + 4096;
}

double ic_memory_bytes(const Params& params, double film_pixels) {
    return double(ic_record_capacity(IcSettings::from_params(params), film_pixels)) * double(k_ic_bytes_per_record);
}

/// The pre-pass's sub-pass of full-frame pixel (fx, fy) at stride s (coarsest: `top`), or -1 if it is not a grid
/// point first visited at that stride. A level's points are split by the parity of their grid coordinates
/// (fx/s, fy/s) into sub-passes, each reading the cache the earlier ones completed: first the points farthest from
/// the points already visited — at a finer level the centres of the coarser grid's squares (odd, odd), then the
/// midpoints of its edges (odd, even), (even, odd); at the coarsest, (0, 0), (1, 1), (1, 0), (0, 1) — so that
/// neighbouring points of one level do not all gather where one record would have served them.
int ic_prepass_sub_pass(int fx, int fy, int s, int top) {
    if (fx % s != 0 || fy % s != 0) return -1;
    const int ox = (fx / s) & 1, oy = (fy / s) & 1;
    if (s == top) return ox == oy ? ox : 2 + oy;  // (0,0) 0, (1,1) 1, (1,0) 2, (0,1) 3
    if (ox == 0 && oy == 0) return -1;            // a point of a coarser level
    return ox && oy ? 0 : 1 + oy;                 // (1,1) 0, (1,0) 1, (0,1) 2
}

namespace {

/// The coarsest pre-pass grid: the largest power of two ≤ the maximum spacing (at least 1, at most 64 pixels).
int coarsest_stride(float max_spacing) {
    int s = 1;
    while (s * 2 <= std::min(64.f, max_spacing)) s *= 2;
    return s;
}

constexpr int k_prepass_sub_passes = 4;  // at most, per level

class IcIntegrator final : public Integrator {
public:
    IcIntegrator(const Params& params, const IcProbe* probe)
        : m_settings(IcSettings::from_params(params)), m_probe(probe) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        m_logged_full = false;
        m_candidates = 0;
        if (scene.has_motion()) return render_moving(scene, film, ctx);
        const LightSampler light_sampler = make_light_sampler("TREE", scene.lights());
        const IcCacheRules rules = cache_rules(film);
        IcCache cache(scene.bounds(), rules);
        IcTracer tracer(scene, m_settings, light_sampler, cache, PixelFootprint::of(scene.camera()), ctx.cancel,
                        m_probe);
        State state{scene, film, ctx, cache, tracer};
        state.seed = m_settings.pixel.seed;
        if (!prepass(state)) {
            ctx.counters.stop_reason = int(StopReason::Cancelled);
            return;
        }
        const size_t from_prepass = cache.size(), prepass_gathers = m_candidates;
        render_passes(state);
        ctx.info("irradiance cache: " + std::to_string(cache.size()) + " records (" + std::to_string(from_prepass) +
                 " from the pre-pass, " + std::to_string(cache.size() - from_prepass) +
                 " added while rendering; gathers: " + std::to_string(prepass_gathers) + " in the pre-pass, " +
                 std::to_string(m_candidates - prepass_gathers) + " while rendering)");
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "sample"}; }
    // Motion blur: one shutter time per pass, with a cache of that time (render_moving).
    uint32_t honoured_features() const override { return k_feature_motion_blur; }

private:
    struct State {
        const Scene& scene;
        Film& film;
        RenderContext& ctx;
        IcCache& cache;
        IcTracer& tracer;
        uint64_t seed = 0;                            // of the pre-pass gathers' keys
        float time = k_shutter_middle;                // the shutter time every path of this cache sees
        const std::vector<float>* earlier = nullptr;  // IC Records of earlier shutter passes (motion blur)
    };

    IcCacheRules cache_rules(const Film& film) const {
        IcCacheRules rules;
        rules.a = m_settings.error;
        rules.gradients = m_settings.gradients;
        rules.neighbour_clamping = m_settings.neighbour_clamping;
        rules.capacity = ic_record_capacity(m_settings, double(film.width()) * film.height());
        return rules;
    }

    /// Motion blur: the samples are rendered as T = Samples shutter passes, pass j at one time τ_j
    /// (stratified_shutter_time: one τ in each 1/T of the shutter). Each pass builds a cache of its own at τ_j — the
    /// pre-pass, then sample j of every pixel, which reads it and completes it — so no record is interpolated at a
    /// point of another time, and the film's mean over the passes is the time average. A cache built per pass
    /// costs its gathers T times over, so a pass's records gather M_t = max(⌈M/T⌉, 64) rays (M = Gather Rays; M
    /// itself if it is below 64): a record's E is unbiased for any M_t and its variance ∝ 1/M_t, and the T passes'
    /// caches are independent, so their average holds T·M_t ≥ M rays' worth of record noise, what one cache of M
    /// rays has; the interpolation's bias is set by a and the spacing limits, which do not change. 64 rays (5 × 13
    /// strata) is the least kept for R and the gradients, which a pass uses and the average does not smooth. The
    /// gathers then cost max(1, 64·T/M) times the still render's. One cache exists at a time.
    void render_moving(const Scene& scene, Film& film, RenderContext& ctx) {
        const int64_t passes = m_settings.pixel.samples;
        IcSettings pass_settings = m_settings;
        constexpr int k_min_rays = 64;
        if (m_settings.gather_rays > k_min_rays)
            pass_settings.gather_rays =
                int(std::max<int64_t>(k_min_rays, (int64_t(m_settings.gather_rays) + passes - 1) / passes));
        const LightSampler light_sampler = make_light_sampler("TREE", scene.lights());
        const IcCacheRules rules = cache_rules(film);
        const PixelFootprint footprint = PixelFootprint::of(scene.camera());
        const uint64_t time_key = hash_combine(m_settings.pixel.seed, 0x6963206d62ULL);
        std::vector<float> earlier(size_t(film.width()) * film.height(), 0.f);
        const GatherStrata strata = GatherStrata::for_rays(pass_settings.gather_rays);
        ctx.info("irradiance cache: motion blur: " + std::to_string(passes) +
                 " shutter passes of one sample per pixel, each with a cache of its own time, gathers of " +
                 std::to_string(strata.count()) + " rays");
        size_t records = 0;
        int64_t built = 0;
        ProgressivePlan plan;
        plan.total = passes;
        plan.max_pass = camera_max_pass(film, m_settings.pixel);
        plan.time_limit = m_settings.pixel.time_limit;
        plan.noise_threshold = m_settings.pixel.noise_threshold;
        run_progressive(
            ctx, plan,
            [&](int64_t begin, int64_t end) {
                for (int64_t j = begin; j < end && !ctx.cancel.cancelled(); ++j) {
                    IcCache cache(scene.bounds(), rules);
                    IcTracer tracer(scene, pass_settings, light_sampler, cache, footprint, ctx.cancel, m_probe);
                    State state{scene, film, ctx, cache, tracer};
                    state.seed = hash_combine(m_settings.pixel.seed, uint64_t(j));
                    state.time = stratified_shutter_time(time_key, uint64_t(j), uint64_t(passes));
                    state.earlier = &earlier;
                    if (!prepass(state)) return;  // the driver sees the cancel
                    tracer.set_stage(IcStage::Render);
                    const CameraTilePass<IcTracer> tiles(scene, film, ctx, m_settings.pixel, tracer);
                    render_range(state, tiles, j, j + 1);
                    if (ctx.cancel.cancelled()) return;
                    for (const IcRecord& r : cache.records()) {
                        const int x = r.pixel_x - film.origin_x(), y = r.pixel_y - film.origin_y();
                        if (x >= 0 && y >= 0 && x < film.width() && y < film.height())
                            earlier[size_t(y) * film.width() + x] += 1.f;
                    }
                    records += cache.size();
                    ++built;
                }
            },
            NoiseSource{});
        if (built > 0)
            ctx.info("irradiance cache: " + std::to_string(records) + " records in " + std::to_string(built) +
                     " caches (" + std::to_string(records / size_t(built)) + " per shutter pass)");
    }

    /// Inserts a pass's candidates (the cache is not read meanwhile) in raster order — by the full-frame pixel
    /// whose path made them, bottom row first, and for one pixel in the order its samples ran, which is fixed — so
    /// the order depends neither on the thread count nor on the tiles; then shows the new state.
    void merge(State& s, std::vector<IcRecord>& pending) {
        std::stable_sort(pending.begin(), pending.end(), [](const IcRecord& a, const IcRecord& b) {
            return a.pixel_y != b.pixel_y ? a.pixel_y < b.pixel_y : a.pixel_x < b.pixel_x;
        });
        size_t dropped = 0;
        m_candidates += pending.size();
        for (const IcRecord& r : pending)
            if (s.cache.full())
                ++dropped;
            else
                s.cache.insert(r);
        if (dropped && !m_logged_full) {
            m_logged_full = true;
            s.ctx.log("irradiance cache full at " + std::to_string(s.cache.size()) +
                      " records (its memory estimate): further records are used where made but not stored");
        }
        s.ctx.counters.stage.set_note(std::to_string(s.cache.size()) + " records");
        write_records_pass(s);
    }

    /// The "IC Records" pass: how many records each pixel's paths made.
    void write_records_pass(State& s) {
        AovFilm* aovs = s.ctx.aovs;
        if (!aovs || !aovs->enabled("IC Records")) return;
        const int w = s.film.width(), h = s.film.height();
        std::vector<float> count = s.earlier ? *s.earlier : std::vector<float>(size_t(w) * h, 0.f);
        for (const IcRecord& r : s.cache.records()) {
            const int x = r.pixel_x - s.film.origin_x(), y = r.pixel_y - s.film.origin_y();
            if (x >= 0 && y >= 0 && x < w && y < h) count[size_t(y) * w + x] += 1.f;
        }
        aovs->set_pass("IC Records", std::move(count));
    }

    /// The pre-pass: grids of stride 2^k, …, 2, 1 pixels, each level in sub-passes (ic_prepass_sub_pass); at each point
    /// the camera ray's first Lambertian surface gets a record where none of the earlier sub-passes' is usable. A
    /// sub-pass reads the cache as the earlier ones left it; its records are merged in raster order (merge). False
    /// if cancelled.
    bool prepass(State& s) {
        const Film& film = s.film;
        const int top = coarsest_stride(m_settings.max_spacing);
        const int x0 = film.origin_x(), y0 = film.origin_y();
        int64_t total = 0;
        for (int st = top; st >= 1; st /= 2)
            for (int y = 0; y < film.height(); ++y)
                for (int x = 0; x < film.width(); ++x) total += ic_prepass_sub_pass(x0 + x, y0 + y, st, top) >= 0;
        s.ctx.counters.stage.begin("Irradiance cache", total, /*percent=*/true);
        s.ctx.counters.stage.set_note("0 records");
        s.tracer.set_stage(IcStage::Prepass);
        std::atomic<int64_t> done{0};
        const auto& tiles = film.tiles();
        for (int st = top; st >= 1; st /= 2)
            for (int sub = 0; sub < k_prepass_sub_passes; ++sub) {
                std::vector<IcRecord> pending;
                try {
                    parallel_ordered(
                        s.ctx.threads, tiles.size(), size_t(2 * std::max(1, s.ctx.threads)),
                        [&](size_t t) {
                            const ShutterScope scope(s.time);
                            const Tile& tile = tiles[t];
                            std::vector<IcRecord> out;
                            PathStats stats;
                            int64_t points = 0;
                            for (int y = tile.y0; y < tile.y1 && !s.ctx.cancel.cancelled(); ++y)
                                for (int x = tile.x0; x < tile.x1; ++x) {
                                    const int fx = x0 + x, fy = y0 + y;
                                    if (ic_prepass_sub_pass(fx, fy, st, top) != sub) continue;
                                    ++points;
                                    const uint64_t key = hash_values(s.seed, uint64_t(st),
                                                                     (uint64_t(uint32_t(fy)) << 32) | uint32_t(fx));
                                    IcRecord r;
                                    if (s.tracer.prepass_record(fx, fy, key, stats, &r)) out.push_back(r);
                                }
                            stats.flush(s.ctx.counters);
                            s.ctx.counters.stage.set_done(done += points);
                            return out;
                        },
                        [&](size_t, std::vector<IcRecord>&& out) {
                            pending.insert(pending.end(), out.begin(), out.end());
                        },
                        &s.ctx.cancel);
                } catch (const Cancelled&) {
                    return false;
                }
                if (s.ctx.cancel.cancelled()) return false;
                merge(s, pending);
            }
        s.ctx.counters.stage.end();
        return true;
    }

    /// The progressive render: camera samples through the tile loop, each pass reading the cache as the previous
    /// left it; records its paths make (where none was usable) are merged after it in raster order. No noise source:
    /// both noise replicates read one cache, so their agreement says nothing of its error (the driver logs that
    /// and keeps the noise stop off).
    void render_passes(State& s) {
        const CameraTilePass<IcTracer> tiles(s.scene, s.film, s.ctx, m_settings.pixel, s.tracer);
        s.tracer.set_stage(IcStage::Render);
        ProgressivePlan plan;
        plan.total = m_settings.pixel.samples;
        plan.max_pass = camera_max_pass(s.film, m_settings.pixel);
        plan.time_limit = m_settings.pixel.time_limit;
        plan.noise_threshold = m_settings.pixel.noise_threshold;
        run_progressive(
            s.ctx, plan, [&](int64_t begin, int64_t end) { render_range(s, tiles, begin, end); }, NoiseSource{});
    }

    /// Samples [begin, end) of every pixel reading the cache as it is; the records they make are merged after.
    void render_range(State& s, const CameraTilePass<IcTracer>& tiles, int64_t begin, int64_t end) {
        std::vector<IcRecord> pending;
        try {
            parallel_ordered(
                s.ctx.threads, s.film.tiles().size(), size_t(2 * std::max(1, s.ctx.threads)),
                [&](size_t t) {
                    const ShutterScope scope(s.time);
                    std::vector<IcRecord> out;
                    struct Sink {  // the tracer's records go to `out` while this tile renders
                        explicit Sink(std::vector<IcRecord>* v) { IcTracer::set_sink(v); }
                        ~Sink() { IcTracer::set_sink(nullptr); }
                    } sink(&out);
                    tiles.render_tile(t, int(begin), int(end));
                    return out;
                },
                [&](size_t, std::vector<IcRecord>&& out) { pending.insert(pending.end(), out.begin(), out.end()); },
                &s.ctx.cancel);
        } catch (const Cancelled&) {
            return;  // the driver sees the cancel
        }
        if (!s.ctx.cancel.cancelled()) merge(s, pending);
    }

    IcSettings m_settings;
    const IcProbe* m_probe;
    bool m_logged_full = false;  // "cache full" is logged once per render
    size_t m_candidates = 0;     // records made (each a gather), stored or not
};

}  // namespace

std::unique_ptr<Integrator> make_ic_integrator(const Params& params) {
    return std::make_unique<IcIntegrator>(params, nullptr);
}

std::unique_ptr<Integrator> make_ic_integrator(const Params& params, const IcProbe* probe) {
    return std::make_unique<IcIntegrator>(params, probe);
}

}  // namespace candela
