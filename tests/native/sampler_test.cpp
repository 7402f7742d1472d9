// Pixel samplers: exact radical-inverse / Halton / Hammersley values (docs/verification.md §4.1–§4.4), elementary
// intervals and strata, call-order independence, value range, decorrelation of pixels and dimensions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "sampling/low_discrepancy.h"
#include "sampling/sampler.h"

namespace candela {
namespace {

const std::vector<std::string> k_all = {"RANDOM", "STRATIFIED", "NROOKS", "HALTON", "HAMMERSLEY", "SOBOL"};
const std::vector<std::string> k_qmc = {"STRATIFIED", "NROOKS", "HALTON", "HAMMERSLEY", "SOBOL"};

// ---- exact values ----

TEST(LowDiscrepancy, RadicalInverseTables) {
    const double b2[16] = {0,     .5,    .25,   .75,   .125,  .625,  .375,  .875,
                           .0625, .5625, .3125, .8125, .1875, .6875, .4375, .9375};
    for (int i = 0; i < 16; ++i) EXPECT_EQ(radical_inverse(0, uint64_t(i)), b2[i]) << i;
    const double b3[9] = {0, 1 / 3., 2 / 3., 1 / 9., 4 / 9., 7 / 9., 2 / 9., 5 / 9., 8 / 9.};
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(radical_inverse(1, uint64_t(i)), b3[i], 1e-15) << i;
    const double b5[6] = {0, .2, .4, .6, .8, .04};
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(radical_inverse(2, uint64_t(i)), b5[i], 1e-15) << i;
    // Indices beyond 32 bits go through the digit loop: Φ_2(2^32 + 1) = 1/2 + 2^-33.
    EXPECT_EQ(radical_inverse_base(2, (uint64_t(1) << 32) + 1), 0.5 + 0x1p-33);
}

TEST(LowDiscrepancy, RadicalInverseBase2IsReversedBits) {
    for (uint32_t a = 0; a < 1024; ++a)
        ASSERT_EQ(radical_inverse(0, a), double(reverse_bits32(a)) * 2.3283064365386963e-10) << a;
}

TEST(LowDiscrepancy, PrimesAndGeneralBaseLoop) {
    const uint32_t first[10] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29};
    for (int i = 0; i < 10; ++i) EXPECT_EQ(prime(i), first[i]);
    EXPECT_EQ(prime(255), 1619u);
    EXPECT_EQ(prime(k_num_primes - 1), 8161u);
    // Φ_b(b^k) = b^-(k+1) and Φ_b(b−1) = (b−1)/b in any base.
    for (int bi = 0; bi < 50; ++bi) {
        const uint32_t b = prime(bi);
        EXPECT_NEAR(radical_inverse(bi, b), 1.0 / (double(b) * b), 1e-15);
        EXPECT_NEAR(radical_inverse(bi, b - 1), double(b - 1) / b, 1e-15);
    }
}

TEST(LowDiscrepancy, UnscrambledHaltonTable) {
    const double t[5][5] = {{0, 0, 0, 0, 0},
                            {0.5, 0.333333333333333, 0.2, 0.142857142857143, 0.090909090909091},
                            {0.25, 0.666666666666667, 0.4, 0.285714285714286, 0.181818181818182},
                            {0.75, 0.111111111111111, 0.6, 0.428571428571429, 0.272727272727273},
                            {0.125, 0.444444444444444, 0.8, 0.571428571428571, 0.363636363636364}};
    for (int i = 0; i < 5; ++i)
        for (int d = 0; d < 5; ++d) EXPECT_NEAR(halton(d, uint64_t(i)), t[i][d], 1e-7) << i << "," << d;
}

TEST(LowDiscrepancy, UnscrambledHammersleyTable) {
    const double t[5][4] = {{0, 0, 0, 0},
                            {0.2, 0.5, 0.333333333333333, 0.2},
                            {0.4, 0.25, 0.666666666666667, 0.4},
                            {0.6, 0.75, 0.111111111111111, 0.6},
                            {0.8, 0.125, 0.444444444444444, 0.8}};
    for (int i = 0; i < 5; ++i)
        for (int d = 0; d < 4; ++d) EXPECT_NEAR(hammersley(d, uint64_t(i), 5), t[i][d], 1e-7) << i << "," << d;
}

TEST(LowDiscrepancy, SobolFirstDimensions) {
    // Dimension 1 of Sobol (primitive polynomial x + 1): direction numbers m = 1, 3, 5, 15 → 0.5, 0.75, 0.625, 0.9375.
    EXPECT_EQ(sobol_dim1(1), 0x80000000u);
    EXPECT_EQ(sobol_dim1(2), 0xc0000000u);
    EXPECT_EQ(sobol_dim1(4), 0xa0000000u);
    EXPECT_EQ(sobol_dim1(8), 0xf0000000u);
    EXPECT_EQ(sobol_dim1(3), 0x40000000u);  // 0.5 xor 0.75 = 0.25
    EXPECT_EQ(sobol_dim0(1), 0x80000000u);
    EXPECT_EQ(sobol_dim0(3), 0xc0000000u);
    // The byte-table evaluation equals the bit-by-bit generator matrix on every single bit and on random words.
    for (int b = 0; b < 32; ++b) EXPECT_EQ(sobol_dim1(1u << b), sobol_dim1_bitwise(1u << b)) << b;
    Pcg32 rng(5, 6);
    for (int k = 0; k < 10000; ++k) {
        const uint32_t i = rng.next_u32();
        ASSERT_EQ(sobol_dim1(i), sobol_dim1_bitwise(i)) << i;
        ASSERT_EQ(sobol_dim1_reversed(i), reverse_bits32(sobol_dim1_bitwise(i))) << i;
    }
}

TEST(LowDiscrepancy, PermuteIndexIsAPermutation) {
    for (uint32_t n : {1u, 2u, 3u, 5u, 7u, 16u, 31u, 100u, 1000u, 4097u}) {
        for (uint64_t seed : {0ull, 1ull, 12345ull}) {
            std::vector<int> seen(n, 0);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t p = permute_index(i, n, seed);
                ASSERT_LT(p, n);
                ++seen[p];
            }
            for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "n=" << n;
        }
    }
    // Different seeds give different permutations (a random pair of 1000-permutations agrees in ≈1 place).
    int same = 0;
    for (uint32_t i = 0; i < 1000; ++i) same += permute_index(i, 1000, 1) == permute_index(i, 1000, 2);
    EXPECT_LT(same, 10);
}

TEST(LowDiscrepancy, OwenScrambleKeepsAlignedBlocks) {
    // Base-2 Owen scrambling maps each aligned block of 2^m words onto one aligned block, bijectively: both the
    // keyed scramble (Halton, Hammersley) and Burley's cheap one (Sobol).
    const std::function<uint32_t(uint32_t, uint32_t)> scramblers[] = {
        [](uint32_t v, uint32_t seed) { return owen_scramble_base2(v, uint64_t(seed)); },
        [](uint32_t v, uint32_t seed) { return owen_scramble_fast(v, seed); },
    };
    for (const auto& scramble : scramblers) {
        for (uint32_t seed : {3u, 77u, 0xdeadbeefu}) {
            for (int m = 0; m <= 10; ++m) {
                const uint32_t n = 1u << m;
                std::set<uint32_t> values;
                const uint32_t block = scramble(0, seed) >> m;
                for (uint32_t i = 0; i < n; ++i) {
                    const uint32_t v = scramble(i, seed);
                    ASSERT_EQ(v >> m, block);
                    values.insert(v);
                }
                ASSERT_EQ(values.size(), n);
            }
        }
    }
}

TEST(LowDiscrepancy, OwenRadicalInverseIsUniform) {
    // Over many seeds one scrambled value is uniform on [0, 1): 10 bins, χ² with 9 dof (p ≈ 1e-4 cut: 33.7).
    for (uint32_t base : {3u, 5u, 29u, 1619u}) {
        std::vector<int> bins(10, 0);
        const int n = 20000;
        for (int s = 0; s < n; ++s) {
            const double v = owen_radical_inverse(base, 7, uint64_t(s));
            ASSERT_GE(v, 0.0);
            ASSERT_LT(v, 1.0);
            ++bins[size_t(v * 10)];
        }
        double chi2 = 0;
        for (int c : bins) chi2 += (c - n / 10.0) * (c - n / 10.0) / (n / 10.0);
        EXPECT_LT(chi2, 33.7) << "base " << base;
    }
}

// ---- registry and dimensions ----

TEST(Sampler, RegistryNames) {
    EXPECT_EQ(sampler_names(), k_all);
    for (const auto& name : k_all) EXPECT_NO_THROW(make_sampler(name, 1, 16));
    EXPECT_THROW(make_sampler("NOPE", 0, 1), InvalidParameter);
}

TEST(Sampler, NamedDimensionsAreFixedIndices) {
    EXPECT_EQ(dimension_index(Dim::Filter, 7), 0u);
    EXPECT_EQ(dimension_index(Dim::Lens, 7), 2u);
    EXPECT_EQ(dimension_index(Dim::LightSelect, 0), 4u);
    EXPECT_EQ(dimension_index(Dim::Light, 0), 5u);
    EXPECT_EQ(dimension_index(Dim::Bsdf, 0), 7u);
    EXPECT_EQ(dimension_index(Dim::Roulette, 0), 9u);
    EXPECT_EQ(dimension_index(Dim::BsdfLobe, 0), 10u);
    EXPECT_EQ(dimension_index(Dim::LightSelect, 1), 11u);
    EXPECT_EQ(dimension_index(Dim::Roulette, 63), 9u + 7u * 63u);
}

// The sequential interface walks the same dimensions as the named one.
TEST(Sampler, SequentialMatchesNamedDimensions) {
    for (const auto& name : k_all) {
        Sampler s = make_sampler(name, 5, 64);
        start_pixel_sample(s, 10, 20, 33);
        for (int bounce = 0; bounce < 50; ++bounce) {
            const float a = get_1d(s);
            const Vec2 b = get_2d(s), c = get_2d(s);
            const float d = get_1d(s), e = get_1d(s);
            ASSERT_EQ(a, get_1d(s, Dim::LightSelect, bounce)) << name;
            ASSERT_EQ(b.x, get_2d(s, Dim::Light, bounce).x) << name;
            ASSERT_EQ(b.y, get_2d(s, Dim::Light, bounce).y) << name;
            ASSERT_EQ(c.x, get_2d(s, Dim::Bsdf, bounce).x) << name;
            ASSERT_EQ(c.y, get_2d(s, Dim::Bsdf, bounce).y) << name;
            ASSERT_EQ(d, get_1d(s, Dim::Roulette, bounce)) << name;
            ASSERT_EQ(e, get_1d(s, Dim::BsdfLobe, bounce)) << name;
        }
    }
}

// The same (pixel, index, dimension) gives the same value whatever was requested before.
TEST(Sampler, ValuesIndependentOfCallOrder) {
    for (const auto& name : k_all) {
        Sampler a = make_sampler(name, 9, 64), b = make_sampler(name, 9, 64);
        start_pixel_sample(a, 3, 4, 5);
        std::vector<float> ref;
        for (uint32_t d = 0; d < 300; ++d) ref.push_back(sample_1d_at(a, d));
        const Vec2 ref2 = get_2d(a, Dim::Bsdf, 6);
        // b: other pixels, other indices, dimensions in reverse order, sequential draws in between.
        start_pixel_sample(b, 7, 7, 0);
        get_1d(b);
        get_2d(b);
        start_pixel_sample(b, 3, 4, 6);
        get_2d(b, Dim::Bsdf, 6);
        start_pixel_sample(b, 3, 4, 5);
        get_2d(b);
        get_1d(b);
        for (int d = 299; d >= 0; --d) ASSERT_EQ(sample_1d_at(b, uint32_t(d)), ref[size_t(d)]) << name << " dim " << d;
        const Vec2 v = get_2d(b, Dim::Bsdf, 6);
        EXPECT_EQ(v.x, ref2.x) << name;
        EXPECT_EQ(v.y, ref2.y) << name;
        // A fresh sampler gives the same too.
        Sampler c = make_sampler(name, 9, 64);
        start_pixel_sample(c, 3, 4, 5);
        EXPECT_EQ(sample_1d_at(c, 42), ref[42]) << name;
    }
}

TEST(Sampler, ValuesInUnitInterval) {
    for (const auto& name : k_all) {
        for (int spp : {1, 7, 16, 64}) {
            Sampler s = make_sampler(name, 11, spp);
            for (uint32_t px = 0; px < 4; ++px)
                for (int i = 0; i < spp + 2; ++i) {  // includes indices ≥ N: the fallback
                    start_pixel_sample(s, px, 2 * px, uint32_t(i));
                    for (uint32_t d = 0; d < 420; d += 1) {
                        const float v = sample_1d_at(s, d);
                        const Vec2 w = sample_2d_at(s, d);
                        ASSERT_TRUE(v >= 0.f && v < 1.f) << name << " " << v;
                        ASSERT_TRUE(w.x >= 0.f && w.x < 1.f && w.y >= 0.f && w.y < 1.f) << name;
                    }
                }
        }
    }
}

// ---- stratification ----

std::vector<Vec2> pixel_points(const std::string& name, int n, uint32_t px, uint32_t py, Dim dim = Dim::Filter,
                               int bounce = 0, uint64_t seed = 1) {
    Sampler s = make_sampler(name, seed, n);
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i) {
        start_pixel_sample(s, px, py, uint32_t(i));
        pts.push_back(get_2d(s, dim, bounce));
    }
    return pts;
}

/// Every elementary interval 2^-i × 2^-(m−i) holds exactly one of the 2^m points.
::testing::AssertionResult elementary_intervals(const std::vector<Vec2>& pts, int m) {
    const uint32_t n = 1u << m;
    if (pts.size() != n) return ::testing::AssertionFailure() << "wrong count";
    for (int i = 0; i <= m; ++i) {
        const uint32_t nx = 1u << i, ny = 1u << (m - i);
        std::vector<int> count(n, 0);
        for (const Vec2& p : pts) {
            const uint32_t cx = uint32_t(p.x * nx), cy = uint32_t(p.y * ny);
            ++count[cy * nx + cx];
        }
        for (uint32_t c = 0; c < n; ++c)
            if (count[c] != 1) return ::testing::AssertionFailure() << "m=" << m << " shape " << nx << "x" << ny;
    }
    return ::testing::AssertionSuccess();
}

TEST(SamplerStrata, UnscrambledHammersleyElementaryIntervals) {
    for (int m = 2; m <= 10; ++m) {
        const uint32_t n = 1u << m;
        std::vector<Vec2> pts;
        for (uint32_t i = 0; i < n; ++i) pts.push_back({float(hammersley(0, i, n)), float(hammersley(1, i, n))});
        EXPECT_TRUE(elementary_intervals(pts, m));
    }
}

TEST(SamplerStrata, ScrambledNetsElementaryIntervals) {
    for (const char* name : {"HAMMERSLEY", "SOBOL"}) {
        for (int m = 2; m <= 10; ++m) {
            for (uint32_t px = 0; px < 3; ++px) {
                EXPECT_TRUE(elementary_intervals(pixel_points(name, 1 << m, px, 5), m)) << name;
            }
        }
    }
    // Sobol: every 2-D request is a (0,2)-sequence, not only the pixel dimension.
    for (int m = 2; m <= 10; ++m) {
        EXPECT_TRUE(elementary_intervals(pixel_points("SOBOL", 1 << m, 4, 4, Dim::Light, 3), m));
        EXPECT_TRUE(elementary_intervals(pixel_points("SOBOL", 1 << m, 4, 4, Dim::Bsdf, 60), m));
    }
}

TEST(SamplerStrata, StratifiedOneSamplePerStratum) {
    for (int n : {1, 4, 8, 9, 16, 32, 64, 100, 128, 256, 1024}) {
        const StratifiedSampler probe(1, n);
        const uint32_t nx = probe.grid_x(), ny = probe.grid_y();
        ASSERT_EQ(int(nx * ny), n) << "an exact, at most 2:1 grid exists for " << n;
        ASSERT_LE(ny, 2 * nx);
        for (auto [dim, bounce] : {std::pair{Dim::Filter, 0}, {Dim::Light, 0}, {Dim::Bsdf, 9}}) {
            const auto pts = pixel_points("STRATIFIED", n, 2, 3, dim, bounce);
            std::vector<int> count(size_t(n), 0);
            for (const Vec2& p : pts) ++count[uint32_t(p.y * ny) * nx + uint32_t(p.x * nx)];
            for (int c : count) ASSERT_EQ(c, 1) << "n=" << n;
        }
        // 1-D dimensions: one sample per 1/N stratum.
        Sampler s = make_sampler("STRATIFIED", 1, n);
        for (auto [dim, bounce] : {std::pair{Dim::LightSelect, 0}, {Dim::Roulette, 20}}) {
            std::vector<int> count(size_t(n), 0);
            for (int i = 0; i < n; ++i) {
                start_pixel_sample(s, 2, 3, uint32_t(i));
                ++count[size_t(get_1d(s, dim, bounce) * n)];
            }
            for (int c : count) ASSERT_EQ(c, 1) << "n=" << n;
        }
    }
    // N without an at most 2:1 factorisation: the ⌊√N⌋ × ⌊N/⌊√N⌋⌋ grid holds the first samples, one per stratum.
    const StratifiedSampler odd(1, 17);
    EXPECT_EQ(odd.grid_x(), 4u);
    EXPECT_EQ(odd.grid_y(), 4u);
}

TEST(SamplerStrata, NRooksOnePerRowAndColumn) {
    for (int n : {4, 7, 16, 50, 256, 1024}) {
        for (auto [dim, bounce] : {std::pair{Dim::Filter, 0}, {Dim::Bsdf, 5}}) {
            const auto pts = pixel_points("NROOKS", n, 1, 1, dim, bounce);
            std::vector<int> rows(size_t(n), 0), cols(size_t(n), 0);
            for (const Vec2& p : pts) {
                ++cols[size_t(p.x * n)];
                ++rows[size_t(p.y * n)];
            }
            for (int i = 0; i < n; ++i) {
                ASSERT_EQ(rows[size_t(i)], 1) << n;
                ASSERT_EQ(cols[size_t(i)], 1) << n;
            }
        }
    }
}

TEST(SamplerStrata, HaltonPixelDimensionStratifiesBase2And3) {
    // Owen-scrambled Halton: for N = 2^a·3^b the (base 2, base 3) pixel point set has one point in each
    // 2^-a × 3^-b box (scrambling permutes digits within each prefix).
    const int n = 72;  // 2^3 · 3^2
    const auto pts = pixel_points("HALTON", n, 6, 2);
    std::vector<int> count(size_t(n), 0);
    for (const Vec2& p : pts) ++count[size_t(uint32_t(p.y * 9) * 8 + uint32_t(p.x * 8))];
    for (int c : count) EXPECT_EQ(c, 1);
}

// ---- decorrelation ----

TEST(SamplerDecorrelation, NeighbouringPixelsDiffer) {
    for (const auto& name : k_qmc) {
        Sampler s = make_sampler(name, 3, 64);
        std::set<std::pair<float, float>> firsts;
        int equal_neighbours = 0;
        Vec2 prev{-1.f, -1.f};
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                start_pixel_sample(s, x, y, 0);
                const Vec2 p = get_pixel_2d(s);
                firsts.insert({p.x, p.y});
                equal_neighbours += (p.x == prev.x) || (p.y == prev.y);
                prev = p;
            }
        EXPECT_EQ(firsts.size(), 64u) << name << ": first samples repeat across pixels";
        EXPECT_EQ(equal_neighbours, 0) << name;
        // The first samples of 1024 pixels are uniform over the pixel: 4×4 bins, χ² with 15 dof (cut 37.7,
        // p ≈ 1e-3).
        std::vector<int> bins(16, 0);
        for (uint32_t p = 0; p < 1024; ++p) {
            start_pixel_sample(s, p % 32, p / 32 + 100, 0);
            const Vec2 v = get_pixel_2d(s);
            ++bins[size_t(uint32_t(v.y * 4) * 4 + uint32_t(v.x * 4))];
        }
        double chi2 = 0;
        for (int c : bins) chi2 += (c - 64.0) * (c - 64.0) / 64.0;
        EXPECT_LT(chi2, 37.7) << name;
    }
}

/// Pearson correlation of two coordinates over the samples of many pixels.
double correlation(const std::string& name, int n, uint32_t dim_a, uint32_t dim_b, int pixels) {
    Sampler s = make_sampler(name, 21, n);
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int count = 0;
    for (int p = 0; p < pixels; ++p)
        for (int i = 0; i < n; ++i) {
            start_pixel_sample(s, uint32_t(p), 1, uint32_t(i));
            const double a = sample_1d_at(s, dim_a), b = sample_1d_at(s, dim_b);
            sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
            ++count;
        }
    const double ma = sa / count, mb = sb / count;
    return (sab / count - ma * mb) / std::sqrt((saa / count - ma * ma) * (sbb / count - mb * mb));
}

TEST(SamplerDecorrelation, DimensionsDoNotCorrelate) {
    // Independent coordinates: r ~ N(0, 1/√count); 5σ bound.
    const int n = 64, pixels = 64;
    const double bound = 5.0 / std::sqrt(double(n * pixels));
    const std::pair<Dim, Dim> pairs[] = {{Dim::LightSelect, Dim::Roulette},
                                         {Dim::Light, Dim::Bsdf},
                                         {Dim::Filter, Dim::Light},
                                         {Dim::Filter, Dim::Bsdf}};
    for (const auto& name : k_all) {
        for (auto [a, b] : pairs) {
            for (int bounce : {0, 3, 60}) {  // bounce 60: past the radical-inverse dimensions
                const double r = correlation(name, n, dimension_index(a, bounce), dimension_index(b, bounce), pixels);
                EXPECT_LT(std::fabs(r), bound)
                    << name << " dims " << dimension_index(a, bounce) << "," << dimension_index(b, bounce);
            }
        }
        // Same named dimension at consecutive bounces.
        const double r = correlation(name, n, dimension_index(Dim::Bsdf, 1), dimension_index(Dim::Bsdf, 2), pixels);
        EXPECT_LT(std::fabs(r), bound) << name;
    }
}

}  // namespace
}  // namespace candela

namespace candela {

namespace {
/// Exposes the per-dimension seeds so the fast Sobol evaluation can be checked against its definition.
struct SobolProbe : SobolSampler {
    using SobolSampler::seeds;
    using SobolSampler::SobolSampler;
};
}  // namespace

TEST(SobolSampler, EqualsTheTextbookComposition) {
    // Burley 2020: the index shuffled by a base-2 Owen scramble, then each Sobol coordinate Owen-scrambled.
    SobolProbe s(7, 64);
    for (uint32_t index : {0u, 1u, 2u, 3u, 17u, 63u, 64u, 1000u, 123456u}) {
        s.start_pixel_sample(3, 5, index);
        for (uint32_t dim : {0u, 2u, 4u, 5u, 7u, 100u}) {
            const auto seeds = s.seeds(dim);
            const uint32_t i = owen_scramble_fast(index, seeds.shuffle);
            const float x = fixed_to_float(owen_scramble_fast(sobol_dim0(i), seeds.first));
            const float y = fixed_to_float(owen_scramble_fast(sobol_dim1(i), seeds.second));
            EXPECT_EQ(s.sample_1d(dim), x) << index << "/" << dim;
            const Vec2 v = s.sample_2d(dim);
            EXPECT_EQ(v.x, x) << index << "/" << dim;
            EXPECT_EQ(v.y, y) << index << "/" << dim;
        }
    }
}

}  // namespace candela

namespace candela {

TEST(SobolSampler, EightLaneBatchEqualsOneLaneAtATime) {
    // The batch (sampling/sobol_x8.h: SIMD with AVX2, else the split scalar form with precomputed seed
    // multiples) must reproduce its one-lane definition bit for bit: any lane mix-up, wrong constant, shift or
    // mis-split hash step shows as a mismatch on some of these random inputs.
    Pcg32 rng(5, 9);
    for (int trial = 0; trial < 20000; ++trial) {
        uint32_t dims[8];
        for (uint32_t& d : dims) d = rng.next_u32() % 600u;
        const uint32_t seed = rng.next_u32(), index = rng.next_u32(), y_lanes = rng.next_u32() & 0xffu;
        float simd[8], scalar[8];
        sobol_x8(seed, index, dims, y_lanes, simd);
        sobol_x8_scalar(seed, index, dims, y_lanes, scalar);
        for (int k = 0; k < 8; ++k) ASSERT_EQ(simd[k], scalar[k]) << "trial " << trial << " lane " << k;
    }
}

TEST(SobolSampler, BounceBatchEqualsTheNamedDraws) {
    SobolSampler s(11, 64);
    for (uint32_t index : {0u, 1u, 5u, 63u, 200u}) {
        s.start_pixel_sample(17, 4, index);
        for (int bounce : {0, 1, 7, 40}) {
            const BounceSample b = s.sample_bounce(bounce);
            EXPECT_EQ(b.light_select, get_1d(s, Dim::LightSelect, bounce));
            EXPECT_EQ(b.light.x, get_2d(s, Dim::Light, bounce).x);
            EXPECT_EQ(b.light.y, get_2d(s, Dim::Light, bounce).y);
            EXPECT_EQ(b.bsdf.x, get_2d(s, Dim::Bsdf, bounce).x);
            EXPECT_EQ(b.bsdf.y, get_2d(s, Dim::Bsdf, bounce).y);
            EXPECT_EQ(b.roulette, get_1d(s, Dim::Roulette, bounce));
            EXPECT_EQ(b.lobe, get_1d(s, Dim::BsdfLobe, bounce));
        }
    }
}

TEST(SobolSampler, CachedBounceSeedsEqualTheUncachedBatch) {
    // sample_bounce caches the seeds of the first k_cached_bounces bounces per pixel run, sample_2d those of the
    // Filter request. Visit pixels the way
    // the tile renderer does (runs of a pixel's samples, interleaved samplers, a return to an earlier pixel)
    // and bounces out of order, below and beyond the cached range: every batch must equal the batch with seeds
    // computed on the spot, and the named one-at-a-time draws. A cache not reset on a pixel change, a wrong slot or a
    // stale bit shows as a mismatch.
    constexpr int k_deep = SobolSampler::k_cached_bounces + 3;
    struct Visit {
        uint32_t px, py, index;
    };
    const Visit visits[] = {{3, 4, 0}, {3, 4, 1}, {3, 4, 2}, {9, 4, 0}, {9, 4, 5}, {3, 4, 3}, {3, 5, 0}, {3, 5, 1}};
    const int bounce_order[] = {0, 1, 2, 5, 3, k_deep - 1, 4, 7, 6, 2, 0, SobolSampler::k_cached_bounces, 1, 60, 7};
    SobolProbe cached(23, 64);
    for (const Visit& v : visits) {
        cached.start_pixel_sample(v.px, v.py, v.index);
        SobolSampler fresh(23, 64);
        fresh.start_pixel_sample(v.px, v.py, v.index);
        // The Filter request's seeds are kept per pixel run too.
        const auto seeds = cached.seeds(dimension_index(Dim::Filter));
        const uint32_t i = owen_scramble_fast(v.index, seeds.shuffle);
        const Vec2 filter = cached.sample_2d(dimension_index(Dim::Filter));
        ASSERT_EQ(filter.x, fixed_to_float(owen_scramble_fast(sobol_dim0(i), seeds.first))) << v.px << "," << v.py;
        ASSERT_EQ(filter.y, fixed_to_float(owen_scramble_fast(sobol_dim1(i), seeds.second))) << v.px << "," << v.py;
        for (int bounce : bounce_order) {
            const BounceSample a = cached.sample_bounce(bounce), b = fresh.sample_bounce_uncached(bounce);
            const float got[7] = {a.light_select, a.light.x, a.light.y, a.bsdf.x, a.bsdf.y, a.roulette, a.lobe};
            const float want[7] = {b.light_select, b.light.x, b.light.y, b.bsdf.x, b.bsdf.y, b.roulette, b.lobe};
            for (int k = 0; k < 7; ++k)
                ASSERT_EQ(got[k], want[k]) << "pixel " << v.px << "," << v.py << " index " << v.index << " bounce "
                                           << bounce << " value " << k;
            ASSERT_EQ(a.bsdf.y, get_2d(fresh, Dim::Bsdf, bounce).y);
            ASSERT_EQ(a.lobe, get_1d(fresh, Dim::BsdfLobe, bounce));
        }
    }
    // A copy carries its cache along: still correct for its pixel, and after moving to another pixel.
    SobolSampler copy = cached;  // (slices the probe: the sampler part is what is copied)
    SobolSampler fresh(23, 64);
    for (const Visit& v : {Visit{3, 5, 2}, Visit{40, 41, 0}}) {
        copy.start_pixel_sample(v.px, v.py, v.index);
        fresh.start_pixel_sample(v.px, v.py, v.index);
        for (int bounce = 0; bounce < k_deep; ++bounce) {
            ASSERT_EQ(copy.sample_bounce(bounce).bsdf.x, fresh.sample_bounce_uncached(bounce).bsdf.x) << bounce;
            ASSERT_EQ(copy.sample_bounce(bounce).light.y, get_2d(fresh, Dim::Light, bounce).y) << bounce;
        }
    }
}

}  // namespace candela
