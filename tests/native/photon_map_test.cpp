// The photon mappers (integrators/photon_map/; docs/photon-mapping.md): smoke and development checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "agreement.h"
#include "integrators/integrator.h"

namespace candela::test {
namespace {

TEST(PhotonSmoke, FurnacePhoton) {
    Params p = basic_params(16, 16, 16, 40);
    p.set("integrator", std::string("PHOTON"));
    p.set("threads", int64_t(2));
    const RenderResult r = render(furnace_scene(FurnaceScene::PointLight), p);
    std::printf("PHOTON furnace %.5f (expected %.5f) se %.5f\n", r.mean_rgb, furnace_expected(FurnaceScene::PointLight, 40), r.standard_error);
}

TEST(PhotonSmoke, FurnaceSppm) {
    Params p = basic_params(16, 16, 16, 40);
    p.set("integrator", std::string("SPPM"));
    p.set("threads", int64_t(2));
    const RenderResult r = render(furnace_scene(FurnaceScene::PointLight), p);
    std::printf("SPPM furnace %.5f (expected %.5f)\n", r.mean_rgb, furnace_expected(FurnaceScene::PointLight, 40));
}

}  // namespace
}  // namespace candela::test
