// `make skip-bench` (docs/auto.md, "Skips"): what each skip of integrators/scene_skips.h saves, measured in one run
// as the time ratio of a scene that allows the skip (A) to the same scene with the smallest change that defeats it
// (B: an emitter of zero or negligible power, a Transparent quad nobody sees, a world texture of one colour), both
// rendered through a Session (scene build included) in alternating order, round after round; the ratio printed is
// the median over rounds of t_B / t_A. Also AUTO's analysis (static features and pilot) as a share of a
// default-sample render (64 samples). Prints a Markdown table; asserts nothing (timings are the machine's).
//   candela_bench_skips [--rounds N] [--size W H] [--samples S]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "reference_scenes.h"
#include "session/session.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"

using namespace candela;
using namespace candela::test;

namespace {

struct Config {
    int rounds = 3, width = 96, height = 72, samples = 16;
};

double render_seconds(const SceneArrays& arrays, const Params& p, std::vector<std::string>* log = nullptr) {
    const auto t0 = std::chrono::steady_clock::now();
    Session s(arrays, p);
    s.start();
    s.join();
    if (auto e = s.error()) {
        std::fprintf(stderr, "render failed: %s\n", e->c_str());
        std::exit(1);
    }
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (log) *log = s.take_log();
    return t;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

Params params_for(const Config& c, const char* integrator) {
    Params p = basic_params(c.width, c.height, c.samples, 8);
    p.set("threads", int64_t(2));
    p.set("integrator", std::string(integrator));
    return p;
}

// A room of diffuse boxes on a floor in front of a wall.
MeshBuilder room() {
    MeshBuilder b;
    const uint32_t white = b.add_material(Color(0.6f), Color(0.f));
    b.add_instance(add_parallelogram(b, Vec3(-3.f, -1.f, -7.f), Vec3(0.f, 0.f, 6.f), Vec3(6.f, 0.f, 0.f), white));
    b.add_instance(add_parallelogram(b, Vec3(-3.f, -1.f, -7.f), Vec3(6.f, 0.f, 0.f), Vec3(0.f, 4.f, 0.f), white));
    b.add_instance(b.add_sphere(0.6f, 24, 12, white), translation(-0.8f, -0.4f, -4.5f).data());
    b.add_instance(b.add_sphere(0.5f, 24, 12, white), translation(0.9f, -0.5f, -4.f).data());
    return b;
}

// Degenerate (zero-area) emissive quads: light entries of zero power.
void add_zero_power_emitters(MeshBuilder& b, int n) {
    const uint32_t e = b.add_material(Color(0.f), Color(5.f));
    for (int i = 0; i < n; ++i)
        b.add_instance(
            add_parallelogram(b, Vec3(-2.f + 0.004f * i, 2.5f, -5.f), Vec3(0.1f, 0.f, 0.f), Vec3(0.2f, 0.f, 0.f), e));
}

// A quad under the floor, facing down, nobody sees and no light reaches: `emission` (a negligible emitter) or a
// Transparent closure.
void add_hidden_quad(MeshBuilder& b, bool transparent, Color emission) {
    const uint32_t m = b.add_material(Color(0.f), emission);
    if (transparent) b.add_closure(m, "TRANSPARENT", {{"color_r", 1.f}, {"color_g", 1.f}, {"color_b", 1.f}});
    b.add_instance(add_parallelogram(b, Vec3(-0.5f, -2.f, -4.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 0.f, 1.f), m));
}

SceneArrays with_world_texture(SceneArrays a, Color c) {
    ProgramBuilder pb;
    const uint32_t tex = pb.image(8, 4, std::vector<Color>(32, c));
    const uint32_t dir = pb.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
    const uint32_t img =
        pb.op(ShaderOpCode::Image, dir, 0, 0,
              {tex, uint32_t(TexInterpolation::Linear), 0, uint32_t(ImageProjection::Equirectangular)});
    pb.bind(InputTarget::World, 0, 0, 3, pb.end_program(), img);
    pb.add_to(a);
    return a;
}

struct Case {
    const char* skip;
    const char* integrator;
    const char* a_desc;
    const char* b_desc;
    SceneArrays a, b;
};

}  // namespace

int main(int argc, char** argv) {
    Config c;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc) c.rounds = std::atoi(argv[++i]);
        if (!std::strcmp(argv[i], "--samples") && i + 1 < argc) c.samples = std::atoi(argv[++i]);
        if (!std::strcmp(argv[i], "--size") && i + 2 < argc) {
            c.width = std::atoi(argv[++i]);
            c.height = std::atoi(argv[++i]);
        }
    }
    std::vector<Case> cases;
    {
        MeshBuilder a = room();
        a.world_color = {0.5f, 0.6f, 0.8f};
        MeshBuilder b = a;
        add_zero_power_emitters(b, 1);
        cases.push_back({"no_nee", "PATH", "lit by a constant world only", "+ one zero-power emitter (NEE runs)",
                         a.arrays(), b.arrays()});
    }
    {
        MeshBuilder a = room();
        a.add_area_light(Vec3(0.f, 2.5f, -4.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 0.f, 1.f), Vec3(0.f, -1.f, 0.f),
                         Color(20.f), false);
        a.world_color = {0.3f, 0.3f, 0.3f};
        MeshBuilder b0 = room();
        b0.add_area_light(Vec3(0.f, 2.5f, -4.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 0.f, 1.f), Vec3(0.f, -1.f, 0.f),
                          Color(20.f), false);
        cases.push_back({"constant_world", "PATH", "area light, constant world 0.3",
                         "the same world as an 8x4 image of 0.3 (importance map, light-sampled)", a.arrays(),
                         with_world_texture(b0.arrays(), Color(0.3f))});
    }
    {
        MeshBuilder a = room();
        a.add_area_light(Vec3(0.f, 2.5f, -4.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 0.f, 1.f), Vec3(0.f, -1.f, 0.f),
                         Color(20.f), false);
        MeshBuilder b = a;
        add_zero_power_emitters(b, 1000);
        cases.push_back({"zero_power_lights", "PATH", "one area light",
                         "+ 1000 zero-power emitters (kept, never selected)", a.arrays(), b.arrays()});
    }
    {
        MeshBuilder a = room();
        a.add_point_light(Vec3(0.f, 2.f, -4.f), Color(40.f));
        a.add_area_light(Vec3(1.f, 2.5f, -5.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 0.f, 1.f), Vec3(0.f, -1.f, 0.f),
                         Color(10.f), false);
        MeshBuilder b = a;
        add_hidden_quad(b, true, Color(0.f));
        cases.push_back({"no_transparent_shadows", "PATH", "point and area light",
                         "+ an unseen Transparent quad (shadow rays walk surfaces)", a.arrays(), b.arrays()});
    }
    {
        MeshBuilder a = room();
        a.add_point_light(Vec3(0.f, 2.f, -4.f), Color(40.f));
        MeshBuilder b = a;
        add_hidden_quad(b, false, Color(1e-9f));
        cases.push_back({"bdpt_no_s0", "BDPT", "point light only",
                         "+ an unseen emitter of 1e-9 (s = 0 strategies evaluated)", a.arrays(), b.arrays()});
    }

    std::printf(
        "Skip savings: %dx%d, %d samples, 2 threads, median of %d paired rounds (t_B / t_A; > 1: the skip "
        "saves)\n\n",
        c.width, c.height, c.samples, c.rounds);
    std::printf("| skip | integrator | A (skip applies) | B (skip defeated) | t_A s | t_B s | t_B / t_A |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const Case& k : cases) {
        const Params p = params_for(c, k.integrator);
        std::vector<double> ratios, ta, tb;
        render_seconds(k.a, p);  // warm-up (caches, page faults)
        for (int r = 0; r < c.rounds; ++r) {
            double a, b;
            if (r % 2 == 0) {
                a = render_seconds(k.a, p);
                b = render_seconds(k.b, p);
            } else {
                b = render_seconds(k.b, p);
                a = render_seconds(k.a, p);
            }
            ta.push_back(a);
            tb.push_back(b);
            ratios.push_back(b / a);
        }
        std::printf("| `%s` | %s | %s | %s | %.3f | %.3f | %.3f |\n", k.skip, k.integrator, k.a_desc, k.b_desc,
                    median(ta), median(tb), median(ratios));
        std::fflush(stdout);
    }

    // AUTO's analysis as a share of a render at the default 64 samples.
    std::printf("\nAUTO's analysis (static features + pilot) against a 64-sample render, %dx%d:\n\n", 2 * c.width,
                2 * c.height);
    std::printf("| scene | choice | analysis ms | pilot ms | render s | share |\n|---|---|---|---|---|---|\n");
    const std::pair<const char*, SceneArrays> scenes[] = {{"cornell_box", cornell_box()},
                                                          {"glass_caustic", glass_caustic()}};
    for (const auto& [name, arrays] : scenes) {
        Params p = basic_params(2 * c.width, 2 * c.height, 64, 12);
        p.set("threads", int64_t(2));
        p.set("integrator", std::string("AUTO"));
        std::vector<std::string> log;
        const double t = render_seconds(arrays, p, &log);
        double analysis = -1.0, pilot = -1.0;
        std::string choice = "?";
        for (const std::string& l : log) {
            const size_t at = l.find("; analysis ");
            if (l.rfind("Auto: chose ", 0) == 0 && at != std::string::npos) {
                choice = l.substr(12, l.find(' ', 12) - 12);
                std::sscanf(l.c_str() + at, "; analysis %lf ms, of which pilot %lf ms", &analysis, &pilot);
            }
        }
        std::printf("| %s | %s | %.1f | %.1f | %.2f | %.2f %% |\n", name, choice.c_str(), analysis, pilot, t,
                    100.0 * analysis / 1000.0 / t);
    }
    return 0;
}
