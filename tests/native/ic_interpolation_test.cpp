// The gather and the interpolation against closed forms (docs/irradiance_cache.md, "How it is tested"): a receiver
// in the analytic room of ic_analytic.h, lit by a disk, a rectangle or a triangle emitter that only gather rays
// reach (no next-event estimation: the irradiance is the gathers' alone).
//   - The gather's irradiance is unbiased: the mean of 128 independent gathers equals the closed form within 4σ, σ
//     from their spread (a false alarm about 10⁻⁴ per point, 15 points), and 4σ resolves 5 % of it.
//   - The rotational gradient equals the derivative of the closed form with the normal within 4σ plus the bound of
//     its one approximation (L constant over a cell: at most ∫ sin θ dω over the cells the emitter's outline crosses).
//     The translational gradient (Ward & Heckbert's boundary-sweep estimate, no such bound) points the way the
//     closed form's does, at most a factor 1.25 off in length: what a sign or a missing factor would break.
//   - Interpolation: records are placed over the floor by the cache's own rule (a record wherever none is usable,
//     in raster order over a fine grid), from gathers, with their irradiance replaced by the exact value so that
//     what is left is the interpolation's own error (and that of the gradients and R the gathers estimated). At
//     random points between records the error falls as a shrinks — significantly (z > 4 between successive a, with
//     the standard error of each mean square from its i.i.d. query points) and at least at the rate the error
//     model gives with margin: the error of an interpolation without gradients is first order in the distance to
//     the records (∝ a: rms ∝ a¹, tested ≥ a^0.7), with exact gradients second order (∝ a², tested ≥ a^1.5). On the
//     same record sets the gradients lower the error for a ≤ 0.1 (paired per point, z > 4); at a = 0.2 and above
//     records reach so far (a·R ~ R/5) that the linear extrapolation is no better than none: docs/irradiance_cache.md
//     gives the measured table.
//   - The record count grows as 1/a²: the validity radius is a·R, so records cover area ∝ a²; with a boundary
//     term ∝ perimeter/(a·R) the local exponent of count(a) is −2 + O(a). Fitted over a = 0.2 … 0.05 on a grid ten
//     times finer than the smallest radius it must lie in [−2.2, −1.7] (the measured value is in the docs).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/math.h"
#include "ic_analytic.h"
#include "integrators/irradiance_cache/ic_cache.h"

namespace candela::test {
namespace {

const Vec3 k_up(0.f, 0.f, 1.f);
constexpr RoomEmitter k_emitters[] = {RoomEmitter::Disk, RoomEmitter::Rectangle, RoomEmitter::Triangle};

struct MeanSd {
    double mean = 0.0, se = 0.0;  // the mean and its standard error
};
MeanSd mean_se(const std::vector<double>& v) {
    double m = 0.0;
    for (double x : v) m += x;
    m /= double(v.size());
    double s2 = 0.0;
    for (double x : v) s2 += (x - m) * (x - m);
    return {m, std::sqrt(s2 / double(v.size() - 1) / double(v.size()))};
}

TEST(IcGather, IrradianceIsUnbiased) {
    const GatherStrata strata = GatherStrata::for_rays(1024);
    const Frame frame(k_up);
    Pcg32 rng(3, 4);
    for (RoomEmitter e : k_emitters) {
        const AnalyticRoom room{e};
        const AnalyticField field = room.field();
        for (const Vec3 x : {Vec3(0.f, 0.f, 0.f), Vec3(0.6f, -0.3f, 0.f), Vec3(-0.8f, 0.7f, 0.f), Vec3(0.2f, 0.9f, 0.f),
                             Vec3(0.9f, -0.9f, 0.f)}) {
            std::vector<double> E;
            for (int k = 0; k < 128; ++k)
                E.push_back(estimate_gather(analytic_gather(field, x, frame, strata, rng)).E.x);
            const MeanSd m = mean_se(E);
            const double exact = room.exact(x);
            EXPECT_GT(m.se, 0.0);
            EXPECT_LT(std::fabs(m.mean - exact), 4.0 * m.se) << "emitter " << int(e) << " at " << x.x << ", " << x.y;
            EXPECT_LT(4.0 * m.se, 0.05 * exact);  // precise enough to mean something
        }
    }
}

/// Σ over the cells the emitter's outline crosses of ∫_cell sin θ dω: the most the cell-constant rotational
/// gradient can be off by (L ∈ [0, 1]). A cell is crossed when an 8 × 8 grid of directions in it sees both values.
double rotational_cell_bound(const AnalyticField& field, const Vec3& x, const Frame& frame, const GatherStrata& s) {
    double bound = 0.0;
    const double dphi = 2.0 * k_pi / s.N;
    for (int j = 0; j < s.M; ++j) {
        const double t0 = std::asin(std::sqrt(double(j) / s.M)), t1 = std::asin(std::sqrt(double(j + 1) / s.M));
        const double polar = 0.5 * (t1 - t0) - 0.25 * (std::sin(2 * t1) - std::sin(2 * t0));
        for (int k = 0; k < s.N; ++k) {
            bool lit = false, dark = false;
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    const Vec3 w = gather_direction(s, j, k, (a + 0.5f) / 8.f, (b + 0.5f) / 8.f);
                    (field(x, frame.to_world(w)).L.x > 0.f ? lit : dark) = true;
                }
            if (lit && dark) bound += polar * dphi;
        }
    }
    return bound;
}

TEST(IcGather, GradientsAgreeWithTheClosedForm) {
    const GatherStrata strata = GatherStrata::for_rays(1024);
    const Frame frame(k_up);
    Pcg32 rng(5, 6);
    const float h = 1e-3f;
    for (RoomEmitter e : {RoomEmitter::Rectangle, RoomEmitter::Triangle}) {  // Lambert's formula tilts the normal
        const AnalyticRoom room{e};
        const AnalyticField field = room.field();
        const std::vector<Vec3> corners =
            e == RoomEmitter::Rectangle
                ? std::vector<Vec3>{{-0.3f, -0.2f, 1.2f}, {0.5f, -0.2f, 1.2f}, {0.5f, 0.4f, 1.2f}, {-0.3f, 0.4f, 1.2f}}
                : std::vector<Vec3>{{-0.4f, -0.3f, 1.2f}, {0.5f, -0.2f, 1.2f}, {0.1f, 0.6f, 1.2f}};
        for (const Vec3 x : {Vec3(0.7f, -0.5f, 0.f), Vec3(-0.6f, 0.4f, 0.f), Vec3(0.1f, 0.05f, 0.f)}) {
            std::vector<double> rot[2], tr[2];
            for (int k = 0; k < 48; ++k) {
                GatherEstimate g = estimate_gather(analytic_gather(field, x, frame, strata, rng));
                gradients_to_world(frame, g);
                for (int c = 0; c < 2; ++c) {
                    // Rotation about the world axis c (x or y): the change of E per radian is g_r·axis.
                    rot[c].push_back(c == 0 ? g.grad_r[0].x : g.grad_r[0].y);
                    tr[c].push_back(c == 0 ? g.grad_t[0].x : g.grad_t[0].y);
                }
            }
            const double bound = rotational_cell_bound(field, x, frame, strata);
            double fd_t[2];
            for (int c = 0; c < 2; ++c) {
                const Vec3 axis = c == 0 ? Vec3(1.f, 0.f, 0.f) : Vec3(0.f, 1.f, 0.f);
                // n rotated by ±h about the axis: n ± h (axis × n).
                const Vec3 t = cross(axis, k_up);
                const double fd_r = (polygon_irradiance(corners, x, normalize(k_up + t * h)) -
                                     polygon_irradiance(corners, x, normalize(k_up - t * h))) /
                                    (2.0 * h);
                const MeanSd m = mean_se(rot[c]);
                EXPECT_LT(std::fabs(m.mean - fd_r), 4.0 * m.se + bound)
                    << "emitter " << int(e) << " axis " << c << ": " << m.mean << " vs " << fd_r << " (bound " << bound
                    << ")";
                fd_t[c] = (polygon_irradiance(corners, x + axis * h, k_up) -
                           polygon_irradiance(corners, x - axis * h, k_up)) /
                          (2.0 * h);
            }
            const double est[2] = {mean_se(tr[0]).mean, mean_se(tr[1]).mean};
            const double dotp = est[0] * fd_t[0] + est[1] * fd_t[1];
            const double ne = std::hypot(est[0], est[1]), nf = std::hypot(fd_t[0], fd_t[1]);
            EXPECT_GT(dotp, 0.9 * ne * nf) << "translational gradient direction, emitter " << int(e);
            EXPECT_LT(std::fabs(std::log(ne / nf)), std::log(1.25)) << ne << " vs " << nf;
        }
    }
}

/// Records over the floor [−half, half]², by the cache's rule, in raster order over a grid of `n`² points; each
/// from a gather of `rays`, its irradiance replaced by the closed form where `exact_E`.
IcCache place_records(const AnalyticRoom& room, float a, float half, int n, int rays, bool exact_E, uint64_t seed) {
    IcCacheRules rules;
    rules.a = a;
    IcCache cache(SceneSphere{Vec3(0.f, 0.f, 0.6f), 3.f}, rules);
    RecordRules rr;
    rr.a = a;
    rr.max_R = 6.f;
    const GatherStrata strata = GatherStrata::for_rays(rays);
    const Frame frame(k_up);
    const AnalyticField field = room.field();
    Pcg32 rng(seed, 9);
    for (int iy = 0; iy <= n; ++iy)
        for (int ix = 0; ix <= n; ++ix) {
            const Vec3 x(-half + 2.f * half * ix / n, -half + 2.f * half * iy / n, 0.f);
            if (cache.covered(x, k_up)) continue;
            IcRecord r =
                record_from_gather(estimate_gather(analytic_gather(field, x, frame, strata, rng)), x, frame, rr);
            if (exact_E) r.E = Color(float(room.exact(x)));
            cache.insert(r);
        }
    return cache;
}

/// Squared relative errors of the interpolation at Q random points of [−0.5, 0.5]², with and without gradients.
struct Errors {
    std::vector<double> with, without;
};
Errors interpolation_errors(const AnalyticRoom& room, const IcCache& cache, int Q) {
    Errors out;
    Pcg32 q(99, 3);
    for (int i = 0; i < Q; ++i) {
        const Vec3 x(-0.5f + q.next_float(), -0.5f + q.next_float(), 0.f);
        const double exact = room.exact(x);
        Color g, ng;
        EXPECT_TRUE(cache.interpolate(x, k_up, true, &g));
        EXPECT_TRUE(cache.interpolate(x, k_up, false, &ng));
        out.with.push_back(sqr(float((g.x - exact) / exact)));
        out.without.push_back(sqr(float((ng.x - exact) / exact)));
    }
    return out;
}

TEST(IcInterpolation, ConvergesAsTheErrorShrinksAndGradientsLowerIt) {
    const float as[] = {0.4f, 0.2f, 0.1f, 0.05f, 0.025f};
    for (RoomEmitter e : k_emitters) {
        const AnalyticRoom room{e};
        std::vector<MeanSd> with, without;
        for (float a : as) {
            const IcCache cache = place_records(room, a, 0.6f, 240, 1024, true, 17);
            const Errors err = interpolation_errors(room, cache, 1500);
            with.push_back(mean_se(err.with));
            without.push_back(mean_se(err.without));
            if (a <= 0.1f) {
                std::vector<double> diff;
                for (size_t i = 0; i < err.with.size(); ++i) diff.push_back(err.without[i] - err.with[i]);
                const MeanSd d = mean_se(diff);
                EXPECT_GT(d.mean, 4.0 * d.se)
                    << "gradients do not lower the error at a = " << a << ", emitter " << int(e);
            }
        }
        for (size_t k = 0; k + 1 < with.size(); ++k) {
            for (const auto* m : {&with, &without}) {
                const MeanSd& big = (*m)[k];
                const MeanSd& small = (*m)[k + 1];
                EXPECT_GT(big.mean - small.mean, 4.0 * std::hypot(big.se, small.se))
                    << (m == &with ? "with" : "without") << " gradients, a = " << as[k + 1] << ", emitter " << int(e);
            }
        }
        // The rates over a = 0.1 … 0.025 (rms ∝ a^p: p = ½ log2 of the mean-square ratio per halving).
        const double p_with = 0.5 * std::log2(with[2].mean / with[4].mean) / 2.0;
        const double p_without = 0.5 * std::log2(without[2].mean / without[4].mean) / 2.0;
        EXPECT_GT(p_with, 1.5) << "emitter " << int(e);
        EXPECT_GT(p_without, 0.7) << "emitter " << int(e);
        std::printf("emitter %d: rms error at a = 0.4 … 0.025 with gradients", int(e));
        for (const MeanSd& m : with) std::printf(" %.2e", std::sqrt(m.mean));
        std::printf(" (rate %.2f), without", p_with);
        for (const MeanSd& m : without) std::printf(" %.2e", std::sqrt(m.mean));
        std::printf(" (rate %.2f)\n", p_without);
    }
}

TEST(IcInterpolation, RecordCountGrowsAsOneOverASquared) {
    const AnalyticRoom room{RoomEmitter::Rectangle};
    const float as[] = {0.2f, 0.1f, 0.05f};
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::printf("records:");
    for (float a : as) {
        // The smallest validity radius here is about 0.05·0.5: a grid of 0.0025.
        const IcCache cache = place_records(room, a, 0.6f, 480, 256, false, 23);
        const double x = std::log(a), y = std::log(double(cache.size()));
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        std::printf(" a = %.3f: %zu", a, cache.size());
    }
    const double n = 3.0, slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    std::printf("; exponent %.2f\n", slope);
    EXPECT_GT(slope, -2.2);
    EXPECT_LT(slope, -1.7);
}

}  // namespace
}  // namespace candela::test
