#include "integrators/path/path_integrator.h"

#include "core/error.h"
#include "integrators/path/path_tracer.h"
#include "integrators/tile_renderer.h"

namespace candela {

PathSettings PathSettings::from_params(const Params& params) {
    PathSettings s;
    s.pixel = PixelSampling::from_params(params);
    s.max_bounces = params.get<int>("max_bounces", 12);
    s.rr_start_bounce = params.get<int>("rr_start_bounce", 3);
    if (s.max_bounces < 0 || s.max_bounces > 1024) throw InvalidParameter("max_bounces must be between 0 and 1024");
    if (s.rr_start_bounce < 0) throw InvalidParameter("rr_start_bounce must not be negative");
    return s;
}

namespace {

class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(const Params& params) : m_settings(PathSettings::from_params(params)) {}

    void render(const Scene& scene, Film& film, RenderContext& ctx) override {
        const PathTracer tracer(scene, m_settings);
        render_progressive(scene, film, ctx, m_settings.pixel, tracer);
    }
    int samples_per_pixel() const override { return m_settings.pixel.samples; }

private:
    PathSettings m_settings;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator(const Params& params) {
    return std::make_unique<PathIntegrator>(params);
}

}  // namespace candela
