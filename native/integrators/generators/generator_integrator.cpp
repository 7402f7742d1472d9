#include "integrators/generators/generator_integrator.h"

#include <optional>
#include <string>

#include "integrators/camera_tiles.h"
#include "integrators/generators/generator_tracer.h"
#include "lights/light_sampler.h"

namespace candela {

namespace {

class GeneratorIntegrator final : public Integrator {
public:
    GeneratorIntegrator(const Params& params, PathGenerator generator)
        : m_settings(GeneratorSettings::from_params(params, generator)) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        const std::string name = path_generator_name(m_settings.generator);
        const bool surfaces_needed = m_settings.generator == PathGenerator::SurfaceSampling || m_settings.combine;
        const bool connects = surfaces_needed || m_settings.generator == PathGenerator::SourceShooting;
        if (connects && (scene.hidden_ray_types() & (k_ray_diffuse | k_ray_glossy | k_ray_transmission)))
            ctx.log(name +
                    ": objects hidden from diffuse, glossy or transmission rays still block and receive the "
                    "generator's connections (only camera and shadow visibility are honoured)");
        std::optional<SurfaceSampler> surfaces;
        if (surfaces_needed) {
            surfaces.emplace(scene, &ctx.cancel);
            if (!(surfaces->total_area() > 0.0)) ctx.log(name + ": the scene has no surface to sample");
        }
        const LightSampler light_sampler = make_light_sampler(m_settings.light_selection, scene.lights());
        const EmitterSet emitters(scene.lights(), scene.bounds());
        const GeneratorTracer tracer(scene, m_settings, light_sampler, emitters, surfaces ? &*surfaces : nullptr);
        // Motion blur: one shutter time per camera sample, seen by all its sub-paths (the light path of source
        // shooting, the surface points of surface sampling: SurfaceSampler places them at that time too).
        render_camera_progressive(scene, film, ctx, m_settings.pixel, tracer, /*motion_blur=*/true);
    }
    WorkBudget budget() const override { return {m_settings.pixel.samples, "sample"}; }
    uint32_t honoured_features() const override { return k_feature_motion_blur; }

private:
    GeneratorSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_surface_sampling_integrator(const Params& params) {
    return std::make_unique<GeneratorIntegrator>(params, PathGenerator::SurfaceSampling);
}
std::unique_ptr<Integrator> make_source_shooting_integrator(const Params& params) {
    return std::make_unique<GeneratorIntegrator>(params, PathGenerator::SourceShooting);
}
std::unique_ptr<Integrator> make_receiver_gathering_integrator(const Params& params) {
    return std::make_unique<GeneratorIntegrator>(params, PathGenerator::ReceiverGathering);
}

}  // namespace candela
