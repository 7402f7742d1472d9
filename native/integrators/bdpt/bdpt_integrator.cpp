#include "integrators/bdpt/bdpt_integrator.h"

#include <algorithm>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/parallel_ordered.h"
#include "film/aov_film.h"
#include "integrators/bdpt/bdpt_tracer.h"
#include "integrators/camera_tiles.h"

namespace candela {

namespace {

/// The strategy images as the integrator's passes ("BDPT d1 s1 t2", ...), where the render asked for them.
void publish_strategy_images(const StrategyImages& strategies, RenderContext& ctx) {
    if (!ctx.aovs) return;
    for (auto& [name, rgb] : strategies.images()) ctx.aovs->set_pass(name, std::move(rgb));
}

/// Throws for a panoramic camera, before the scene is built: the t = 1 strategies connect vertices to the lens,
/// and the camera vertex's stored densities come from pdf_we; Camera::connect, raster_of and pdf_we invert a
/// perspective or orthographic viewplane and are not derived for a panorama. Refused by name rather than rendered
/// with t = 1 dropped (as for the orthographic pinhole): that variant has no agreement test for a panorama.
void check_camera(const Params& params) {
    if (params.get<std::string>("camera_type", "PERSP") == "PANO")
        throw InvalidParameter("integrator BDPT: " + Camera::panoramic_not_connectable_message(params.get<std::string>(
                                                         "panorama_type", "FISHEYE_EQUISOLID")));
}

class BdptIntegrator final : public Integrator {
public:
    explicit BdptIntegrator(const Params& params) : m_settings(BdptSettings::from_params(params)) {
        check_camera(params);
    }

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        // The params were checked; a scene whose camera was replaced since (Scene::set_camera) is checked here.
        if (scene.camera().is_panoramic())
            throw InvalidParameter("integrator BDPT: " + scene.camera().not_connectable_message());
        const EmitterSet& emitters = scene.emitters();
        if (scene.hidden_ray_types() & (k_ray_diffuse | k_ray_glossy | k_ray_transmission))
            ctx.log(
                "BDPT: objects hidden from diffuse, glossy or transmission rays are visible to light subpaths and "
                "connections (only camera and shadow visibility are honoured)");
        if (!scene.camera().connectable())
            ctx.log("BDPT: " + scene.camera().not_connectable_kind() +
                    " has no light-tracing strategy (t = 1): the other strategies render the image");
        const BdptTracer tracer(scene, m_settings, emitters);
        std::optional<StrategyImages> strategies;
        if (m_settings.strategy_images)
            strategies.emplace(std::min(m_settings.strategy_depth, m_settings.max_bounces + 1), film.width(),
                               film.height(), film.origin_x(), film.origin_y());
        const PixelSampling& ps = m_settings.pixel;
        // Motion blur: the camera and light subpaths of one sample share its shutter time (CameraTilePass).
        const CameraTilePass<BdptTracer> tiles(scene, film, ctx, ps, tracer, /*motion_blur=*/true);
        const double frame_pixels = double(scene.camera().full_width()) * scene.camera().full_height();
        struct TileSplats {
            SplatBuffer buffer;
            StrategyImages::Buffer strategies;
            bool complete = false;
        };
        ProgressivePlan plan;
        plan.total = ps.samples;
        plan.max_pass = camera_max_pass(film, ps);
        plan.time_limit = ps.time_limit;
        plan.noise_threshold = ps.noise_threshold;
        run_progressive(
            ctx, plan,
            [&](int64_t begin, int64_t end) {
                parallel_ordered(
                    ctx.threads, film.tiles().size(), size_t(2 * resolve_thread_count(ctx.threads)),
                    [&](size_t t) {
                        TileSplats out;
                        StrategyRecording& rec = strategy_recording();
                        if (strategies) rec = {&*strategies, &out.strategies};
                        out.complete = tiles.render_tile(t, int(begin), int(end), &out.buffer);
                        rec = {};
                        return out;
                    },
                    [&](size_t t, TileSplats&& splats) {
                        if (!splats.complete) return;
                        // t = 1 splats: one light subpath per camera sample, counted per pixel of the full frame.
                        const Tile& tile = film.tiles()[t];
                        const double share = double(tile.width()) * tile.height() / frame_pixels;
                        double samples[k_noise_replicates] = {};
                        for (int64_t s = begin; s < end; ++s) samples[noise_replicate_of(uint32_t(s))] += share;
                        film.add_splats(splats.buffer, ps.filter, samples);
                        if (strategies) strategies->merge(splats.strategies, samples[0] + samples[1]);
                    },
                    &ctx.cancel);
            },
            [&] { return film.noise_estimate(); });
        if (strategies) publish_strategy_images(*strategies, ctx);
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "sample"}; }
    // Its BSDF is VertexBsdf's, which applies bump shadowing (tests/native/light_paths_test.cpp).
    uint32_t honoured_features() const override { return k_feature_bump_shadowing | k_feature_motion_blur; }

private:
    BdptSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_bdpt_integrator(const Params& params) {
    return std::make_unique<BdptIntegrator>(params);
}

double bdpt_integrator_memory(const Params& params, double film_pixels) {
    const BdptSettings s = BdptSettings::from_params(params);
    const double strategies = s.strategy_images ? StrategyImages::bytes_per_pixel(s.strategy_depth) : 0.0;
    return film_pixels * (double(sizeof(SplatAccum)) + strategies);
}

}  // namespace candela
