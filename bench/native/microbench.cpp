// Micro-benchmarks (Google Benchmark) of the per-sample routines a path spends time in outside Embree:
// pixel-filter sampling, light selection, light sampling and a closest-hit query; and the scene build's
// coplanar-overlap detection on its worst case. `make microbench`.
#include <benchmark/benchmark.h>

#include "core/rng.h"
#include "film/pixel_filter.h"
#include "input/scene_arrays.h"
#include "lights/light.h"
#include "sampling/warp.h"
#include "scene/coplanar_overlap.h"
#include "scene/scene.h"

namespace candela {
namespace {

void BM_FilterSample(benchmark::State& state) {
    const PixelFilter filter("BLACKMAN_HARRIS", 1.5f);
    Pcg32 rng(1, 2);
    for (auto _ : state) benchmark::DoNotOptimize(filter.sample({rng.next_float(), rng.next_float()}));
}
BENCHMARK(BM_FilterSample);

void BM_CosineHemisphere(benchmark::State& state) {
    Pcg32 rng(1, 2);
    for (auto _ : state) benchmark::DoNotOptimize(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
}
BENCHMARK(BM_CosineHemisphere);

void BM_LightSelect(benchmark::State& state) {
    LightSet set;
    Pcg32 rng(1, 2);
    for (int i = 0; i < state.range(0); ++i) {
        PointLight p;
        p.intensity = Color(1.f + rng.next_float());
        set.add(p);
    }
    set.finalize(1.f);
    float pmf;
    for (auto _ : state) benchmark::DoNotOptimize(set.select(rng.next_float(), &pmf));
}
BENCHMARK(BM_LightSelect)->Arg(4)->Arg(1024)->Arg(65536);

void BM_TriangleLightSample(benchmark::State& state) {
    TriangleLight t{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0, 0, -1), Color(1.f), 0.5f};
    const Light light(t);
    Pcg32 rng(1, 2);
    const LightSampleContext ctx{Vec3(0.f), Vec3(0, 0, 1)};
    for (auto _ : state) benchmark::DoNotOptimize(light_sample_li(light, ctx, {rng.next_float(), rng.next_float()}));
}
BENCHMARK(BM_TriangleLightSample);

/// A closed box of 12 triangles with the camera inside: closest hits in random directions.
void BM_SceneIntersect(benchmark::State& state) {
    const float p[24] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1};
    const uint32_t t[36] = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                            3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
    const uint32_t zeros[12] = {}, start[2] = {0, 12}, inst[1] = {0}, mtype[1] = {0};
    const float eye[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, mat[6] = {0.5f, 0.5f, 0.5f, 0, 0, 0};
    SceneArrays a;
    a.set("positions", ElemType::F32, {8, 3}, p);
    a.set("triangles", ElemType::U32, {12, 3}, t);
    a.set("tri_material", ElemType::U32, {12}, zeros);
    a.set("mesh_tri_start", ElemType::U32, {2}, start);
    a.set("instance_mesh", ElemType::U32, {1}, inst);
    a.set("instance_transform", ElemType::F32, {1, 4, 4}, eye);
    a.set("material_type", ElemType::U32, {1}, mtype);
    a.set("materials", ElemType::F32, {1, 6}, mat);
    a.set("camera_to_world", ElemType::F32, {4, 4}, eye);
    Params params;
    params.set("width", int64_t(8));
    params.set("height", int64_t(8));
    params.set("threads", int64_t(1));
    const Scene scene(a, params, nullptr);
    Pcg32 rng(1, 2);
    SurfaceHit hit;
    for (auto _ : state) {
        const Ray r{Vec3(0.f), sample_uniform_sphere({rng.next_float(), rng.next_float()})};
        benchmark::DoNotOptimize(scene.intersect(r, &hit));
    }
}
BENCHMARK(BM_SceneIntersect);

// Coplanar-overlap detection (scene build) on its worst case: two coplanar n×n-quad grids side by side, touching
// along an edge, so every face lands in one plane cluster. Arg: n (500 gives a million faces).
void BM_CoplanarDetectionTwoGrids(benchmark::State& state) {
    const int n = int(state.range(0));
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
    std::vector<CoplanarObject> objects;
    for (int g = 0; g < 2; ++g) {
        const auto v0 = uint32_t(positions.size() / 3), t0 = uint32_t(triangles.size() / 3);
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) positions.insert(positions.end(), {g + float(i) / n, float(j) / n, -2.f});
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const uint32_t a = v0 + uint32_t(i * (n + 1) + j), c = a + uint32_t(n + 1);
                triangles.insert(triangles.end(), {a, c, c + 1, a, c + 1, a + 1});
            }
        objects.push_back({t0, uint32_t(triangles.size() / 3), Affine()});
    }
    for (auto _ : state) benchmark::DoNotOptimize(find_coplanar_rivals(positions.data(), triangles.data(), objects));
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(triangles.size() / 3));
}
BENCHMARK(BM_CoplanarDetectionTwoGrids)->Arg(100)->Arg(500)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace candela

// main(): bench/native/texture_microbench.cpp (it adds the texture ratio table).
