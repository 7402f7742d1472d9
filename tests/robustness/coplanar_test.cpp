// Coplanar surfaces: a Blender area light and an emissive quad lying exactly in the ceiling plane, and two
// overlapping coplanar quads of different colours, at several scales, far from the origin and under a
// rotation that breaks exact float coplanarity. "Speckle" is measured three ways:
//  - colour mixtures: where two coplanar quads overlap, a pixel whose samples hit both (R > 0 and G > 0 for a
//    pure red and a pure green quad; B > 0 on a yellow emitter lying on a blue ceiling) is z-fighting. This is
//    exact (a pure colour reflects nothing in the other channels), so it needs no tolerance;
//  - per pixel, against the same scene with the light moved 1e-4 (of the room size) into the room, where nothing
//    is ambiguous: |difference| ≤ 6σ (hard_scenes.h derives it);
//  - over the light's whole image, a mean that must agree within 4 standard errors: mixtures too weak to show in
//    one pixel still bias the mean.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hard_scenes.h"
#include "session/session.h"

namespace candela::test {
namespace {

// Camera at `eye`, looking down −Z tilted up by `pitch` radians (rotation about +X).
std::vector<float> camera_rows(Vec3 eye, float pitch) {
    const float c = std::cos(pitch), s = std::sin(pitch);
    return {1, 0, 0, eye.x, 0, c, -s, eye.y, 0, s, c, eye.z, 0, 0, 0, 1};
}

Params params(int w, int h, int spp, int bounces, bool transparent = false) {
    Params p = basic_params(w, h, spp, bounces);
    p.set("film_transparent", transparent);
    p.set("clip_start", 1e-6);
    p.set("clip_end", 1e9);
    return p;
}

// A closed room [-1.5, 1.5] × [-1, 1] × [-4, 1] (times `scale`, shifted by `offset`) with grey walls and a
// ceiling (y = 1) of pure blue albedo. Lit by a point light unless told otherwise.
struct Room {
    float scale = 1.f;
    Vec3 offset{0.f};
    Vec3 at(float x, float y, float z) const { return Vec3(x, y, z) * scale + offset; }
    Vec3 vec(float x, float y, float z) const { return Vec3(x, y, z) * scale; }

    void build(ShadedBuilder& b, bool point_light = true) const {
        const uint32_t grey = b.add_material(Color(0.6f), Color(0.f));
        const uint32_t blue = b.add_material(Color(0.f, 0.f, 0.8f), Color(0.f));
        auto quad = [&](Vec3 p0, Vec3 e1, Vec3 e2, uint32_t m) { b.add_instance(b.add_quad(p0, e1, e2, m)); };
        quad(at(-1.5f, 1.f, -4.f), vec(3.f, 0, 0), vec(0, 0, 5.f), blue);   // ceiling
        quad(at(-1.5f, -1.f, -4.f), vec(0, 0, 5.f), vec(3.f, 0, 0), grey);  // floor
        quad(at(-1.5f, -1.f, -4.f), vec(3.f, 0, 0), vec(0, 2.f, 0), grey);  // far wall
        quad(at(-1.5f, -1.f, 1.f), vec(0, 2.f, 0), vec(3.f, 0, 0), grey);   // wall behind the camera
        quad(at(-1.5f, -1.f, -4.f), vec(0, 2.f, 0), vec(0, 0, 5.f), grey);  // left
        quad(at(1.5f, -1.f, -4.f), vec(0, 0, 5.f), vec(0, 2.f, 0), grey);   // right
        if (point_light) b.add_point_light(at(0.f, 0.f, -2.f), Color(20.f * scale * scale));
    }
    std::vector<float> camera() const { return camera_rows(at(0.f, 0.f, 0.f), 0.45f); }
};

struct Placement {
    float scale;
    Vec3 offset;
    std::string name;
};
const Placement k_placements[] = {
    {1e-3f, Vec3(0.f), "scale 1e-3"},
    {1.f, Vec3(0.f), "scale 1"},
    {1e3f, Vec3(0.f), "scale 1e3"},
    {1.f, Vec3(3e4f, -2e4f, 1e4f), "offset 3e4"},
};

// The Blender area light in the ceiling plane (y = 1), and the same light 1e-4 below it.
TEST(Coplanar, AreaLightInTheCeilingPlaneMatchesTheLightJustBelowIt) {
    for (const Placement& pl : k_placements) {
        const Room room{pl.scale, pl.offset};
        RenderResult r[2];
        for (int moved = 0; moved < 2; ++moved) {
            ShadedBuilder b;
            room.build(b);
            const float y = moved ? 1.f - 1e-4f : 1.f;
            b.add_area_light(room.at(0.f, y, -2.5f), room.vec(0.8f, 0, 0), room.vec(0, 0, 0.8f), Vec3(0.f, -1.f, 0.f),
                             Color(40.f * pl.scale * pl.scale));
            const auto cam = room.camera();
            r[moved] = render(b.arrays(cam.data()), params(40, 30, 32, 3));
        }
        // The light's pixels: where the coplanar render is much brighter than the blue-only ceiling could be.
        std::vector<uint8_t> light(r[0].noise.size());
        for (size_t i = 0; i < light.size(); ++i) light[i] = r[1].rgba[4 * i] > 1.f;
        ASSERT_GT(mask_count(light), 40u) << pl.name << ": the light must be in view";
        EXPECT_EQ(count_disagreeing_pixels(r[0], r[1], 6.0), 0u) << pl.name;
        double m0, s0, m1, s1;
        masked_mean(r[0], light, &m0, &s0);
        masked_mean(r[1], light, &m1, &s1);
        EXPECT_NEAR(m0, m1, 4.0 * std::hypot(s0, s1)) << pl.name;
    }
}

// A yellow emissive quad (no reflection) lying on the blue ceiling: where it covers the ceiling every sample
// must see the emitter (blue = 0 exactly), and the image must match the emitter moved 1e-4 into the room.
TEST(Coplanar, EmissiveQuadOnTheCeilingShowsNoSpeckle) {
    for (const Placement& pl : k_placements) {
        const Room room{pl.scale, pl.offset};
        const auto cam = room.camera();
        auto scene = [&](bool with_room, float y) {
            ShadedBuilder b;
            if (with_room) room.build(b);
            const uint32_t glow = b.add_material(Color(0.f), Color(5.f, 5.f, 0.f));
            b.add_instance(b.add_quad(room.at(-0.4f, y, -2.9f), room.vec(0.8f, 0, 0), room.vec(0, 0, 0.8f), glow));
            return b.arrays(cam.data());
        };
        const RenderResult alone = render(scene(false, 1.f), params(40, 30, 2, 0, true));
        const std::vector<uint8_t> inside = covered_interior(alone);
        ASSERT_GT(mask_count(inside), 30u) << pl.name;
        const RenderResult coplanar = render(scene(true, 1.f), params(40, 30, 32, 3));
        const RenderResult below = render(scene(true, 1.f - 1e-4f), params(40, 30, 32, 3));
        size_t mixed = 0;
        for (size_t i = 0; i < inside.size(); ++i)
            if (inside[i]) mixed += coplanar.rgba[4 * i + 2] != 0.f || std::fabs(coplanar.rgba[4 * i] - 5.f) > 1e-4f;
        EXPECT_EQ(mixed, 0u) << pl.name << ": emitter pixels that also saw the ceiling";
        EXPECT_EQ(count_speckles(coplanar, inside), 0u) << pl.name;
        EXPECT_EQ(count_disagreeing_pixels(coplanar, below, 6.0), 0u) << pl.name;
        EXPECT_NEAR(coplanar.mean_rgb, below.mean_rgb, 4.0 * std::hypot(coplanar.standard_error, below.standard_error))
            << pl.name;
    }
}

// Two overlapping quads in one plane, pure red and pure green, seen face-on and at a grazing angle, rotated
// off the axes (so the four corners are no longer exactly coplanar in float): every pixel of the overlap must
// show one colour, and the same one everywhere.
TEST(Coplanar, OverlappingQuadsOfTwoColoursShowOneOfThemEverywhere) {
    struct View {
        float pitch;  // camera tilt toward the plane's normal
        float roll;   // rotation of the quads about the view axis
        std::string name;
    };
    for (const Placement& pl : k_placements)
        for (const View& v : {View{0.f, 0.f, "face-on"}, View{0.f, 0.5f, "face-on rotated"},
                              View{-1.25f, 0.f, "grazing"}, View{-1.25f, 0.3f, "grazing rotated"}}) {
            const std::string what = pl.name + ", " + v.name;
            // The plane z = −2 (face-on) seen by a camera pitched by v.pitch: at −1.25 rad it is seen at 18°.
            const float c = std::cos(v.roll), s = std::sin(v.roll);
            const std::vector<float> xf = {c * pl.scale,
                                           -s * pl.scale,
                                           0,
                                           pl.offset.x,
                                           s * pl.scale,
                                           c * pl.scale,
                                           0,
                                           pl.offset.y,
                                           0,
                                           0,
                                           pl.scale,
                                           pl.offset.z,
                                           0,
                                           0,
                                           0,
                                           1};
            // Grazing: 0.5 in front of the plane, looking down at 18° to it, toward the overlap.
            const Vec3 eye = v.pitch != 0.f ? Vec3(0.f, 1.8f, -1.5f) : Vec3(0.f);
            const auto cam = camera_rows(pl.offset + eye * pl.scale, v.pitch);
            auto scene = [&](bool red, bool green) {
                ShadedBuilder b;
                const uint32_t mr = b.add_material(Color(0.8f, 0.f, 0.f), Color(0.f));
                const uint32_t mg = b.add_material(Color(0.f, 0.8f, 0.f), Color(0.f));
                if (red)
                    b.add_instance(b.add_quad(Vec3(-1.f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0), mr),
                                   xf.data());
                if (green)
                    b.add_instance(b.add_quad(Vec3(-0.3f, -1.f, -2.f), Vec3(1.3f, 0, 0), Vec3(0, 3.f, 0), mg),
                                   xf.data());
                b.add_point_light(pl.offset + Vec3(0.f, 0.f, 0.f), Color(30.f * pl.scale * pl.scale));
                b.world_color = {0.1f, 0.1f, 0.1f};
                return b.arrays(cam.data());
            };
            const RenderResult red = render(scene(true, false), params(40, 30, 2, 0, true));
            const RenderResult green = render(scene(false, true), params(40, 30, 2, 0, true));
            const std::vector<uint8_t> overlap = mask_and(covered_interior(red), covered_interior(green));
            ASSERT_GT(mask_count(overlap), 20u) << what;
            const RenderResult both = render(scene(true, true), params(40, 30, 16, 2));
            size_t mixed = 0, red_only = 0, green_only = 0;
            for (size_t i = 0; i < overlap.size(); ++i) {
                if (!overlap[i]) continue;
                const float R = both.rgba[4 * i], G = both.rgba[4 * i + 1];
                mixed += R > 0.f && G > 0.f;
                red_only += R > 0.f && G == 0.f;
                green_only += G > 0.f && R == 0.f;
            }
            EXPECT_EQ(mixed, 0u) << what << ": overlap pixels showing both quads";
            EXPECT_TRUE(red_only == 0 || green_only == 0)
                << what << ": " << red_only << " red and " << green_only << " green overlap pixels";
            EXPECT_EQ(count_speckles(both, overlap), 0u) << what;
        }
}

// The other side of the tie-break: distinct surfaces are never merged. A red quad 1e-4 (of the scene's size) in
// front of a green one, which would win a tie (it is the later object): every pixel covered by both must be
// pure red, face-on and at 18° grazing, at every scale and far from the origin. (With a tie tolerance 1000×
// too wide, every placement fails.)
TEST(Coplanar, ParallelQuadsAGapOf1e4ApartStayDistinct) {
    for (const Placement& pl : k_placements)
        for (const float pitch : {0.f, -1.25f}) {
            const std::string what = pl.name + (pitch != 0.f ? ", grazing" : ", face-on");
            const std::vector<float> xf = scale_translate(Vec3(pl.scale), pl.offset);
            const Vec3 eye = pitch != 0.f ? Vec3(0.f, 1.8f, -1.5f) : Vec3(0.f);
            const auto cam = camera_rows(pl.offset + eye * pl.scale, pitch);
            ShadedBuilder b;
            const uint32_t mr = b.add_material(Color(0.8f, 0.f, 0.f), Color(0.f));
            const uint32_t mg = b.add_material(Color(0.f, 0.8f, 0.f), Color(0.f));
            b.add_instance(b.add_quad(Vec3(-1.f, -1.f, -2.f), Vec3(2.f, 0, 0), Vec3(0, 3.f, 0), mr), xf.data());
            b.add_instance(b.add_quad(Vec3(-1.f, -1.f, -2.f - 1e-4f), Vec3(2.f, 0, 0), Vec3(0, 3.f, 0), mg), xf.data());
            b.add_point_light(pl.offset, Color(30.f * pl.scale * pl.scale));
            const RenderResult r = render(b.arrays(cam.data()), params(40, 30, 8, 0, true));
            const std::vector<uint8_t> covered = covered_interior(r);
            ASSERT_GT(mask_count(covered), 50u) << what;
            // The front quad is lit by the light at the camera, so each pixel is red (R > 0, G = 0); the quad behind
            // shows as green where lit, or black where the front quad shadows it.
            size_t not_red = 0;
            for (size_t i = 0; i < covered.size(); ++i)
                not_red += covered[i] && !(r.rgba[4 * i] > 0.f && r.rgba[4 * i + 1] == 0.f);
            EXPECT_EQ(not_red, 0u) << what << ": pixels showing the quad behind";
        }
}

// The speckle measure can fail: one pixel of a smooth render pushed by 10σ is found, and only that one.
TEST(Coplanar, SpeckleMeasureFindsAnInjectedOutlier) {
    ShadedBuilder b;
    b.add_instance(
        b.add_quad(Vec3(-2.f, -2.f, -2.f), Vec3(4.f, 0, 0), Vec3(0, 4.f, 0), b.add_material(Color(0.7f), Color(0.f))));
    b.add_point_light(Vec3(0.f, 0.f, 0.f), Color(30.f));
    RenderResult r = render(b.arrays(), params(24, 18, 16, 1));
    std::vector<uint8_t> all(r.noise.size(), 1);
    EXPECT_EQ(count_speckles(r, all), 0u);
    const size_t i = 9 * 24 + 12;
    const float bump = 10.f * std::max(r.noise[i], 1e-3f) / 0.2126f;
    r.rgba[4 * i] += bump;
    EXPECT_EQ(count_speckles(r, all), 1u);
}

}  // namespace
}  // namespace candela::test
