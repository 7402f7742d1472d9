#include "integrators/path/path_integrator.h"

#include "integrators/camera_tiles.h"
#include "integrators/path/path_tracer.h"
#include "lights/light_sampler.h"

namespace candela {

namespace {

class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(const Params& params) : m_settings(PathSettings::from_params(params)) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        // The scene keeps its light samplers: a viewport restart (a new view, a coarse level) reuses the light tree.
        const LightSampler& light_sampler = scene.light_sampler(parse_light_selection(m_settings.light_selection));
        const PathTracer tracer(scene, m_settings, light_sampler);
        render_camera_progressive(scene, film, ctx, m_settings.pixel, tracer, /*motion_blur=*/true);
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "sample"}; }
    uint32_t honoured_features() const override {
        // Motion blur: one shutter time per camera path (CameraTilePass::render_moving).
        return k_feature_light_path | k_feature_transparent_shadows | k_feature_terminator_offset |
               k_feature_bump_shadowing | k_feature_motion_blur;
    }

private:
    PathSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator(const Params& params) {
    return std::make_unique<PathIntegrator>(params);
}

}  // namespace candela
