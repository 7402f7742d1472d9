// One strategy (s, t) of bidirectional path tracing (Veach 1997, §10.2–10.3): the path made of the light subpath's
// first s vertices and the camera subpath's first t, joined by a connection (s = 0: the camera subpath found an
// emitter; s = 1: a fresh point on an emitter; t = 1: a fresh point on the lens, splatted), its unweighted
// contribution, and its multiple-importance weight among all strategies that could have produced the same path:
//     w_{s,t} = p_s^β / Σ_i p_i^β   (β = 1 balance, β = 2 power heuristic; eq. 10.9),
// computed as pbrt-v3 does (§16.3.4) from the ratios p_{i±1}/p_i, which each vertex's two area densities give: the
// connection changes the reverse densities of the two vertices on each side of it, recomputed here. Delta vertices
// (delta lobes, delta lights, the lens of an orthographic pinhole) drop the strategies that would have to hit or
// connect through them.
//
// A path of two vertices, an emitter the camera sees, has two strategies: (0, 2), the camera ray that hits it, and
// (1, 1), a point sampled on the emitter joined to the lens (light tracing's image of the emitter). Their weights
// compare the camera ray's area density at the point, about N_e/(W·H·A) for an emitter covering N_e of the W·H pixels
// and of area A, with the emission's P(e)/A: where an emitter covers few pixels, the (1, 1) splats — W·H/N_e of them per
// pixel of the emitter and pass, against one camera ray — carry its image and its antialiased edges. (1, 1) exists
// for emitters a camera ray can hit (lens_strategy); for the others (0, 2) keeps the weight 1.
#pragma once

#include <vector>

#include "integrators/bdpt/subpaths.h"

namespace candela {

struct StrategyResult {
    Color L{0.f};        // unweighted contribution (what this strategy alone would estimate)
    float weight = 0.f;  // its MIS weight
    bool splat = false;  // t = 1: L lands at `raster`, not in the camera sample's pixel
    Vec2 raster{0.f};
};

/// The area densities with which each direction's sampling produces a vertex (path_vertex.h), for the MIS weights.
class Densities {
public:
    explicit Densities(const BdptContext& c) : m_c(c) {}
    /// The light side's density of `next` from `cur` (which was reached from `prev`; null for an emitter).
    float light_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next) const;
    /// The camera side's density of `next` from `cur` (reached from `prev` toward the camera; or the camera itself).
    float camera_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next) const;
    /// An emitter's density of emitting toward `next` (area measure at next; parallel rays for a distant one).
    float emission(const PathVertex& light, const PathVertex& next) const;
    /// The same three with the unit directions from `cur` (or `light`) toward prev and next given (w_prev unused
    /// without prev): strategy_weight knows each of them once.
    float light_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, const Vec3& w_prev,
                     const Vec3& w_next) const;
    float camera_side(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, const Vec3& w_prev,
                      const Vec3& w_next) const;
    float emission(const PathVertex& light, const PathVertex& next, const Vec3& d) const;
    /// A subpath's step from `cur` (reached from `prev`, or null) to `next`, in one: next's forward density and
    /// prev's reverse one (without prev, prev_rev is not written), the same values as camera_side(cur, prev, next) and
    /// light_side(cur, &next, *prev) (light_step: light_side and camera_side), each direction made once.
    void camera_step(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, float* next_fwd,
                     float* prev_rev) const;
    void light_step(const PathVertex& cur, const PathVertex* prev, const PathVertex& next, float* next_fwd,
                    float* prev_rev) const;
    /// The density of an emitting vertex as the origin of a light subpath: P(emitter)·p_pos (a distant one: its
    /// direction's solid-angle density).
    float origin(const PathVertex& v, const PathVertex& toward) const;

private:
    const BdptContext& m_c;
};

/// The MIS weight of strategy (s, t) of the path y[0 .. s) + z[t − 1 .. 0]; `sampled` replaces z[0] for t = 1, else
/// y[0] for s = 1; `area` (s = 0) replaces the camera vertex t − 1 (an area light passed on that segment).
/// `known`: what the connection already computed, bit for bit what the weight would compute from the vertices.
struct KnownConnection {
    const Vec3* w = nullptr;  // the unit direction from light vertex s − 1 toward camera vertex t − 1 (s, t ≥ 1)
    float lens_pdf_dir = -1.f;  // t = 1, when ≥ 0: the lens vertex's solid-angle density toward light vertex s − 1,
                                // as Camera::pdf_we gives it (up to rounding)
};
float strategy_weight(const BdptContext& c, const std::vector<PathVertex>& y, int s, const std::vector<PathVertex>& z,
                      int t, const PathVertex* sampled, const PathVertex* area, const KnownConnection& known = {});

/// Whether strategy (1, 1) exists for a path whose emitter end is `light_end` (a light vertex, or a surface or area
/// light a camera ray hit): an area light visible to the camera, or an emissive triangle in a scene where no object
/// is hidden from the camera and none is a holdout (a light vertex does not know its object), with a camera a
/// connection can reach.
bool lens_strategy(const BdptContext& c, const PathVertex& light_end);

/// Strategy (s, t) with s light and t camera vertices (s + t ≥ 2, t ≥ 1; for s = 0 the camera vertex t − 1 must be
/// an emitter). `area` (s = 0 only): the area light hit on the camera subpath's segment t − 1 instead of its vertex.
StrategyResult evaluate_strategy(const BdptContext& c, const std::vector<PathVertex>& y, int s,
                                 const std::vector<PathVertex>& z, int t,
                                 const std::vector<VertexNumbers>& camera_numbers,
                                 const std::vector<VertexNumbers>& light_numbers, const AreaLightHit* area,
                                 PathStats& stats);

}  // namespace candela
