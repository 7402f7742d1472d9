#include "integrators/photon_map/sppm_gather.h"

#include <algorithm>

#include "core/parallel.h"
#include "core/parallel_ordered.h"
#include "integrators/common/fixed_view_bsdf.h"
#include "integrators/photon_map/visible_point_grid.h"
#include "scene/shutter_time.h"

namespace candela {

namespace {

/// The points with their radii and side normals (a surface that does not transmit: ng on w_o's side).
VisiblePointGrid grid_of(const std::vector<VisiblePoint>& points, const std::vector<float>& radii) {
    std::vector<GridPoint> g(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const VisiblePoint& vp = points[i];
        if (!vp.valid) continue;
        g[i].p = vp.hit.p;
        g[i].radius2 = radii[i] * radii[i];
        if (!vp.transmits) g[i].normal = dot(vp.wo, vp.hit.ng) < 0.f ? -vp.hit.ng : vp.hit.ng;
    }
    VisiblePointGrid grid;
    grid.build(g);
    return grid;
}

/// The photons each point accepts: photons_of[start[i] .. start[i + 1]) for point i, in photon order.
struct Gathered {
    std::vector<uint32_t> start, photons_of;
};

/// The pairs of photon batches [b0, b1).
Gathered gather(const VisiblePointGrid& grid, size_t points, const std::vector<Photon>& photons, size_t b0, size_t b1,
                RenderContext& ctx) {
    struct Pair {
        uint32_t point, photon;
    };
    struct Batch {
        std::vector<Pair> pairs;
    };
    // The consumer counts each batch's pairs per point while later batches are still being gathered, and keeps
    // the batches (moved, in order) for the fill.
    Gathered g;
    g.start.assign(points + 1, 0u);
    std::vector<Batch> kept(b1 - b0);
    parallel_ordered(
        ctx.threads, b1 - b0, size_t(2 * resolve_thread_count(ctx.threads)),
        [&](size_t k) {
            Batch out;
            const size_t b = b0 + k, end = std::min(photons.size(), (b + 1) * k_gather_batch);
            for (size_t j = b * k_gather_batch; j < end; ++j) {
                const Photon& ph = photons[j];
                grid.query(ph.position(), decode_direction(ph.dir), [&](uint32_t i) {
                    out.pairs.push_back({i, uint32_t(j)});
                });
            }
            return out;
        },
        [&](size_t k, Batch&& out) {
            for (const Pair& q : out.pairs) ++g.start[q.point + 1];
            kept[k] = std::move(out);
            ctx.counters.stage.set_done(int64_t(std::min(photons.size(), (b0 + k + 1) * k_gather_batch)));
        },
        &ctx.cancel);
    for (size_t i = 0; i < points; ++i) g.start[i + 1] += g.start[i];
    g.photons_of.resize(g.start[points]);
    std::vector<uint32_t> fill(g.start.begin(), g.start.end() - 1);
    for (const Batch& batch : kept)
        for (const Pair& q : batch.pairs) g.photons_of[fill[q.point]++] = q.photon;
    return g;
}

/// Adds a round's pairs to the points' sums: each point shaded once, f·a toward each of its photons.
void add_flux(const Scene& scene, const std::vector<VisiblePoint>& points, const PhotonShot& shot, const Gathered& g,
              float alpha_threshold, float time, int threads, PixelFlux& flux) {
    if (g.photons_of.empty()) return;
    const LobeSubset estimated{alpha_threshold, false};
    const size_t n = points.size(), chunk = 1024;
    parallel_for(threads, (n + chunk - 1) / chunk, [&](size_t c) {
        const ShutterScope scope(time);  // the visible points' shading at their iteration's time
        for (size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) {
            const uint32_t b = g.start[i], e = g.start[i + 1];
            if (e == b) continue;
            const VisiblePoint& vp = points[i];
            const ShadingPoint sp = scene.shade(vp.hit, vp.wo);
            const FixedViewBsdf fv(vp.hit, vp.wo, sp, &estimated);
            Color phi(0.f);
            for (uint32_t k = b; k < e; ++k) {
                const Photon& ph = shot.photons[g.photons_of[k]];
                phi += fv.f_adjoint(decode_direction(ph.dir)) * decode_flux(ph.flux);
            }
            flux.phi[i] += phi * shot.flux_scale;
            flux.found[i] += e - b;
        }
    });
}

}  // namespace

PixelFlux gather_flux(const Scene& scene, const std::vector<VisiblePoint>& points, const std::vector<float>& radii,
                      const PhotonShot& shot, float alpha_threshold, float time, RenderContext& ctx) {
    PixelFlux flux{std::vector<Color>(points.size(), Color(0.f)), std::vector<uint32_t>(points.size(), 0u)};
    const VisiblePointGrid grid = grid_of(points, radii);
    if (grid.empty() || shot.photons.empty()) return flux;
    const size_t batches = (shot.photons.size() + k_gather_batch - 1) / k_gather_batch;
    ctx.counters.stage.begin("Gathering photons", int64_t(shot.photons.size()));
    // The first round is one batch: nothing is known yet about the pairs per batch, and a round of several
    // batches at a large radius (hundreds of points per photon) would hold many times the budget.
    size_t per_round = 1;
    for (size_t b0 = 0; b0 < batches && !ctx.cancel.cancelled();) {
        const size_t b1 = std::min(batches, b0 + per_round);
        const Gathered g = gather(grid, points.size(), shot.photons, b0, b1, ctx);
        if (ctx.cancel.cancelled()) break;
        add_flux(scene, points, shot, g, alpha_threshold, time, ctx.threads, flux);
        const size_t per_batch = std::max<size_t>(1, g.photons_of.size() / (b1 - b0));
        per_round = std::max<size_t>(1, k_pair_budget / per_batch);
        b0 = b1;
    }
    ctx.counters.stage.end();
    return flux;
}

}  // namespace candela
