// Light selection strategies — the add-on's `light_selection` option. Every strategy answers
//   select(ctx, u, &pmf) → light index (pmf == 0: no light could be chosen), and
//   pmf(ctx, i)          → exactly the probability with which select() returns i from ctx (for MIS),
// with Σ_i pmf(ctx, i) = 1 whenever any light can contribute at ctx.
//   ALL      — the caller estimates every light once per vertex (for i < size(): weight 1). select/pmf
//              behave as UNIFORM for callers that still draw one light; nee_pmf() returns 1 (the MIS
//              selection probability of an exhaustive loop).
//   UNIFORM  — 1/N.
//   AREA     — ∝ emitting area; lights without one (point, spot, sun, world) use the stand-in "mean area of
//              the area-like lights" (1 if there are none), so they are neither starved nor favoured.
//   POWER    — ∝ flux (light_power), the LightSet's own distribution.
//   TREE     — a light BVH (Conty & Kulla 2018 / pbrt-v4) over every finite light; a stochastic descent
//              from (p, n) picks a child ∝ its importance (∝ flux where both children's importance is 0, so the
//              pmf always sums to one and every finite light with φ > 0 stays reachable). Infinite lights (sun,
//              world) stay outside the tree with a fixed share: each gets 1/(n_inf + 1) (pbrt-v4), the tree the
//              rest. The descent stops early at a *cluster*: a node small as seen from p (bounding sphere within
//              a cone of half-angle asin τ_d) whose emitters are two-sided or face nearly one way (normal
//              spread ≤ θ_c). Below it the leaves' importances differ by distance and cosine factors that vary
//              little over it, so the descent would mostly reproduce the flux ratios: a light is picked ∝ flux
//              among the node's leaves (prefix sums, one binary search). A tessellated emitter seen from afar is
//              one cluster instead of a 12-level descent (the thresholds and their cost: light_sampler.cpp).
//   WARD     — Ward 1991: per-point upper bounds of every light's contribution. select() picks ∝ bound;
//              candidates(ctx) returns the lights sorted by decreasing bound for adaptive shadow testing.
// Samplers keep a pointer to the LightSet they were built from: it must outlive them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "core/math.h"
#include "lights/light.h"
#include "lights/light_bounds.h"
#include "sampling/distribution_1d.h"

namespace candela {

enum class LightSelection : uint8_t { All, Uniform, Area, Power, Tree, Ward };

/// "ALL", "UNIFORM", "AREA", "POWER", "TREE", "WARD" (index = enum value).
const std::vector<std::string>& light_selection_names();
/// Throws InvalidScene for an unknown name.
LightSelection parse_light_selection(const std::string& name);

class UniformLightSampler {
public:
    explicit UniformLightSampler(uint32_t n = 0) : m_n(n) {}
    uint32_t select(const LightSampleContext&, float u, float* pmf) const;
    float pmf(const LightSampleContext&, uint32_t light) const { return light < m_n ? 1.f / float(m_n) : 0.f; }

private:
    uint32_t m_n;
};

/// A fixed distribution over lights (AREA, POWER).
class TableLightSampler {
public:
    TableLightSampler() = default;
    explicit TableLightSampler(std::vector<float> weights);
    uint32_t select(const LightSampleContext&, float u, float* pmf) const {
        if (!m_usable) {
            *pmf = 0.f;
            return 0;
        }
        return uint32_t(m_dist.sample_discrete(u, pmf));
    }
    float pmf(const LightSampleContext&, uint32_t light) const {
        return light < m_dist.size() ? m_dist.pmf(light) : 0.f;
    }

private:
    Distribution1D m_dist;
    bool m_usable = false;  // some weight > 0
};

class TreeLightSampler {
public:
    struct Node {
        LightBounds lb;
        LightImportance importance;  // lb prepared for queries
        uint32_t index = 0;          // leaf: light index; interior: second child (the first is this node + 1)
        uint32_t parent = ~0u;
        uint32_t first_leaf = 0, leaf_count = 1;  // the node's leaves, ranks in depth-first order
        bool leaf = false;
        bool narrow = false;  // interior node that may be a cluster: two-sided, or normal spread ≤ θ_c
    };

    TreeLightSampler() = default;
    explicit TreeLightSampler(const LightSet& lights);

    uint32_t select(const LightSampleContext& ctx, float u, float* pmf) const;
    float pmf(const LightSampleContext& ctx, uint32_t light) const;

    const std::vector<Node>& nodes() const { return m_nodes; }
    const std::vector<uint32_t>& infinite_lights() const { return m_infinite; }
    /// Probability of the infinite lights together.
    float infinite_share() const { return m_p_infinite; }
    int depth() const { return m_depth; }

    /// Whether the descent stops at interior node `node` for ctx and picks among its leaves ∝ flux.
    bool is_cluster(uint32_t node, const LightSampleContext& ctx) const;

private:
    void child_importances(uint32_t node, const LightSampleContext& ctx, float* c0, float* c1) const;
    void index_leaves();
    /// Leaf rank picked ∝ flux within `node`'s leaves by u, and its probability there.
    uint32_t pick_in_cluster(const Node& node, float u, float* pmf) const;
    float cluster_pmf(const Node& node, uint32_t rank) const;
    uint32_t build(std::vector<std::pair<uint32_t, LightBounds>>& items, size_t begin, size_t end, uint32_t parent,
                   int depth);

    std::vector<Node> m_nodes;
    std::vector<uint32_t> m_leaf_of_light;  // node index, ~0u if the light is not in the tree
    std::vector<uint32_t> m_light_of_rank;  // light index by depth-first leaf rank
    std::vector<uint32_t> m_rank_of_light;  // the inverse (~0u outside the tree)
    std::vector<double> m_flux_prefix;      // Σ flux of the leaves of rank < r, size leaves + 1
    std::vector<uint32_t> m_infinite;       // sun and world lights
    std::vector<bool> m_is_infinite;
    float m_p_infinite = 0.f;
    int m_depth = 0;
};

/// Lights sorted by decreasing upper bound of their contribution at one shading point (Ward 1991).
///
/// Adaptive shadow testing, as the caller runs it: for k = 0, 1, ... shadow-test candidates()[k] (its full NEE
/// estimate c_k, visibility v_k), accumulate A += v_k·c_k, and stop once remainder(k+1) ≤ threshold · A
/// (should_stop). The untested tail candidates()[k+1..] is then accounted for by one of:
///   - Ward's original (biased, low variance): add hit_rate · Σ_tail c̃_j, where c̃_j is the light's unoccluded
///     estimate (no shadow ray) and hit_rate = Σ v_k c_k / Σ c_k over the tested lights (Radiance's running
///     rate; 1 if none was tested) — or, cheaper and more biased, hit_rate · remainder(k+1) using the bounds;
///   - unbiased: draw one tail light j ∝ bound with select_tail(k+1, u, &pmf), shadow-test it and add
///     v_j·c_j / pmf (a one-sample estimate of the tail sum; `pmf` is exact).
/// Lights with a zero bound cannot contribute at this point and are left out.
class WardList {
public:
    struct Candidate {
        uint32_t light;
        float bound;
    };

    const std::vector<Candidate>& candidates() const { return m_candidates; }
    size_t size() const { return m_candidates.size(); }
    /// Σ of all bounds.
    double total() const { return m_suffix.empty() ? 0.0 : m_suffix[0]; }
    /// Σ_{j ≥ k} bound_j: the most the untested lights k.. can still add (0 for k ≥ size()).
    double remainder(size_t k) const { return k < m_suffix.size() ? m_suffix[k] : 0.0; }
    /// Ward's stopping rule after testing the first k candidates with accumulated (visible) value A.
    bool should_stop(size_t k, double accumulated, double threshold) const {
        return k >= size() || remainder(k) <= threshold * accumulated;
    }
    /// Picks candidate index j ≥ k ∝ bound (returns size() with pmf 0 if the tail is empty).
    size_t select_tail(size_t k, float u, float* pmf) const;

private:
    friend class WardLightSampler;
    std::vector<Candidate> m_candidates;
    std::vector<double> m_suffix;  // suffix sums of the bounds, size()+1 entries
};

class WardLightSampler {
public:
    WardLightSampler() = default;
    explicit WardLightSampler(const LightSet& lights) : m_lights(&lights) {}

    /// Picks a light ∝ its bound at ctx (pbrt's "exhaustive" sampler with Ward's bounds): O(N) per call.
    uint32_t select(const LightSampleContext& ctx, float u, float* pmf) const;
    float pmf(const LightSampleContext& ctx, uint32_t light) const;
    /// The bound-sorted candidate list at ctx: O(N log N).
    WardList candidates(const LightSampleContext& ctx) const;
    /// The probability with which adaptive shadow testing at ctx, having tested the first `tested` candidates
    /// with every light sample, estimates `light`: 1 if it was tested, its tail-selection pmf otherwise
    /// (0 for a light with a zero bound). The MIS light density of that realisation.
    float adaptive_pmf(const LightSampleContext& ctx, uint32_t light, size_t tested) const;

private:
    const LightSet* m_lights = nullptr;
};

struct LightSamplerOptions {
    // (reserved: tree split parameters, Ward thresholds live with the caller)
};

/// A light-selection strategy (closed family).
class LightSampler {
public:
    using Impl = std::variant<UniformLightSampler, TableLightSampler, TreeLightSampler, WardLightSampler>;

    LightSampler() = default;
    LightSampler(LightSelection kind, uint32_t num_lights, Impl impl)
        : m_kind(kind), m_size(num_lights), m_impl(std::move(impl)) {}

    LightSelection kind() const { return m_kind; }
    const char* name() const { return light_selection_names()[size_t(m_kind)].c_str(); }
    uint32_t size() const { return m_size; }
    /// ALL: the caller loops over every light (weight 1 each) instead of drawing one.
    bool exhaustive() const { return m_kind == LightSelection::All; }

    uint32_t select(const LightSampleContext& ctx, float u, float* pmf) const {
        return std::visit([&](const auto& s) { return s.select(ctx, u, pmf); }, m_impl);
    }
    float pmf(const LightSampleContext& ctx, uint32_t light) const {
        return std::visit([&](const auto& s) { return s.pmf(ctx, light); }, m_impl);
    }
    /// The selection probability to put in the MIS light density for light i: 1 for ALL (every light is
    /// estimated), pmf(ctx, i) otherwise.
    float nee_pmf(const LightSampleContext& ctx, uint32_t light) const {
        return exhaustive() ? (light < m_size ? 1.f : 0.f) : pmf(ctx, light);
    }

    const Impl& impl() const { return m_impl; }
    const TreeLightSampler* tree() const { return std::get_if<TreeLightSampler>(&m_impl); }
    const WardLightSampler* ward() const { return std::get_if<WardLightSampler>(&m_impl); }

private:
    LightSelection m_kind = LightSelection::Power;
    uint32_t m_size = 0;
    Impl m_impl;
};

/// The registry: builds strategy `name` (light_selection_names()) over a finalized LightSet.
LightSampler make_light_sampler(const std::string& name, const LightSet& lights, const LightSamplerOptions& = {});
LightSampler make_light_sampler(LightSelection kind, const LightSet& lights, const LightSamplerOptions& = {});

// ---- `light_samples`: k light samples per vertex -------------------------------------------------------
// One selection number u and one 2-D number u2 per vertex are spread over k samples:
//   for j < k:  i_j = sampler.select(ctx, light_select_u(u, j, k), &pmf_j);
//               ls_j = lights.sample_li(i_j, ctx, light_sample_u(u2, j, k));
//               L += f·ls_j.Li·cos / (k · pmf_j · ls_j.pdf)            (× MIS weight)
// The selection numbers are stratified over [0,1) — exact for every strategy, since each maps u to lights by
// nested intervals of length pmf — and the 2-D numbers form a Cranley–Patterson-rotated Fibonacci lattice.
// For MIS with one BSDF sample, the light strategy's density is k·pmf·pdf (light_mis_pdf); with ALL,
// k·pdf_li per light.

/// The j-th of k stratified selection numbers: (j + u)/k, kept below 1. Inline for the common k = 1 (called
/// several times per path vertex).
inline float light_select_u(float u, uint32_t j, uint32_t k) {
    if (k <= 1) return std::min(u, k_one_minus_epsilon);
    return std::min((float(j) + u) / float(k), k_one_minus_epsilon);
}
/// The j-th of k 2-D light-sample numbers: frac(u2 + (j/k, frac(j·φ⁻¹))).
Vec2 light_sample_u_strided(Vec2 u2, uint32_t j, uint32_t k);
inline Vec2 light_sample_u(Vec2 u2, uint32_t j, uint32_t k) { return k <= 1 ? u2 : light_sample_u_strided(u2, j, k); }
/// The light strategy's density for the power heuristic with k light samples per vertex.
inline float light_mis_pdf(float selection_pmf, float pdf_li, uint32_t k) { return float(k) * selection_pmf * pdf_li; }

}  // namespace candela
