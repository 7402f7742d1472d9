// The cost of one shading evaluation of each procedural texture (a shader program: coordinates → the texture with
// Blender's default settings) against an image texture lookup (UV → a 1024² 8-bit sRGB image, linear
// interpolation, Blender's defaults), measured in the same run; `make microbench` prints the ratios at the end.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/rng.h"
#include "texture/shader_program.h"

namespace candela {
namespace {

struct Program {
    std::vector<ShaderOp> ops;
    std::vector<float> consts;
    uint32_t constant(float x, float y, float z) {
        const uint32_t offset = uint32_t(consts.size());
        consts.insert(consts.end(), {x, y, z});
        ops.push_back({ShaderOpCode::Const, 0, 0, 0, {offset, 0, 0, 0}});
        return uint32_t(ops.size() - 1);
    }
    uint32_t op(ShaderOpCode code, uint32_t a = 0, uint32_t b = 0, uint32_t c = 0, std::array<uint32_t, 4> i = {}) {
        ops.push_back({code, a, b, c, {i[0], i[1], i[2], i[3]}});
        return uint32_t(ops.size() - 1);
    }
    uint32_t coord(CoordKind kind) { return op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(kind), 0, 0, 0}); }
};

/// Blender's defaults for each texture node, as one program each.
std::map<std::string, Program> texture_programs() {
    std::map<std::string, Program> out;
    auto make = [&](const char* name, auto build) {
        Program p;
        const uint32_t v = p.coord(CoordKind::Generated);
        build(p, v);
        out[name] = std::move(p);
    };
    make("Noise3D", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexNoise, v, p.constant(0.f, 5.f, 2.f), p.constant(0.5f, 0.f, 0.f), {3, 0, 0, 0});
    });
    make("Noise3DColor", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexNoise, v, p.constant(0.f, 5.f, 2.f), p.constant(0.5f, 0.f, 0.f), {3, 1, 0, 0});
    });
    make("Noise4DDetail15", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexNoise, v, p.constant(0.3f, 5.f, 15.f), p.constant(0.5f, 0.f, 0.f), {4, 0, 0, 0});
    });
    make("WhiteNoise3D", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexWhiteNoise, v, p.constant(0.f, 0.f, 0.f), 0, {3, 1, 0, 0});
    });
    make("VoronoiF1", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexVoronoi, v, p.constant(0.f, 5.f, 1.f), p.constant(0.5f, 1.f, 0.f), {3, 0, 0, 0});
    });
    make("VoronoiSmoothF1", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexVoronoi, v, p.constant(0.f, 5.f, 1.f), p.constant(0.5f, 1.f, 0.f), {3, 2, 0, 1});
    });
    make("MusgraveFbm", [](Program& p, uint32_t v) {
        const uint32_t gain = p.constant(1.f, 1.f, 1.f);
        p.op(ShaderOpCode::TexMusgrave, v, p.constant(0.f, 5.f, 2.f), p.constant(2.f, 2.f, 0.f), {gain, 3, 1, 0});
    });
    make("WaveBands", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexWave, v, p.constant(5.f, 0.f, 2.f), p.constant(1.f, 0.5f, 0.f), {0, 0, 0, 0});
    });
    make("Magic", [](Program& p, uint32_t v) {
        p.op(ShaderOpCode::TexMagic, v, p.constant(5.f, 1.f, 0.f), 0, {2, 0, 0, 0});
    });
    make("Checker", [](Program& p, uint32_t v) {
        const uint32_t scale = p.constant(5.f, 5.f, 5.f);
        p.op(ShaderOpCode::TexChecker, v, p.constant(0.8f, 0.8f, 0.8f), p.constant(0.2f, 0.2f, 0.2f), {scale, 0, 0, 0});
    });
    make("Brick", [](Program& p, uint32_t v) {
        const uint32_t mortar = p.constant(0.f, 0.f, 0.f), sizes = p.constant(5.f, 0.02f, 0.1f),
                       shape = p.constant(0.f, 0.5f, 0.25f);
        const uint32_t k = uint32_t(p.consts.size());
        p.consts.insert(p.consts.end(), {0.5f, 2.f, 1.f, 2.f, 0.f});
        p.op(ShaderOpCode::TexBrick, v, p.constant(0.8f, 0.8f, 0.8f), p.constant(0.2f, 0.2f, 0.2f),
             {mortar, sizes, shape, k});
    });
    make("Gradient", [](Program& p, uint32_t v) { p.op(ShaderOpCode::TexGradient, v, 0, 0, {0, 0, 0, 0}); });
    return out;
}

std::shared_ptr<const ShaderLibrary> library(const Program& p, TexturePools pools = {}) {
    return std::make_shared<const ShaderLibrary>(std::move(pools), std::vector<float>(), p.consts, p.ops,
                                                 std::vector<uint32_t>{0, uint32_t(p.ops.size())});
}

void run(benchmark::State& state, const ShaderLibrary& lib) {
    Pcg32 rng(3, 5);
    std::vector<ShadingInputs> points(1024);
    for (ShadingInputs& in : points) {
        in.generated = Vec3(rng.next_float(), rng.next_float(), rng.next_float());
        in.uv = Vec3(rng.next_float(), rng.next_float(), 0.f);
    }
    ShaderRegisters regs(lib.program_size(0));
    size_t k = 0;
    for (auto _ : state) {
        lib.evaluate(0, points[k++ & 1023], regs.data());
        benchmark::DoNotOptimize(regs.data()[lib.program_size(0) - 1]);
    }
}

void BM_TextureImageLookup(benchmark::State& state) {
    constexpr uint32_t n = 1024;
    TexturePools pools;
    pools.bytes.resize(size_t(4) * n * n);
    Pcg32 rng(7, 1);
    for (auto& b : pools.bytes) b = uint8_t(rng.next_float() * 255.f);
    pools.info = {0, n, n, uint32_t(TexColorSpace::Srgb), uint32_t(TexStorage::Byte)};
    Program p;
    const uint32_t uv = p.coord(CoordKind::Uv);
    p.op(ShaderOpCode::Image, uv, 0, 0, {0, uint32_t(TexInterpolation::Linear), uint32_t(TexExtension::Repeat), 0});
    run(state, *library(p, std::move(pools)));
}
BENCHMARK(BM_TextureImageLookup);

void BM_TextureProcedural(benchmark::State& state, const std::string& name) {
    static const auto programs = texture_programs();
    run(state, *library(programs.at(name)));
}

const bool k_registered = [] {
    for (const auto& [name, program] : texture_programs())
        benchmark::RegisterBenchmark(("BM_TextureProcedural/" + name).c_str(), BM_TextureProcedural, name);
    return true;
}();

}  // namespace

/// Prints each procedural texture's time per evaluation over the image lookup's, from the same run.
class TextureRatioReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& r : runs) {
            const std::string name = r.benchmark_name();
            const double ns = r.GetAdjustedRealTime();
            if (name == "BM_TextureImageLookup")
                m_image_ns = ns;
            else if (name.rfind("BM_TextureProcedural/", 0) == 0)
                m_procedural.emplace_back(name.substr(21), ns);
        }
        ConsoleReporter::ReportRuns(runs);
    }
    void Finalize() override {
        ConsoleReporter::Finalize();
        if (m_image_ns <= 0.0 || m_procedural.empty()) return;
        std::printf(
            "\nShading evaluation per texture (Blender's defaults) against an image lookup (1024^2 8-bit sRGB, "
            "linear), this run:\n%-18s %10s %10s\n",
            "texture", "ns/call", "x image");
        std::printf("%-18s %10.1f %10.2f\n", "ImageLookup", m_image_ns, 1.0);
        for (const auto& [name, ns] : m_procedural)
            std::printf("%-18s %10.1f %10.2f\n", name.c_str(), ns, ns / m_image_ns);
    }

private:
    double m_image_ns = 0.0;
    std::vector<std::pair<std::string, double>> m_procedural;
};

}  // namespace candela

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    candela::TextureRatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}
