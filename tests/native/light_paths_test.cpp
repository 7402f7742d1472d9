// The Light Paths settings and rules (integrators/common/light_paths.h, docs/light_paths.md): the bounce budget per
// type against the furnace's truncated series, transparent pass-throughs that are not bounces, transparent shadows
// and MIS across transparent surfaces, Cycles' clamp rule, Filter Glossy, the Caustics switches, the Light Path node
// in the path tracer, bump shadowing, the shadow terminator offset and film exposure.
//
// Exact checks (deterministic estimators: a point light seen by next-event estimation, emission seen by camera rays)
// use a relative tolerance of 1e-4 for float rounding along offset ray origins. Statistical checks use 4 standard
// errors from the renders' own noise estimate plus 1e-3 (false alarm about 6·10⁻⁵ per check for Gaussian errors).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "agreement.h"
#include "bsdf/bsdf_filters.h"
#include "bsdf/material_inputs.h"
#include "integrators/common/light_paths.h"
#include "integrators/integrator.h"
#include "scene/scene.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr double k_exact = 1e-4;

double statistical(const RenderResult& r) { return 4.0 * r.standard_error + 1e-3; }

// ---- the rules --------------------------------------------------------------------------------------------------

BsdfSample sample_of(uint32_t flags, float pdf = 0.5f) {
    BsdfSample s;
    s.flags = flags;
    s.pdf = pdf;
    return s;
}

TEST(LightPathRules, ScatteringsCountByTypeAsCyclesDoes) {
    LightPathState st;
    after_scatter(st, sample_of(k_bsdf_reflection | k_bsdf_diffuse, 0.3f));
    EXPECT_EQ(st.depth.bounce, 1);
    EXPECT_EQ(st.depth.diffuse, 1);
    EXPECT_EQ(st.ray_flags, uint32_t(LightPathInfo::k_reflection | LightPathInfo::k_diffuse));
    EXPECT_FLOAT_EQ(st.min_ray_pdf, 0.3f);
    EXPECT_FALSE(st.transparent_background);
    after_scatter(st, sample_of(k_bsdf_reflection | k_bsdf_specular, 1.f));  // a mirror: glossy and singular
    EXPECT_EQ(st.depth.glossy, 1);
    EXPECT_EQ(st.ray_flags,
              uint32_t(LightPathInfo::k_reflection | LightPathInfo::k_glossy | LightPathInfo::k_singular));
    EXPECT_FLOAT_EQ(st.min_ray_pdf, 0.3f) << "a delta scattering does not lower Filter Glossy's density";
    after_scatter(st, sample_of(k_bsdf_transmission | k_bsdf_diffuse));  // translucency counts as transmission
    EXPECT_EQ(st.depth.transmission, 1);
    EXPECT_EQ(st.depth.diffuse, 1);
    EXPECT_EQ(st.ray_flags, uint32_t(LightPathInfo::k_transmission | LightPathInfo::k_diffuse));
    const uint32_t before = st.ray_flags;
    after_scatter(st, sample_of(k_bsdf_transmission | k_bsdf_specular | k_bsdf_transparent, 1.f));
    EXPECT_EQ(st.depth.bounce, 3) << "a transparent pass-through is not a bounce";
    EXPECT_EQ(st.depth.transparent, 1);
    EXPECT_EQ(st.ray_flags, before) << "the ray keeps its type through a transparent surface";
}

TEST(LightPathRules, LimitsAreTheUiValuePlusOne) {
    LightPathSettings s;
    s.max_bounces = 3;
    s.diffuse_bounces = 1;
    s.transparent_bounces = 2;
    PathDepth d;
    d.bounce = 3;
    EXPECT_TRUE(may_scatter(s, d)) << "Max Bounces 3: the vertex after three scatterings still scatters";
    d.bounce = 4;
    EXPECT_FALSE(may_scatter(s, d));
    d.bounce = 2;
    d.diffuse = 1;
    EXPECT_TRUE(may_scatter(s, d));
    d.diffuse = 2;
    EXPECT_FALSE(may_scatter(s, d));
    d.diffuse = 0;
    d.transparent = 2;
    EXPECT_TRUE(may_scatter(s, d));
    d.transparent = 3;
    EXPECT_FALSE(may_scatter(s, d));
    EXPECT_FALSE(may_pass_transparent(s, d));
}

TEST(LightPathRules, ClampScalesTheComponentSumToThreeTimesTheLimit) {
    LightPathSettings s;
    s.clamp_direct = 1.f;
    s.clamp_indirect = 2.f;
    Color c(4.f, 1.f, 1.f);  // sum 6 > 3·1
    clamp_contribution(c, s, 0);
    EXPECT_NEAR(c.x + c.y + c.z, 3.f, 1e-5f);
    EXPECT_NEAR(c.x / c.y, 4.f, 1e-5f) << "the colour is kept";
    Color d(4.f, 1.f, 1.f);  // sum 6 = 3·2: indirect leaves it
    clamp_contribution(d, s, 1);
    EXPECT_EQ(d.x, 4.f);
    s.clamp_direct = 0.f;  // off
    Color e(100.f, 0.f, 0.f);
    clamp_contribution(e, s, 0);
    EXPECT_EQ(e.x, 100.f);
}

TEST(LightPathRules, FilterGlossyBlursAfterUnlikelyScatterings) {
    LightPathSettings s;
    s.filter_glossy = 1.f;
    const Bsdf mirror(MicrofacetReflection{Microfacet{MicrofacetDistribution::GGX, 0.f, 0.f}, SpecularFresnel{}});
    LightPathState st;  // a camera ray: min_ray_pdf = ∞, nothing to blur
    BsdfSlot slot;
    EXPECT_TRUE(vertex_scattering_bsdf(mirror, s, st, 1.f, {}, slot).is_delta());
    after_scatter(st, sample_of(k_bsdf_reflection | k_bsdf_diffuse, 0.19f));
    const Bsdf& blurred = vertex_scattering_bsdf(mirror, s, st, 1.f, {}, slot);
    ASSERT_FALSE(blurred.is_delta());
    const auto& lobe = std::get<MicrofacetReflection>(blurred[0].lobe);
    EXPECT_NEAR(lobe.distribution.alpha_x, 0.5f * std::sqrt(1.f - 0.19f), 1e-6f);
    s.filter_glossy = 0.1f;  // p = 0.19 ≥ f: no blur
    EXPECT_TRUE(vertex_scattering_bsdf(mirror, s, st, 1.f, {}, slot).is_delta());
}

TEST(LightPathRules, CausticsSwitchesSplitGlassAsCyclesDoes) {
    const Bsdf glass = glass_bsdf(Color(1.f), 0.f, 1.5f, false);
    const float cos_o = 0.8f, F = fresnel_dielectric(cos_o, 1.5f);
    const Bsdf refr = caustics_filter(glass, cos_o, false, true);
    ASSERT_EQ(refr.size(), 1);
    EXPECT_TRUE(std::get<MicrofacetDielectric>(refr[0].lobe).refraction_only);
    EXPECT_NEAR(refr[0].weight.x, 1.f - F, 1e-6f);
    const Bsdf refl = caustics_filter(glass, cos_o, true, false);
    ASSERT_EQ(refl.size(), 1);
    EXPECT_TRUE(std::holds_alternative<MicrofacetReflection>(refl[0].lobe));
    EXPECT_NEAR(refl[0].weight.x, F, 1e-6f);
    EXPECT_TRUE(caustics_filter(glass, cos_o, false, false).empty());
    // Diffuse lobes always stay; glossy reflection goes with Reflective.
    Bsdf plastic(LambertBsdf{}, Color(0.5f));
    plastic.add(MicrofacetReflection{Microfacet{MicrofacetDistribution::GGX, 0.1f, 0.1f}, SpecularFresnel{}},
                Color(0.5f));
    EXPECT_EQ(caustics_filter(plastic, cos_o, false, true).size(), 1);
    EXPECT_FALSE(caustics_filter_changes(plastic, true, false));
    // Only at vertices reached by diffuse rays.
    LightPathSettings s;
    s.caustics_refractive = false;
    LightPathState camera;
    BsdfSlot slot;
    EXPECT_EQ(vertex_scattering_bsdf(glass, s, camera, cos_o, {}, slot).size(), 1);
    EXPECT_TRUE(std::holds_alternative<MicrofacetDielectric>(
        vertex_scattering_bsdf(glass, s, camera, cos_o, {}, slot)[0].lobe));
    LightPathState diffuse;
    after_scatter(diffuse, sample_of(k_bsdf_reflection | k_bsdf_diffuse));
    EXPECT_TRUE(std::holds_alternative<MicrofacetReflection>(
        vertex_scattering_bsdf(glass, s, diffuse, cos_o, {}, slot)[0].lobe));
}

// ---- bump shadowing ----------------------------------------------------------------------------------------------

TEST(BumpShadowing, ChiangTermScalesOnlyDiffuseLobesAndKeepsThePdf) {
    // Bent normal = local z; smooth normal tilted 30° about x.
    const float a = 30.f * k_pi / 180.f;
    BumpShadowing b;
    b.smooth = Vec3(0.f, std::sin(a), std::cos(a));
    b.active = true;
    const Vec3 up(0.f, 0.f, 1.f);
    EXPECT_FLOAT_EQ(b.term(up), 1.f) << "g = 1/cos²30° > 1 along the bent normal";
    const Vec3 below_smooth = normalize(Vec3(0.f, -1.f, 0.05f));  // above the bent horizon, below the smooth one
    EXPECT_EQ(b.term(below_smooth), 0.f);
    const Vec3 grazing = normalize(Vec3(0.f, -1.f, 1.2f));
    const float cz = grazing.z, g = dot(b.smooth, grazing) / (cz * b.smooth.z);
    ASSERT_GT(g, 0.f);
    ASSERT_LT(g, 1.f);
    EXPECT_NEAR(b.term(grazing), -g * g * g + g * g + g, 1e-6f);
    Bsdf mixed(LambertBsdf{}, Color(0.5f));
    mixed.add(MicrofacetReflection{Microfacet{MicrofacetDistribution::GGX, 0.3f, 0.3f}, SpecularFresnel{}},
              Color(0.5f));
    Bsdf shadowed = mixed;
    shadowed.set_bump_shadowing(b);
    const Vec3 wo = normalize(Vec3(0.f, 0.3f, 1.f));
    const Color diffuse_part = Color(0.5f * k_inv_pi);
    const Color glossy_part = mixed.f(wo, grazing) - diffuse_part;
    const Color expected = diffuse_part * b.term(grazing) + glossy_part;
    const Color got = shadowed.f(wo, grazing);
    EXPECT_NEAR(got.x, expected.x, 1e-5f);
    EXPECT_EQ(shadowed.pdf(wo, grazing), mixed.pdf(wo, grazing));
    // A lone Lambert lobe (the inline path) gets it too.
    Bsdf lambert(LambertBsdf{}, Color(1.f));
    lambert.set_bump_shadowing(b);
    EXPECT_NEAR(lambert.f(wo, grazing).x, k_inv_pi * b.term(grazing), 1e-6f);
}

// ---- renders -------------------------------------------------------------------------------------------------

TEST(LightPathBudget, DiffuseLimitTruncatesTheFurnaceSeriesLikeMaxBounces) {
    Params p = basic_params(16, 16, 256, 40);
    p.set("diffuse_bounces", int64_t(2));
    const RenderResult r = render(furnace_scene(FurnaceScene::EmissiveSphere), p);
    EXPECT_NEAR(r.mean_rgb, furnace_expected(FurnaceScene::EmissiveSphere, 2), statistical(r));
    // The other types' limits do not touch a diffuse furnace.
    Params q = basic_params(16, 16, 256, 40);
    q.set("glossy_bounces", int64_t(0));
    q.set("transmission_bounces", int64_t(0));
    const RenderResult s = render(furnace_scene(FurnaceScene::EmissiveSphere), q);
    EXPECT_NEAR(s.mean_rgb, furnace_expected(FurnaceScene::EmissiveSphere, 40), statistical(s));
}

/// An emissive wall (radiance (1, 2, 3)) at z = −4 behind `planes` transparent planes of the given weight at
/// z = −1, −1.5, …; or a diffuse wall lit by a point light between the camera and the planes.
SceneArrays transparent_stack(int planes, float weight, bool lit_diffuse_wall) {
    MeshBuilder m;
    const uint32_t glass = m.add_material(Color(0.f), Color(0.f));
    m.add_closure(glass, "TRANSPARENT", {{"color_r", weight}, {"color_g", weight}, {"color_b", weight}});
    for (int k = 0; k < planes; ++k)
        m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -1.f - float(k) * 0.5f, glass));
    if (lit_diffuse_wall) {
        const uint32_t wall = m.add_material(Color(0.8f), Color(0.f));
        m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -4.f, wall));
        m.add_point_light(Vec3(0.3f, 0.2f, -0.5f), Color(50.f));  // in front of the planes: shadow rays cross them
    } else {
        const uint32_t lamp = m.add_material(Color(0.f), Color(1.f, 2.f, 3.f));
        m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -4.f, lamp));
    }
    return m.arrays();
}

TEST(LightPathBudget, TransparentSurfacesHaveTheirOwnBudget) {
    Params p = basic_params(4, 4, 4, 0);  // direct light only: transparent surfaces are no bounces
    p.set("transparent_bounces", int64_t(2));
    const RenderResult seen = render(transparent_stack(3, 1.f, false), p);
    EXPECT_NEAR(seen.mean_rgb, 2.0, 2.0 * k_exact) << "three passes: transparent 3 > 2 only at the wall (emission)";
    p.set("transparent_bounces", int64_t(1));
    const RenderResult cut = render(transparent_stack(3, 1.f, false), p);
    EXPECT_EQ(cut.mean_rgb, 0.0) << "the third plane is past the budget: emission only, and it has none";
}

TEST(LightPathBudget, TransparentPassesDoNotUseUpMaxBounces) {
    // Max Bounces 0 lights the wall behind three transparent planes exactly as the bare wall.
    Params p = basic_params(8, 8, 4, 0);
    const RenderResult bare = render(transparent_stack(0, 1.f, true), p);
    const RenderResult behind = render(transparent_stack(3, 1.f, true), p);
    ASSERT_GT(bare.mean_rgb, 0.01);
    EXPECT_NEAR(behind.mean_rgb / bare.mean_rgb, 1.0, k_exact);
}

TEST(TransparentShadows, ShadowRaysPassTransparentSurfacesWithTheirWeight) {
    // One plane of transparency 0.3 before a point-lit wall: the camera sees through it (×0.3) and so does the
    // shadow ray (×0.3).
    Params p = basic_params(8, 8, 4, 0);
    const RenderResult bare = render(transparent_stack(0, 1.f, true), p);
    const RenderResult behind = render(transparent_stack(1, 0.3f, true), p);
    EXPECT_NEAR(behind.mean_rgb / bare.mean_rgb, 0.09, 0.09 * k_exact);
}

/// A diffuse wall lit through a half-transparent plane by an area light between them (out of the camera's view
/// of its emitting side): light sampling, BSDF sampling and MIS must agree.
SceneArrays area_light_behind_plane(bool with_plane) {
    MeshBuilder m;
    const uint32_t wall = m.add_material(Color(0.8f), Color(0.f));
    m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -4.f, wall));
    if (with_plane) {
        const uint32_t glass = m.add_material(Color(0.f), Color(0.f));
        m.add_closure(glass, "TRANSPARENT", {{"color_r", 0.5f}, {"color_g", 0.5f}, {"color_b", 0.5f}});
        m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -3.f, glass));
    }
    m.add_area_light(Vec3(0.f, 0.f, -2.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f), Vec3(0.f, 0.f, -1.f), Color(40.f),
                     false);
    return m.arrays();
}

TEST(TransparentShadows, MisWeighsEmissionFoundThroughTransparentSurfacesConsistently) {
    const PreparedScene scene(area_light_behind_plane(true), basic_params(16, 16, 256, 0));
    RenderResult results[3];
    const char* modes[3] = {"MIS", "LIGHT_ONLY", "BSDF_ONLY"};
    for (int k = 0; k < 3; ++k) {
        Params o;
        o.set("light_sampling", std::string(modes[k]));
        o.set("sampler", std::string("RANDOM"));
        results[k] = scene.render(o);
    }
    for (int k = 1; k < 3; ++k)
        EXPECT_NEAR(results[k].mean_rgb, results[0].mean_rgb,
                    4.0 * std::hypot(results[k].standard_error, results[0].standard_error) + 1e-3)
            << modes[k] << " against MIS";
    // And the plane's two crossings (camera ray, light) take 0.5 · 0.5 of the bare wall.
    const RenderResult bare = render(area_light_behind_plane(false), basic_params(16, 16, 256, 0));
    EXPECT_NEAR(results[0].mean_rgb, 0.25 * bare.mean_rgb,
                4.0 * std::hypot(results[0].standard_error, 0.25 * bare.standard_error) + 1e-3);
}

TEST(Clamping, DirectClampLimitsEmissionSeenByTheCamera) {
    MeshBuilder m;
    const uint32_t lamp = m.add_material(Color(0.f), Color(6.f, 0.f, 0.f));
    m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -3.f, lamp));
    Params p = basic_params(4, 4, 4, 4);
    p.set("clamp_indirect", 1.0);
    EXPECT_NEAR(render(m.arrays(), p).mean_rgb, 2.0, k_exact) << "emission seen directly is direct light";
    p.set("clamp_direct", 1.0);
    EXPECT_NEAR(render(m.arrays(), p).mean_rgb, 1.0, k_exact) << "R + G + B = 6 clamped to 3";
}

TEST(FilmExposure, ScalesTheLightNotTheAlpha) {
    MeshBuilder m;
    const uint32_t lamp = m.add_material(Color(0.f), Color(1.f, 2.f, 3.f));
    m.add_instance(m.add_quad_z(-1.f, 1.f, -20.f, 20.f, -3.f, lamp));
    Params p = basic_params(8, 4, 4, 0);
    p.set("film_transparent", true);
    const RenderResult one = render(m.arrays(), p);
    p.set("film_exposure", 2.5);
    const RenderResult bright = render(m.arrays(), p);
    for (size_t i = 0; i < one.rgba.size(); ++i)
        EXPECT_FLOAT_EQ(bright.rgba[i], (i % 4 == 3) ? one.rgba[i] : 2.5f * one.rgba[i]) << i;
}

// ---- the Light Path node ------------------------------------------------------------------------------------

/// A quad at z = −4 emitting (Is Camera Ray, Transparent Depth, Ray Depth) through its shader program, seen through
/// `planes` transparent planes.
SceneArrays light_path_emitter(int planes) {
    MeshBuilder m;
    const uint32_t glass = m.add_material(Color(0.f), Color(0.f));
    m.add_closure(glass, "TRANSPARENT", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}});
    for (int k = 0; k < planes; ++k)
        m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -1.f - float(k) * 0.5f, glass));
    const uint32_t lamp = m.add_material(Color(0.f), Color(0.f));
    m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 20.f, -4.f, lamp));
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    const uint32_t cam = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::IsCameraRay)});
    const uint32_t td = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::TransparentDepth)});
    const uint32_t rd = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::RayDepth)});
    const uint32_t rgb = b.op(ShaderOpCode::Combine, cam, td, rd, {uint32_t(ColorModel::Rgb)});
    b.bind(InputTarget::Emission, lamp, 0, 3, b.end_program(), rgb);
    b.add_to(a);
    return a;
}

TEST(LightPathNode, PathTracerDefinesRayTypeAndDepths) {
    const Params p = basic_params(4, 4, 4, 2);
    const RenderResult direct = render(light_path_emitter(0), p);
    const RenderResult through = render(light_path_emitter(2), p);
    for (size_t i = 0; i < direct.rgba.size(); i += 4) {
        EXPECT_EQ(direct.rgba[i], 1.f);  // a camera ray
        EXPECT_EQ(direct.rgba[i + 1], 0.f);
        EXPECT_EQ(through.rgba[i], 1.f) << "still a camera ray through transparent surfaces";
        EXPECT_EQ(through.rgba[i + 1], 2.f) << "two transparent surfaces crossed";
        EXPECT_EQ(through.rgba[i + 2], 0.f) << "no bounce";
    }
}

TEST(LightPathNode, WorldSeenByTheCameraOnlyLightsNothing) {
    // World = Is Camera Ray: white to the camera, black to every other ray; a diffuse floor below the horizon.
    MeshBuilder m;
    const uint32_t floor = m.add_material(Color(0.8f), Color(0.f));
    m.add_instance(m.add_quad_z(-20.f, 20.f, -20.f, 0.f, -3.f, floor));  // the lower half of the view
    SceneArrays a = m.arrays();
    ProgramBuilder b;
    const uint32_t cam = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::IsCameraRay)});
    b.bind(InputTarget::World, 0, 0, 3, b.end_program(), cam);
    b.add_to(a);
    const PreparedScene scene(std::move(a), basic_params(8, 8, 16, 4));
    EXPECT_TRUE(scene.scene().world_reads_light_path());
    const RenderResult r = scene.render(Params());
    double sky = 0.0, ground = 0.0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) (y < 4 ? ground : sky) += r.rgba[4 * size_t(y * 8 + x)];
    EXPECT_NEAR(sky / 32.0, 1.0, k_exact);
    EXPECT_EQ(ground, 0.0);
}

TEST(LightPathNode, IntegratorsThatCannotHonourItSaySo) {
    const PreparedScene scene(light_path_emitter(1), basic_params(4, 4, 4, 2));
    const std::string note = unhonoured_features_note("LIGHT", 0u, scene.scene());
    EXPECT_NE(note.find("Light Path"), std::string::npos) << note;
    EXPECT_NE(note.find("Transparent"), std::string::npos) << note;
    EXPECT_TRUE(unhonoured_features_note("PATH", ~0u, scene.scene()).empty());
}

TEST(LightPathNode, LightRootedIntegratorsSayWhatTheyDoNotHonour) {
    // The registry's LIGHT and BDPT honour none of the camera-path features but bump shadowing (VertexBsdf's) and
    // motion blur (one shutter time per path); PATH all of them.
    for (const char* name : {"LIGHT", "BDPT"}) {
        Params p = basic_params(4, 4, 1, 1);
        p.set("integrator", std::string(name));
        EXPECT_EQ(make_integrator(p)->honoured_features(), k_feature_bump_shadowing | k_feature_motion_blur) << name;
    }
    Params p = basic_params(4, 4, 1, 1);
    EXPECT_EQ(make_integrator(p)->honoured_features(), k_feature_light_path | k_feature_transparent_shadows |
                                                           k_feature_terminator_offset | k_feature_bump_shadowing |
                                                           k_feature_motion_blur);
}

// ---- bump shadowing in every integrator ------------------------------------------------------------------------

/// A diffuse floor whose Normal Map (world space) bends the normal 0.5 rad toward a low point light: the light
/// arrives at g ≈ 0.5 of Chiang et al.'s term, so bump shadowing darkens its direct light by about a third
/// (docs/light_paths.md, "Bump shadowing"), and light and camera subpaths must both see it.
SceneArrays bent_floor() {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.7f), Color(0.f));
    b.add_closure(m, "DIFFUSE", {{"color_r", 0.7f}, {"color_g", 0.7f}, {"color_b", 0.7f}});
    b.add_instance(b.add_triangle(Vec3(-8.f, -1.f, 2.f), Vec3(8.f, -1.f, 2.f), Vec3(0.f, -1.f, -14.f), m));
    b.add_point_light(Vec3(3.f, -0.2f, -3.f), Color(30.f));
    SceneArrays a = b.arrays();
    ProgramBuilder pb;
    const Vec3 n(std::sin(0.5f), std::cos(0.5f), 0.f);
    const uint32_t color = pb.constant((n + Vec3(1.f)) * 0.5f);
    const uint32_t reg =
        pb.op(ShaderOpCode::NormalMap, color, pb.constant(Vec3(1.f)), 0, {uint32_t(NormalMapSpace::World)});
    const uint32_t prog = pb.end_program();
    pb.bind(InputTarget::Normal, 0, 0, 3, prog, reg);
    pb.add_to(a);
    return a;
}

Params bent_floor_params(const char* integrator, int samples) {
    Params p = basic_params(24, 18, samples, 6);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("max_bounces", int64_t(0));
    p.set("integrator", std::string(integrator));
    return p;
}

TEST(BumpShadowing, LightTracingAndBdptAgreeWithPathOnABentNormal) {
    // Agreement (tests/native/agreement.h): 12 seeds a side, t with 22 degrees of freedom; the mean within 4
    // (two-sided false alarm 6e-4), every 4x4 block within 6 (5e-6 per block).
    const SceneArrays arrays = bent_floor();
    const std::vector<RenderResult> path = render_seeds(arrays, bent_floor_params("PATH", 32), 12);
    for (const char* name : {"LIGHT", "BDPT"}) {
        const Agreement g = compare_seed_sets(render_seeds(arrays, bent_floor_params(name, 48), 12), path, 4);
        EXPECT_GT(g.mean_b, 0.0) << name;
        EXPECT_LT(std::fabs(g.mean_z), 4.0) << name << " mean " << g.mean_a << ", PATH " << g.mean_b;
        EXPECT_LT(std::fabs(g.worst_block_z), 6.0) << name << ": block " << g.worst_block << " of " << g.blocks;
    }
}

// ---- the shadow terminator offset ----------------------------------------------------------------------------

TEST(TerminatorOffset, LiftsShadowOriginsTowardTheSmoothSurfaceNearTheTerminator) {
    // A coarse smooth sphere of radius 1 at z = −3: a shading point between vertices lies inside the true sphere; the
    // lifted point lies further out, and not beyond the sphere.
    MeshBuilder m;
    const uint32_t mat = m.add_material(Color(0.8f), Color(0.f));
    const uint32_t sphere = m.add_sphere(1.f, 8, 4, mat);
    const std::vector<float> at = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -3, 0, 0, 0, 1};
    m.add_instance(sphere, at.data());
    SceneArrays a = m.arrays();
    // Smooth: per-vertex normals of the unit sphere.
    const Array& pos = a.get("positions");
    std::vector<float> vn(pos.count());
    for (size_t i = 0; i < pos.count(); i += 3) {
        const Vec3 v = normalize(Vec3(pos.data<float>()[i], pos.data<float>()[i + 1], pos.data<float>()[i + 2]));
        vn[i] = v.x, vn[i + 1] = v.y, vn[i + 2] = v.z;
    }
    a.set("vertex_normals", ElemType::F32, {pos.count() / 3, 3}, vn.data());
    std::vector<uint8_t> smooth(a.rows("triangles"), 1);
    a.set("tri_smooth", ElemType::U8, {smooth.size()}, smooth.data());
    const float offset = 0.1f;
    a.set("instance_terminator", ElemType::F32, {1}, &offset);
    const PreparedScene scene(std::move(a), basic_params(4, 4, 1, 0));
    const Scene& s = scene.scene();
    ASSERT_TRUE(s.has_terminator_offsets());
    Ray ray{Vec3(0.f), normalize(Vec3(0.13f, 0.07f, -1.f))};
    ray.type = k_ray_camera;
    SurfaceHit hit;
    ASSERT_TRUE(s.intersect(ray, &hit));
    const Vec3 centre(0.f, 0.f, -3.f);  // the camera is at the origin: camera-world space is world space
    const float r0 = length(hit.p - centre);
    ASSERT_LT(r0, 0.99f) << "the flat facet lies inside the sphere";
    // A light direction on both horizons (perpendicular to the shading and the geometric normal): the full offset.
    const Vec3 n = hit.ns;
    ASSERT_GT(length(cross(n, hit.ng)), 1e-3f);
    const Vec3 t = normalize(cross(n, hit.ng));
    const Vec3 p = s.terminator_point(hit, n, hit.ng, t);
    const float r1 = length(p - centre);
    EXPECT_GT(r1, r0 + 0.3f * (1.f - r0)) << "lifted toward the smooth sphere";
    // The lift is about quadratic in the facet's size: on this 45°-facet sphere a point between two vertices goes from
    // cos 22.5° = 0.924 to 0.924 + (1 − 0.924²)·… ≈ 1.06 (the tangent planes lie outside the sphere); no further.
    EXPECT_LE(r1, 1.08f);
    // A light high above: none.
    const Vec3 q = s.terminator_point(hit, n, hit.ng, n);
    EXPECT_EQ(length(q - hit.p), 0.f);
}

}  // namespace
}  // namespace candela::test
