// LIGHT and BDPT refuse panoramic cameras by name (issue 20): their light-tracing strategies (t = 1) connect a
// vertex to the lens through Camera::connect, raster_of and pdf_we, which invert a perspective or orthographic
// viewplane; a panorama (equirectangular, fisheye equidistant, fisheye equisolid) has none, so an image they made
// through one would be silently wrong. Refused from the params (before the scene is built) and again at render
// time for a scene whose camera was replaced (Scene::set_camera: the 3D viewport); PATH renders panoramas.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/error.h"
#include "integrators/integrator.h"
#include "scene/scene.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr const char* k_light_rooted[] = {"LIGHT", "BDPT"};
constexpr const char* k_panoramas[][2] = {{"EQUIRECTANGULAR", "Equirectangular"},
                                          {"FISHEYE_EQUIDISTANT", "Fisheye Equidistant"},
                                          {"FISHEYE_EQUISOLID", "Fisheye Equisolid"}};

Params panoramic(Params p, const char* type) {
    p.set("camera_type", std::string("PANO"));
    p.set("panorama_type", std::string(type));
    return p;
}

/// The message of the InvalidParameter `f` throws; fails the test if it throws nothing.
template <class F>
std::string refusal(F&& f, const std::string& what) {
    try {
        f();
    } catch (const InvalidParameter& e) {
        return e.what();
    }
    ADD_FAILURE() << what << ": accepted";
    return std::string();
}

void expect_names(const std::string& message, const std::string& integrator, const std::string& label) {
    EXPECT_NE(message.find("integrator " + integrator), std::string::npos) << message;
    EXPECT_NE(message.find("panoramic camera (" + label + ")"), std::string::npos) << message;
    EXPECT_NE(message.find("use PATH"), std::string::npos) << message;
}

SceneArrays lit_box() {
    MeshBuilder b;
    b.add_instance(b.add_box(Vec3(2.f, 2.f, 2.f), b.add_material(Color(0.5f), Color(0.f))));
    b.add_point_light(Vec3(0.f, 1.f, -1.f), Color(10.f));
    return b.arrays();
}

TEST(PanoramicCamera, LightAndBdptRefuseItFromTheParamsByName) {
    for (const char* integrator : k_light_rooted)
        for (const auto& pano : k_panoramas) {
            Params p = panoramic(basic_params(8, 6, 1, 2), pano[0]);
            p.set("integrator", std::string(integrator));
            const std::string what = std::string(integrator) + " " + pano[0];
            expect_names(refusal([&] { make_integrator(p); }, what), integrator, pano[1]);
        }
}

TEST(PanoramicCamera, PathRendersIt) {
    for (const auto& pano : k_panoramas) {
        Params p = panoramic(basic_params(8, 6, 1, 2), pano[0]);
        p.set("integrator", std::string("PATH"));
        EXPECT_NO_THROW(make_integrator(p)) << pano[0];
    }
}

TEST(PanoramicCamera, LightAndBdptRefuseASceneWhoseCameraBecamePanoramic) {
    // The viewport builds a scene once and replaces its camera per view: the integrator, made for the old
    // (perspective) params, meets the panorama only in render().
    const SceneArrays arrays = lit_box();
    const Params persp = basic_params(8, 6, 1, 2);
    for (const char* integrator : k_light_rooted)
        for (const auto& pano : k_panoramas) {
            Params p = persp;
            p.set("integrator", std::string(integrator));
            Scene scene(arrays, p, nullptr);
            const std::unique_ptr<Integrator> it = make_integrator(p);
            scene.set_camera(panoramic(p, pano[0]), Affine());
            ASSERT_TRUE(scene.camera().is_panoramic());
            Film film(8, 6, 0, 0, 32);
            CancelToken cancel;
            RenderCounters counters;
            RenderContext ctx{cancel, counters, 1};
            const std::string what = std::string(integrator) + " " + pano[0] + " through set_camera";
            expect_names(refusal([&] { it->render(scene, film, ctx); }, what), integrator, pano[1]);
        }
}

}  // namespace
}  // namespace candela::test
