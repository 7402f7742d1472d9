#include "integrators/light/light_integrator.h"

#include <string>
#include <utility>

#include "core/error.h"
#include "core/parallel_ordered.h"
#include "integrators/camera_tiles.h"
#include "integrators/light/light_tracer.h"
#include "scene/shutter_time.h"

namespace candela {

namespace {

/// Throws if the camera has no light-tracing strategy, before the scene is built: an orthographic camera without
/// depth of field receives light from one direction only (no light path can connect to it), and a panoramic
/// camera's projection has no inverse in Camera::connect (Camera::connectable()).
void check_camera(const Params& params) {
    const std::string type = params.get<std::string>("camera_type", "PERSP");
    if (type == "ORTHO" && !params.get<bool>("use_dof", false))
        throw InvalidParameter(
            "integrator LIGHT: the orthographic camera without depth of field has no light-tracing "
            "strategy (no light path can reach it); use PATH or BDPT, or enable depth of field");
    if (type == "PANO")
        throw InvalidParameter("integrator LIGHT: " + Camera::panoramic_not_connectable_message(params.get<std::string>(
                                                          "panorama_type", "FISHEYE_EQUISOLID")));
}

class LightIntegrator final : public Integrator {
public:
    explicit LightIntegrator(const Params& params) : m_settings(LightSettings::from_params(params)) {
        check_camera(params);
    }

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        // The params were checked; a scene whose camera was replaced since (Scene::set_camera) is checked here.
        if (!scene.camera().connectable())
            throw InvalidParameter("integrator LIGHT: " + scene.camera().not_connectable_message());
        const EmitterSet& emitters = scene.emitters();
        if (scene.hidden_ray_types() & (k_ray_diffuse | k_ray_glossy | k_ray_transmission))
            ctx.log(
                "LIGHT: objects hidden from diffuse, glossy or transmission rays are visible to light paths "
                "(only camera and shadow visibility are honoured)");
        for (uint32_t k = 0; k < scene.materials().size(); ++k)
            if (scene.material_flags(k) & k_bsdf_specular) {
                ctx.log(
                    "LIGHT: surfaces the camera sees only through mirrors or glass stay black (a light path cannot "
                    "connect to the camera through a delta lobe; only lights seen that way are drawn); use BDPT");
                break;
            }
        const SpecularCameraTracer camera_tracer(scene, m_settings);
        const CameraTilePass<SpecularCameraTracer> camera_pass(scene, film, ctx, m_settings.pixel, camera_tracer,
                                                               /*motion_blur=*/true);
        const LightTracer tracer(scene, m_settings, emitters);
        const PixelSampling& ps = m_settings.pixel;
        const double frame_pixels = double(scene.camera().full_width()) * scene.camera().full_height();
        const int dim_bounce = m_settings.max_bounces + 2;  // the light path's dimensions follow the camera pass's

        struct TileSplats {
            SplatBuffer buffer;
            bool complete = false;
        };
        // One light path per pixel of the film and per unit, keyed by that pixel and sample (so every sampler works
        // as for camera paths, and sample s belongs to noise replicate s mod 2).
        auto light_paths = [&](size_t tile_index, int begin, int end) {
            TileSplats out;
            const Tile& tile = film.tiles()[tile_index];
            std::vector<Sampler> replicates;
            for (uint32_t r = 0; r < k_noise_replicates; ++r) replicates.push_back(ps.replicate_sampler(r));
            PathStats stats;
            for (int y = tile.y0; y < tile.y1; ++y) {
                if (ctx.cancel.cancelled()) return out;
                for (int x = tile.x0; x < tile.x1; ++x)
                    for (int s = begin; s < end; ++s) {
                        const uint32_t r = noise_replicate_of(uint32_t(s));
                        Sampler& sampler = replicates[r];
                        // A light path's shutter time (motion blur): its emission, bounces and camera connections
                        // all see the scene and the camera at that time.
                        const float time = std::visit(
                            [&](auto& c) {
                                c.start_pixel_sample(uint32_t(film.origin_x() + x), uint32_t(film.origin_y() + y),
                                                     index_in_replicate(uint32_t(s)));
                                return shutter_time_of(c.sample_stream_key());
                            },
                            sampler);
                        const ShutterScope scope(time);
                        tracer.trace(sampler, dim_bounce, r, out.buffer, stats);
                    }
            }
            stats.flush(ctx.counters);
            out.complete = true;
            return out;
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
                        camera_pass.render_tile(t, int(begin), int(end));
                        return light_paths(t, int(begin), int(end));
                    },
                    [&](size_t t, TileSplats&& splats) {
                        if (!splats.complete) return;
                        // The film counts light paths per pixel of the full frame: this tile's share of the pass.
                        const Tile& tile = film.tiles()[t];
                        const double share = double(tile.width()) * tile.height() / frame_pixels;
                        double samples[k_noise_replicates] = {};
                        for (int64_t s = begin; s < end; ++s) samples[noise_replicate_of(uint32_t(s))] += share;
                        film.add_splats(splats.buffer, ps.filter, samples);
                    },
                    &ctx.cancel);
            },
            [&] { return film.noise_estimate(); });
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "light path"}; }
    // Its BSDF is VertexBsdf's, which applies bump shadowing (tests/native/light_paths_test.cpp).
    // Motion blur: one shutter time per light path and per camera path (the camera pass).
    uint32_t honoured_features() const override { return k_feature_bump_shadowing | k_feature_motion_blur; }

private:
    LightSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_light_integrator(const Params& params) {
    return std::make_unique<LightIntegrator>(params);
}

double light_integrator_memory(const Params& params, double film_pixels) {
    // The film's splat accumulators, and the splat buffers in flight (tiles of 32² pixels, a few splats per path).
    return film_pixels * double(sizeof(SplatAccum)) + 64.0 * 1024.0 * 64.0 * double(sizeof(SplatBuffer::Entry));
}

}  // namespace candela
