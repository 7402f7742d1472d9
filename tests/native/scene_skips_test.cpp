// What the scene does not need (integrators/scene_skips.h, docs/auto.md "Skips"): each skip is decided exactly on
// the scenes that allow it and on no other, the session's log names them, and BDPT without its s = 0 strategies in a
// scene lit only by a point light renders the same image as before the skip (those strategies carried nothing).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "integrators/scene_skips.h"
#include "reference_scenes.h"
#include "scene/scene.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

std::set<std::string> skip_ids(const SceneArrays& a, const std::string& integrator = "PATH") {
    const Scene scene(a, basic_params(8, 8, 1, 2), nullptr);
    std::set<std::string> ids;
    for (const SceneSkip& s : scene_skips(integrator, scene)) ids.insert(s.id);
    return ids;
}

MeshBuilder floor_only() {
    MeshBuilder b;
    const uint32_t floor = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(add_parallelogram(b, Vec3(-2.f, -1.f, -6.f), Vec3(0.f, 0.f, 4.f), Vec3(4.f, 0.f, 0.f), floor));
    return b;
}

TEST(SceneSkips, EachSkipExactlyWhereTheSceneAllowsIt) {
    using Ids = std::set<std::string>;
    // Cornell box: an emissive panel (hittable), no world, nothing Transparent.
    EXPECT_EQ(skip_ids(cornell_box()), Ids({"no_transparent_shadows"}));
    EXPECT_EQ(skip_ids(cornell_box(), "BDPT"), Ids({"no_transparent_shadows"}));
    // No light at all: no next-event estimation.
    EXPECT_EQ(skip_ids(floor_only().arrays()), Ids({"no_nee", "no_transparent_shadows"}));
    // A point light: MIS left out for it; for BDPT also the s = 0 strategies (nothing hittable emits).
    MeshBuilder point = floor_only();
    point.add_point_light(Vec3(0.f, 1.f, -4.f), Color(50.f));
    EXPECT_EQ(skip_ids(point.arrays()), Ids({"delta_mis", "no_transparent_shadows"}));
    EXPECT_EQ(skip_ids(point.arrays(), "BDPT"), Ids({"delta_mis", "no_transparent_shadows", "bdpt_no_s0"}));
    EXPECT_EQ(skip_ids(point.arrays(), "MMLT").count("bdpt_no_s0"), 1u);
    // The same with a constant world: no importance map, and the world is an emitter rays hit (s = 0 kept).
    MeshBuilder world = point;
    world.world_color = {0.1f, 0.2f, 0.3f};
    EXPECT_EQ(skip_ids(world.arrays(), "BDPT"), Ids({"constant_world", "delta_mis", "no_transparent_shadows"}));
    // A degenerate emissive quad: light entries of zero power, never selected.
    MeshBuilder zero = floor_only();
    const uint32_t emitter = zero.add_material(Color(0.f), Color(5.f));
    zero.add_instance(add_parallelogram(zero, Vec3(0.f, 1.f, -4.f), Vec3(1.f, 0.f, 0.f), Vec3(2.f, 0.f, 0.f), emitter));
    zero.add_point_light(Vec3(0.f, 1.f, -4.f), Color(50.f));
    EXPECT_EQ(skip_ids(zero.arrays()).count("zero_power_lights"), 1u);
    // A Transparent closure: transparent shadows stay on.
    MeshBuilder transparent = point;
    const uint32_t t = transparent.add_material(Color(0.f), Color(0.f));
    transparent.add_closure(t, "TRANSPARENT", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}});
    transparent.add_instance(
        add_parallelogram(transparent, Vec3(-1.f, 0.f, -5.f), Vec3(2.f, 0.f, 0.f), Vec3(0.f, 0.f, 2.f), t));
    EXPECT_EQ(skip_ids(transparent.arrays()), Ids({"delta_mis"}));
}

std::vector<std::string> render_log(const SceneArrays& arrays, const std::string& integrator) {
    Params p = basic_params(16, 12, 2, 4);
    p.set("threads", int64_t(2));
    p.set("integrator", integrator);
    Session s(arrays, p);
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    return s.take_log();
}

int lines_with(const std::vector<std::string>& log, const std::string& what) {
    return int(
        std::count_if(log.begin(), log.end(), [&](const std::string& l) { return l.find(what) != std::string::npos; }));
}

TEST(SceneSkips, TheLogNamesThemOnce) {
    MeshBuilder point = floor_only();
    point.add_point_light(Vec3(0.f, 1.f, -4.f), Color(50.f));
    const std::vector<std::string> bdpt = render_log(point.arrays(), "BDPT");
    EXPECT_EQ(lines_with(bdpt, "Skipped, the scene does not need them: "), 1);
    EXPECT_EQ(lines_with(bdpt, "BDPT's s = 0 strategies"), 1);
    EXPECT_EQ(lines_with(bdpt, "MIS for 1 point/spot/sun light(s)"), 1);
    const std::vector<std::string> path = render_log(point.arrays(), "PATH");
    EXPECT_EQ(lines_with(path, "BDPT's s = 0"), 0);
    EXPECT_EQ(lines_with(path, "MIS for 1 point"), 1);
    // AUTO logs its chosen integrator's skips (once: the session leaves them to it).
    const std::vector<std::string> autolog = render_log(cornell_box(), "AUTO");
    EXPECT_EQ(lines_with(autolog, "Skipped, the scene does not need them: transparent shadows"), 1);
}

}  // namespace
}  // namespace candela::test
