// Golden images of the path tracer: a small room with every kind of surface and light the path tracer has a
// code path for, rendered per sampler and per path-tracer setting, and compared bit for bit (a 64-bit FNV-1a
// hash of the Combined and Noise floats) with the hashes recorded when the test was written. Refactors of the
// path tracer, the tile loop, the film or the shared path rules must leave these images exactly as they were;
// an intended change of the image updates the hashes in the same commit and says why. Images are identical for
// the same seed and the same binary (docs/architecture.md, "Determinism and the build target"); with floating-point
// contraction off they are also the same for every instruction-set level on one machine. The hashes changed once,
// when contraction was turned off (multiply-adds fused differently in different translation units had made the
// test binary's images depend on which test files it linked).
#include <gtest/gtest.h>

#include <array>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "lights/light.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

uint64_t fnv1a(const std::vector<float>& values, uint64_t h = 1469598103934665603ull) {
    for (float v : values) {
        uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int i = 0; i < 4; ++i) {
            h ^= (bits >> (8 * i)) & 0xffu;
            h *= 1099511628211ull;
        }
    }
    return h;
}

std::vector<float> translate(float x, float y, float z, float s = 1.f) {
    return {s, 0, 0, x, 0, s, 0, y, 0, 0, s, z, 0, 0, 0, 1};
}

void add_quad(MeshBuilder& b, Vec3 a, Vec3 c1, Vec3 c2, Vec3 c3, uint32_t material) {
    b.add_instance(b.add_triangle(a, c1, c2, material));
    b.add_instance(b.add_triangle(a, c2, c3, material));
}

/// A room (diffuse walls) with a window in the back wall onto a dim constant world and a sun, a rough glossy
/// sphere, a glass sphere, a smooth mirror quad, a Principled cube, an emissive ceiling triangle (two-sided), a
/// soft point light, a spot and a disk area light.
SceneArrays golden_room() {
    MeshBuilder b;
    const uint32_t wall = b.add_material(Color(0.6f, 0.55f, 0.5f), Color(0.f));
    const uint32_t glossy = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glossy, "GLOSSY", {{"color_r", 0.9f}, {"color_g", 0.7f}, {"color_b", 0.5f}, {"roughness", 0.3f}});
    const uint32_t glass = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(glass, "GLASS", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}, {"ior", 1.5f}});
    const uint32_t mirror = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(mirror, "GLOSSY", {{"color_r", 0.95f}, {"color_g", 0.95f}, {"color_b", 0.95f}, {"roughness", 0.f}});
    const uint32_t principled = b.add_material(Color(0.f), Color(0.f));
    b.add_closure(principled, "PRINCIPLED",
                  {{"color_r", 0.2f},
                   {"color_g", 0.5f},
                   {"color_b", 0.8f},
                   {"roughness", 0.4f},
                   {"specular", 0.5f},
                   {"clearcoat", 0.3f},
                   {"clearcoat_roughness", 0.1f},
                   {"sheen", 0.2f},
                   {"ior", 1.45f}});
    const uint32_t lamp = b.add_material(Color(0.f), Color(6.f, 5.f, 4.f));

    const float X = 2.f, Y = 1.5f, Z0 = -3.f, Z1 = 3.f;
    add_quad(b, {-X, -Y, Z0}, {X, -Y, Z0}, {X, -Y, Z1}, {-X, -Y, Z1}, wall);  // floor
    add_quad(b, {-X, Y, Z0}, {-X, Y, Z1}, {X, Y, Z1}, {X, Y, Z0}, wall);      // ceiling
    add_quad(b, {-X, -Y, Z0}, {-X, -Y, Z1}, {-X, Y, Z1}, {-X, Y, Z0}, wall);  // left
    add_quad(b, {X, -Y, Z0}, {X, Y, Z0}, {X, Y, Z1}, {X, -Y, Z1}, wall);      // right
    add_quad(b, {-X, -Y, Z1}, {X, -Y, Z1}, {X, Y, Z1}, {-X, Y, Z1}, wall);    // behind the camera
    // The back wall, with a window in its upper right quarter.
    add_quad(b, {-X, -Y, Z0}, {0.5f, -Y, Z0}, {0.5f, Y, Z0}, {-X, Y, Z0}, wall);
    add_quad(b, {0.5f, -Y, Z0}, {X, -Y, Z0}, {X, 0.f, Z0}, {0.5f, 0.f, Z0}, wall);
    const uint32_t sphere = b.add_sphere(0.5f, 24, 12, glossy);
    const std::vector<float> at_left = translate(-0.9f, -1.f, -2.f);
    b.add_instance(sphere, at_left.data());
    const uint32_t glass_sphere = b.add_sphere(0.45f, 24, 12, glass);
    const std::vector<float> at_right = translate(0.8f, -1.05f, -1.6f);
    b.add_instance(glass_sphere, at_right.data());
    const uint32_t cube = b.add_box(Vec3(0.3f, 0.3f, 0.3f), principled);
    const std::vector<float> at_back = translate(0.2f, -1.2f, -2.6f);
    b.add_instance(cube, at_back.data());
    b.add_instance(b.add_quad_z(-1.9f, -0.5f, -1.4f, 0.4f, -2.95f, mirror));
    b.add_instance(b.add_triangle(Vec3(-0.4f, 1.45f, -1.6f), Vec3(0.4f, 1.45f, -1.6f), Vec3(0.f, 1.45f, -2.4f), lamp));
    b.add_point_light(Vec3(1.2f, 1.f, -1.f), Color(8.f, 8.f, 10.f), 0.1f);
    std::vector<float> spot(light_columns().size(), 0.f);
    for (int c = 0; c < 3; ++c) spot[c] = 30.f;        // strength
    spot[3] = -1.5f, spot[4] = 1.2f, spot[5] = -0.5f;  // position
    const Vec3 spot_dir = normalize(Vec3(0.5f, -0.8f, -0.33f));
    spot[6] = spot_dir.x, spot[7] = spot_dir.y, spot[8] = spot_dir.z;  // direction
    spot[15] = 0.05f, spot[16] = 0.9f, spot[17] = 0.3f;                // radius, spot size, blend
    b.add_light(1, spot);
    b.add_area_light(Vec3(1.5f, 0.f, -2.9f), Vec3(0.6f, 0.f, 0.f), Vec3(0.f, 0.4f, 0.f), Vec3(0.f, 0.f, 1.f),
                     Color(10.f, 6.f, 3.f), /*disk=*/true);
    std::vector<float> sun(light_columns().size(), 0.f);
    for (int c = 0; c < 3; ++c) sun[c] = 3.f;                   // irradiance, W/m²
    const Vec3 sun_dir = normalize(Vec3(-0.3f, -0.5f, 0.81f));  // direction of travel: through the window
    sun[6] = sun_dir.x, sun[7] = sun_dir.y, sun[8] = sun_dir.z;
    sun[18] = 0.05f;  // angle
    b.add_light(2, sun);
    b.world_color = {0.05f, 0.06f, 0.08f};
    return b.arrays();
}

Params golden_params() {
    Params p = basic_params(32, 24, 8, 6);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("seed", int64_t(11));
    return p;
}

struct GoldenCase {
    const char* name;
    std::vector<std::pair<std::string, Params::Value>> settings;
    // The image's hash on each machine kind it was recorded on (k_machine_kinds): one bit rounded differently
    // on another CPU (in Embree's kernels or in libm, both of which pick code by CPU) changes every image.
    std::array<uint64_t, 2> hash;
};

// The machine kinds the hashes were recorded on: [0] the first development machines (where every hash was first
// recorded), [1] AMD EPYC with AVX2 and no AVX-512, recorded from a path tracer unchanged since [0]'s record (at
// 15094fc every case differed from [0] there).
constexpr int k_machine_kinds = 2;

std::string hex(uint64_t h) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%016" PRIx64 "ull", h);
    return buf;
}

// The recorded images. Each case differs from the defaults (Sobol, light tree, solid angle, MIS with the power
// heuristic, throughput roulette from bounce 3) in the settings listed.
const std::vector<GoldenCase>& golden_cases() {
    using S = std::string;
    static const std::vector<GoldenCase> cases = {
        {"random", {{"sampler", S("RANDOM")}}, {0x8538de942522682full, 0xe0de03188eaebd55ull}},
        {"stratified", {{"sampler", S("STRATIFIED")}}, {0x38f85f25efa1ea46ull, 0x751a0a581e16c97cull}},
        {"nrooks", {{"sampler", S("NROOKS")}}, {0x0e999f3a9d6a2012ull, 0x309587ad4aef5b17ull}},
        {"halton", {{"sampler", S("HALTON")}}, {0x692f87180c418505ull, 0xa34170fd5c0bab68ull}},
        {"hammersley", {{"sampler", S("HAMMERSLEY")}}, {0x339cb03665fd4f32ull, 0x53664629a3e38eb9ull}},
        {"sobol", {{"sampler", S("SOBOL")}}, {0xf3ab392d0986279cull, 0x4fafc9b4440b44beull}},
        {"cycles_equal",
         {{"light_selection", S("POWER")}, {"rr_mode", S("SQRT_THROUGHPUT")}, {"rr_start_bounce", int64_t(2)}},
         {0x52a61710a19e9102ull, 0x0151c69e45c9c073ull}},
        {"uniform_selection", {{"light_selection", S("UNIFORM")}}, {0x003b03fc6d4d9123ull, 0x913e38a356009414ull}},
        {"area_selection", {{"light_selection", S("AREA")}}, {0x504d690fd97245edull, 0xc8c7f04f6c6636fcull}},
        {"all_lights", {{"light_selection", S("ALL")}}, {0x77ec10bc6c9c9d0eull, 0x42bf7dfe12d2c2caull}},
        {"ward",
         {{"light_selection", S("WARD")}, {"ward_threshold", 0.1}},
         {0x84a6bac085947c6dull, 0xf699728805ec5412ull}},
        {"area_pdf", {{"light_pdf", S("AREA")}}, {0x4a1e926f531528a4ull, 0xf54411c2329fead5ull}},
        {"bsdf_only", {{"light_sampling", S("BSDF_ONLY")}}, {0x4422773877b72fbdull, 0xc473089d4515706aull}},
        {"light_only", {{"light_sampling", S("LIGHT_ONLY")}}, {0x862676df0e29f1d2ull, 0xb60fdcf6b03f38bfull}},
        {"balance", {{"mis_heuristic", S("BALANCE")}}, {0xd914a49f0e26431eull, 0xe50619f308ae5a09ull}},
        {"uniform_hemisphere", {{"hemisphere_sampling", S("UNIFORM")}}, {0xd458973ebb815237ull, 0xf27a1f29b83a5d31ull}},
        {"cosine_hemisphere", {{"hemisphere_sampling", S("COSINE")}}, {0x2d07b40ca3d3b5acull, 0xf4d6e32b86e4d22cull}},
        {"branching", {{"branching_factor", int64_t(3)}}, {0x0c746dfaf1fcf3f7ull, 0xd844f9afbfa0db92ull}},
        {"light_samples", {{"light_samples", int64_t(2)}}, {0xd4a1c582afe49598ull, 0x104e09edfbaae641ull}},
        {"albedo_roulette",
         {{"rr_mode", S("ALBEDO")}, {"rr_start_bounce", int64_t(1)}},
         {0xf38cd9ba788826a3ull, 0x0ca4543e53f486ddull}},
        {"no_roulette", {{"rr_mode", S("OFF")}}, {0x8c2627cdd5dcc410ull, 0xf67e31601a0acd96ull}},
        // Recorded again when clamping took Cycles 3.4's rule (R + G + B against 3 × the clamp, not the brightest component).
        {"clamped", {{"clamp_indirect", 0.5}}, {0x70b4ed69e2c44505ull, 0xd295865c425944b3ull}},
        {"transparent", {{"film_transparent", true}}, {0x6442ccf14e0b4690ull, 0x10372365bca2d23eull}},
        {"noise_stop",
         {{"samples", int64_t(256)}, {"noise_threshold", 0.25}},
         {0x3aa6b438f8f70c55ull, 0xda0b597c9c4d9853ull}},
        {"one_thread_tiles",
         {{"threads", int64_t(1)}, {"tile_size", int64_t(7)}},
         {0xf3ab392d0986279cull, 0x4fafc9b4440b44beull}},
        {"gaussian_dof",
         {{"pixel_filter", S("GAUSSIAN")},
          {"filter_width", 2.0},
          {"use_dof", true},
          {"focus_distance", 2.0},
          {"aperture_fstop", 2.8},
          {"aperture_blades", int64_t(6)}},
         {0x8cd9a03786fe8121ull, 0x7a1a2c69264097b8ull}},
    };
    return cases;
}

TEST(GoldenImage, PathTracerImagesAreBitIdenticalToTheRecordedOnes) {
    // The images pass if one machine kind's hashes match every case: a changed image matches none (a 64-bit
    // hash equal to another kind's record by chance is a 2^-64 event per case).
    std::vector<uint64_t> hashes;
    for (const GoldenCase& c : golden_cases()) {
        Params p = golden_params();
        for (const auto& [key, value] : c.settings) p.set(key, value);
        const RenderResult r = render(golden_room(), p);  // through a Session, as the add-on renders
        EXPECT_GT(r.mean_rgb, 0.02) << c.name << ": the room is lit";
        hashes.push_back(fnv1a(r.noise, fnv1a(r.rgba)));
    }
    int best_kind = 0, best_matches = -1;
    for (int k = 0; k < k_machine_kinds; ++k) {
        int matches = 0;
        for (size_t i = 0; i < hashes.size(); ++i) matches += hashes[i] == golden_cases()[i].hash[size_t(k)];
        if (matches > best_matches) {
            best_matches = matches;
            best_kind = k;
        }
    }
    std::string report;
    for (size_t i = 0; i < hashes.size(); ++i) {
        const GoldenCase& c = golden_cases()[i];
        if (hashes[i] != c.hash[size_t(best_kind)])
            report += std::string("  ") + c.name + ": " + hex(hashes[i]) + " (recorded " +
                      hex(c.hash[size_t(best_kind)]) + " on machine kind " + std::to_string(best_kind) + ")\n";
    }
    EXPECT_EQ(best_matches, int(hashes.size())) << "path-tracer images changed:\n" << report;
}

// The golden cases really are different images (a case whose setting had no effect would guard nothing).
TEST(GoldenImage, EveryCaseRecordsADistinctImage) {
    for (size_t k = 0; k < size_t(k_machine_kinds); ++k) {
        std::vector<uint64_t> seen;
        for (const GoldenCase& c : golden_cases()) {
            if (std::string(c.name) == "one_thread_tiles") continue;  // the same image as "sobol", by determinism
            for (uint64_t h : seen) EXPECT_NE(h, c.hash[k]) << c.name << " on machine kind " << k;
            seen.push_back(c.hash[k]);
        }
        for (const GoldenCase& c : golden_cases()) {
            if (std::string(c.name) != "one_thread_tiles") continue;
            for (const GoldenCase& d : golden_cases())
                if (std::string(d.name) == "sobol") EXPECT_EQ(c.hash[k], d.hash[k]);
        }
    }
}

}  // namespace
}  // namespace candela::test
