// Every unbiased configuration of the sampling toolbox converges to the analytic answer (docs/verification.md
// §1, §7), as the cross product of its axes:
//   sampler (6) × light_sampling (3) × light_pdf (2) × light_selection (6) × rr_mode (THROUGHPUT, ALBEDO)
// on two closed furnaces seen from inside (albedo 0.5, expected 1):
//   EmissiveSphere: a coarse closed 8 × 4 UV sphere whose 48 facets all emit Le = 0.5 (L = Le/(1 − ρ)
//     holds for any closed shape): large emitters, so light selection, spherical-triangle vs area pdfs and
//     MIS all matter, and few enough that ALL (a shadow ray per emitter) and WARD stay affordable;
//   FourPointLights: four coincident point lights of unequal intensity (π·0.1 … π·0.4) at the centre of a
//     128 × 64 UV sphere (pbrt S1/S2): the selection pmfs of delta lights.
// plus branching_factor 4 × sampler × light_sampling × rr_mode, and hemisphere sampling × MIS heuristic at
// branching factors 1 and 4. OFF roulette truncates (biased by design) and is not part of the matrix.
//
// Why a sphere and not the 12-triangle cube of docs/verification.md §1.4: seen from a point near a concave edge,
// area sampling of the adjacent face has an unbounded geometry term (G ∝ sin²φ·ab/d⁴ for dihedral angle φ), so
// LIGHT_ONLY + AREA has infinite variance there (see heavy_tailed below). The tail's constant scales with sin⁴ of
// the angle between neighbouring facets: 1 for the cube, 0.25 for the 8 × 4 sphere; every other strategy is
// bounded.
//
// Each scene is built once (PreparedScene) and rendered with every setting; every render gets its own seed
// so that the renders are independent.
//
// Tolerances (statistical): each render's mean over its 8 × 8 pixels has a standard error σ estimated from
// the film's noise estimate (the spread between each pixel's two independent replicates: one degree of freedom
// per pixel, 64 in all; honest for QMC samplers too). One render fails if |mean − expected| > 5σ + b, where b is
// the geometric bias of the faceted sphere (furnace_facet_bias: 0 for the emissive furnace, exact for any closed
// shape; 5·10⁻⁴ for the 128 × 64 sphere around the point lights, doubled as a bound for the pixels' view of
// it). σ being estimated, the deviation over σ follows Student's t with 64 degrees of freedom, whose tail is
// heavier than the normal's: P(|t₆₄| > 5) ≈ 5·10⁻⁶, so with ~960 renders the chance that a correct estimator
// fails somewhere is ≈ 5·10⁻³. (A 4 × 4 image with 16 degrees of freedom gave P(|t₁₆| > 5) ≈ 1.3·10⁻⁴, a 12 %
// false-alarm rate over the matrix, and σ estimates scattered by ±18 %.)
// Each render must also be precise enough for the check to mean something: 5σ < 0.04 (largest measured 0.033–0.036;
// the point lights get 1.4× the samples to stay there;
// pbrt's analytic tests use 0.02). Pooled checks are where the power is: for every value of every axis (e.g.
// light_pdf = AREA) and every pair of values of two axes (e.g. light_pdf = AREA with light_selection = TREE),
// the mean deviation of all renders using it must be within 5 pooled σ (σ_pool = √Σσ²/n). With 12–216 renders
// per pool that resolves biases of 0.1–0.5 %, which no single render could; ~300 pools keep the chance of a
// false alarm near 2·10⁻⁴.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "lights/light_sampler.h"
#include "sampling/sampler.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

constexpr int k_max_bounces = 30;  // truncation 2^-31: negligible (furnace_expected includes it anyway)
constexpr double k_z = 5.0;
constexpr double k_precision = 0.04;  // largest acceptable 5σ of one render
constexpr int k_samples = 80;         // per pixel, 8 × 8 pixels

using Setting = std::vector<std::pair<std::string, std::string>>;  // (param, value) pairs

class Matrix {
public:
    Matrix(FurnaceScene kind, int samples)
        : m_kind(kind),
          m_samples(samples),
          m_scene(kind == FurnaceScene::EmissiveSphere ? furnace_scene(kind, 8, 4) : furnace_scene(kind, 128, 64),
                  base_params()) {
        m_expected = furnace_expected(kind, k_max_bounces);
        m_bias = kind == FurnaceScene::EmissiveSphere ? 0.0 : 2.0 * std::fabs(furnace_facet_bias(128, 64));
    }

    /// One render; `samples` overrides the matrix's sample count when > 0.
    void run(const Setting& setting, int branching = 1, int samples = 0) {
        Params p;
        p.set("samples", int64_t(samples > 0 ? samples : m_samples));
        p.set("seed", int64_t(++m_renders));
        p.set("branching_factor", int64_t(branching));
        std::string what = name() + ":";
        for (const auto& [key, value] : setting) {
            // Numbers (rr_start_bounce) are integer parameters; everything else is an enum name.
            const bool integer = !value.empty() && value.find_first_not_of("0123456789") == std::string::npos;
            if (integer)
                p.set(key, int64_t(std::stoll(value)));
            else
                p.set(key, value);
            what += " " + key + "=" + value;
        }
        if (branching != 1) what += " branching_factor=" + std::to_string(branching);
        const RenderResult r = m_scene.render(p);
        const double deviation = r.mean_rgb - m_expected, se = r.standard_error;
        if (!heavy_tailed(setting)) {
            EXPECT_LT(k_z * se, k_precision) << what << ": too few samples for a meaningful tolerance";
            m_max_tolerance = std::max(m_max_tolerance, k_z * se);
        }
        EXPECT_LT(std::fabs(deviation), k_z * se + m_bias)
            << what << ": mean " << r.mean_rgb << ", expected " << m_expected << ", σ " << se;
        // Pools: every axis value, and every pair of values of two axes (interactions).
        for (size_t i = 0; i < setting.size(); ++i) {
            add_to_pool(setting[i].first + "=" + setting[i].second, deviation, se);
            for (size_t j = i + 1; j < setting.size(); ++j)
                add_to_pool(
                    setting[i].first + "=" + setting[i].second + " " + setting[j].first + "=" + setting[j].second,
                    deviation, se);
        }
    }

    /// Samples for light_selection = ALL with light sampling: its cost grows with the emitter count, its
    /// variance is the lowest.
    int all_samples() const { return m_kind == FurnaceScene::EmissiveSphere ? m_samples / 2 : m_samples; }

    /// The pooled check over every axis value and pair of values seen so far.
    void check_pools() {
        ::testing::Test::RecordProperty(name() + " renders", m_renders);
        ::testing::Test::RecordProperty(name() + " largest 5 sigma", std::to_string(m_max_tolerance));
        for (const auto& [value, pool] : m_pools) {
            const double mean = pool.deviation / pool.n, se = std::sqrt(pool.variance) / pool.n;
            EXPECT_LT(std::fabs(mean), k_z * se + m_bias) << name() << ", all " << pool.n << " renders with " << value
                                                          << ": mean deviation " << mean << ", pooled σ " << se;
        }
    }

private:
    struct Pool {
        double deviation = 0.0, variance = 0.0;
        int n = 0;
    };
    void add_to_pool(const std::string& key, double deviation, double se) {
        Pool& pool = m_pools[key];
        pool.deviation += deviation;
        pool.variance += se * se;
        ++pool.n;
    }
    /// LIGHT_ONLY with AREA sampling of the faceted emissive sphere: a shading point near the edge shared by
    /// two facets, sampling the neighbouring facet by area, sees a geometry term ∝ 1/d² that is not square
    /// integrable, so the estimator has infinite variance (tail P(F > t) ∝ t^(−3/2)): its σ estimate cannot
    /// promise a precision. The deviation check still applies (the self-normalised deviation stays well
    /// behaved for such tails), and so do the pools.
    bool heavy_tailed(const Setting& setting) const {
        auto value = [&](const char* key) {
            for (const auto& [k, v] : setting)
                if (k == key) return v;
            return std::string();
        };
        return m_kind == FurnaceScene::EmissiveSphere && value("light_sampling") == "LIGHT_ONLY" &&
               value("light_pdf") == "AREA";
    }
    static Params base_params() {
        Params p = basic_params(8, 8, 1, k_max_bounces);
        p.set("tile_size", int64_t(4));  // four tiles: both cores work on an 8 × 8 image
        return p;
    }
    std::string name() const {
        return m_kind == FurnaceScene::EmissiveSphere ? "emissive sphere furnace" : "four point lights in a sphere";
    }

    FurnaceScene m_kind;
    int m_samples;
    PreparedScene m_scene;
    double m_expected = 1.0, m_bias = 0.0;
    int m_renders = 0;
    double m_max_tolerance = 0.0;
    std::map<std::string, Pool> m_pools;
};

void cross_product(Matrix& m) {
    for (const auto& sampler : sampler_names())
        for (const char* ls : {"BSDF_ONLY", "LIGHT_ONLY", "MIS"})
            for (const char* pdf : {"AREA", "SOLID_ANGLE"})
                for (const auto& sel : light_selection_names())
                    for (const char* rr : {"THROUGHPUT", "ALBEDO"})
                        // ALL casts a shadow ray per emitter per vertex (48 on the emissive sphere): fewer
                        // samples, but it also has the lowest variance per sample.
                        m.run({{"sampler", sampler},
                               {"light_sampling", ls},
                               {"light_pdf", pdf},
                               {"light_selection", sel},
                               {"rr_mode", rr}},
                              1, sel == "ALL" && std::string(ls) != "BSDF_ONLY" ? m.all_samples() : 0);
    m.check_pools();
}

TEST(EstimatorMatrix, EmissiveSphereEveryCombinationConvergesToOne) {
    Matrix m(FurnaceScene::EmissiveSphere, k_samples);
    cross_product(m);
}

TEST(EstimatorMatrix, FourPointLightsEveryCombinationConvergesToOne) {
    Matrix m(FurnaceScene::FourPointLights, k_samples * 7 / 5);
    cross_product(m);
}

// Branching at the first surface (stochastic ray tracing): 4 continuation rays, with every sampler (the
// branches draw their own sample dimensions), light-sampling strategy and roulette mode.
// SQRT_THROUGHPUT (Cycles' rule, decided on arrival at a vertex) is tested here and in
// CyclesRouletteConvergesToOne rather than in the full cross product: it changes nothing that light selection
// or the light pdf interact with.
TEST(EstimatorMatrix, BranchingFactorFourConvergesToOne) {
    for (FurnaceScene kind : {FurnaceScene::EmissiveSphere, FurnaceScene::FourPointLights}) {
        Matrix m(kind, k_samples);
        for (const auto& sampler : sampler_names())
            for (const char* ls : {"BSDF_ONLY", "LIGHT_ONLY", "MIS"})
                for (const char* rr : {"THROUGHPUT", "ALBEDO", "SQRT_THROUGHPUT"})
                    m.run({{"sampler", sampler}, {"light_sampling", ls}, {"rr_mode", rr}}, 4);
        m.check_pools();
    }
}

// Cycles' roulette, with every sampler, light-sampling strategy and roulette start (from the first vertex on,
// and the default, the third), without branching.
TEST(EstimatorMatrix, CyclesRouletteConvergesToOne) {
    for (FurnaceScene kind : {FurnaceScene::EmissiveSphere, FurnaceScene::FourPointLights}) {
        Matrix m(kind, k_samples);
        for (const auto& sampler : sampler_names())
            for (const char* ls : {"BSDF_ONLY", "LIGHT_ONLY", "MIS"})
                for (const char* start : {"1", "3"})
                    m.run({{"sampler", sampler},
                           {"light_sampling", ls},
                           {"rr_mode", "SQRT_THROUGHPUT"},
                           {"rr_start_bounce", start}});
        m.check_pools();
    }
}

// Continuation directions drawn uniformly, by cosine or by the BSDF, with both MIS heuristics, at branching
// factors 1 and 4.
TEST(EstimatorMatrix, HemisphereSamplingAndHeuristicVariants) {
    for (FurnaceScene kind : {FurnaceScene::EmissiveSphere, FurnaceScene::FourPointLights}) {
        Matrix m(kind, k_samples);
        for (int branching : {1, 4})
            for (const char* hemisphere : {"UNIFORM", "COSINE", "BSDF"})
                for (const char* heuristic : {"BALANCE", "POWER"})
                    m.run({{"hemisphere_sampling", hemisphere}, {"mis_heuristic", heuristic}}, branching);
        m.check_pools();
    }
}

}  // namespace
}  // namespace candela::test
