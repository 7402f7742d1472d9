#include "lights/light_sampler.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "core/math.h"

namespace candela {

const std::vector<std::string>& light_selection_names() {
    static const std::vector<std::string> names = {"ALL", "UNIFORM", "AREA", "POWER", "TREE", "WARD"};
    return names;
}

LightSelection parse_light_selection(const std::string& name) {
    const auto& names = light_selection_names();
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return LightSelection(i);
    throw InvalidScene("light_selection '" + name + "' is unknown (ALL, UNIFORM, AREA, POWER, TREE, WARD)");
}

// ---- UNIFORM / tables ----------------------------------------------------------------------------------

uint32_t UniformLightSampler::select(const LightSampleContext&, float u, float* pmf) const {
    if (m_n == 0) {
        *pmf = 0.f;
        return 0;
    }
    *pmf = 1.f / float(m_n);
    return std::min(uint32_t(u * float(m_n)), m_n - 1);
}

TableLightSampler::TableLightSampler(std::vector<float> weights)
    : m_dist(std::move(weights)), m_usable(m_dist.size() > 0 && m_dist.integral() > 0.f) {}

// ---- TREE ----------------------------------------------------------------------------------------------

namespace {

/// pbrt-v4's orientation measure M_Ω of a cone (θ_o, θ_e).
float cone_measure(float cos_o, float cos_e) {
    const float theta_o = acos_clamped(cos_o), theta_e = acos_clamped(cos_e);
    const float theta_w = std::min(theta_o + theta_e, k_pi);
    const float sin_o = std::sin(theta_o);
    return 2.f * k_pi * (1.f - cos_o) +
           k_pi / 2.f * (2.f * theta_w * sin_o - std::cos(theta_o - 2.f * theta_w) - 2.f * theta_o * sin_o + cos_o);
}

/// Surface-area-orientation cost of a cluster for a split along `axis` of the parent box extent.
float saoh_cost(const LightBounds& b, const Vec3& parent_extent, int axis) {
    const float max_extent = max_component(parent_extent);
    const float e = axis == 0 ? parent_extent.x : axis == 1 ? parent_extent.y : parent_extent.z;
    const float kr = e > 0.f ? max_extent / e : 1.f;
    return b.phi * cone_measure(b.cos_theta_o, b.cos_theta_e) * kr * std::max(b.bounds.surface_area(), 1e-20f);
}

float axis_of(const Vec3& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

/// The probability of taking child `which` given child importances (c0, c1): the same expression in
/// select() and pmf(), so both give bit-identical products.
inline float child_prob(float c0, float c1, int which) {
    const float p0 = c0 / (c0 + c1);
    return which == 0 ? p0 : 1.f - p0;
}

// Cluster thresholds (see light_sampler.h, TREE). Sampling a cluster's leaves ∝ flux φ_i instead of ∝ their
// importances w_i·φ_i costs that light's share of the variance a factor E_φ[w²]/E_φ[w]², while every level of
// descent saved is two importance evaluations (about a quarter of a path vertex's cost on a tessellated emitter).
// Distance: with the bounding sphere within asin τ_d of p, w's 1/d² spans a ratio ((1 + τ_d)/(1 − τ_d))² = 1.83 at
// τ_d = 0.15: a variance factor 1.03 for w spread evenly over it, 1.09 at worst (half the flux at each end). Orientation: one-sided emitters behind their normal cone get w = 0, so a one-sided node clusters
// only if its normals spread ≤ θ_c = 0.6 rad. Two-sided emitters (emissive triangles) fold the cosine, |cos|, and
// cluster at any spread: for a closed tessellated surface the |cos| weighting the descent would find costs at most
// E[cos²]/E[|cos|]² = 4/3 (a sphere), and its back half is occluded anyway. Measured on Veach's MIS scene (8.8k
// emissive triangles, 160×90, 4 seeds × 64 spp, one thread, variance without the 1 % of pixels with fireflies):
// 10 % more variance than the full descent at 0.56× its time per sample, the same variance × time as POWER where
// the full descent was 1.6× POWER's; `make accuracy` compares TREE and POWER on that scene ("Candela PATH POWER").
constexpr float k_cluster_sin = 0.15f;      // τ_d: the node's bounding sphere radius over its distance
constexpr float k_cluster_cos_o = 0.8253f;  // cos θ_c, θ_c = 0.6 rad (one-sided nodes)

}  // namespace

TreeLightSampler::TreeLightSampler(const LightSet& lights) {
    const auto n = uint32_t(lights.size());
    m_leaf_of_light.assign(n, ~0u);
    m_is_infinite.assign(n, false);
    std::vector<std::pair<uint32_t, LightBounds>> items;
    for (uint32_t i = 0; i < n; ++i) {
        const auto lb = light_bounds(lights[i]);
        if (!lb) {
            m_infinite.push_back(i);
            m_is_infinite[i] = true;
        } else if (lb->phi > 0.f && std::isfinite(lb->phi)) {
            items.emplace_back(i, *lb);
        }
    }
    if (!items.empty()) {
        m_nodes.reserve(2 * items.size());
        build(items, 0, items.size(), ~0u, 1);
        index_leaves();
    }
    const size_t n_inf = m_infinite.size();
    m_p_infinite = n_inf == 0 ? 0.f : float(n_inf) / float(n_inf + (m_nodes.empty() ? 0 : 1));
}

uint32_t TreeLightSampler::build(std::vector<std::pair<uint32_t, LightBounds>>& items, size_t begin, size_t end,
                                 uint32_t parent, int depth) {
    m_depth = std::max(m_depth, depth);
    const auto node_index = uint32_t(m_nodes.size());
    m_nodes.emplace_back();
    m_nodes[node_index].parent = parent;
    if (end - begin == 1) {
        Node& leaf = m_nodes[node_index];
        leaf.leaf = true;
        leaf.index = items[begin].first;
        leaf.lb = items[begin].second;
        leaf.importance = LightImportance(leaf.lb);
        m_leaf_of_light[leaf.index] = node_index;
        return node_index;
    }
    Bounds3 box, centroids;
    for (size_t i = begin; i < end; ++i) {
        box.extend(items[i].second.bounds);
        centroids.extend(items[i].second.bounds.centroid());
    }
    const Vec3 extent = box.diagonal(), cextent = centroids.diagonal();

    // Bucketed SAOH split over the three axes (pbrt-v4's BVHLightSampler::buildBVH, 12 buckets).
    constexpr int k_buckets = 12;
    float best_cost = std::numeric_limits<float>::infinity();
    int best_axis = -1, best_bucket = -1;
    if (depth < 60) {
        for (int a = 0; a < 3; ++a) {
            const float lo = axis_of(centroids.lo, a), ext = axis_of(cextent, a);
            if (!(ext > 0.f)) continue;
            LightBounds buckets[k_buckets];
            for (size_t i = begin; i < end; ++i) {
                int b = int(k_buckets * ((axis_of(items[i].second.bounds.centroid(), a) - lo) / ext));
                b = std::clamp(b, 0, k_buckets - 1);
                buckets[b] = union_bounds(buckets[b], items[i].second);
            }
            // Splits after bucket s, for s < 11. union_bounds returns the other operand unchanged when one has no
            // flux, so folding only the occupied buckets (in order) gives the same bits as folding all of them, and
            // every split between two consecutive occupied buckets has the same two halves, hence the same cost:
            // only the first of them (s = the lower occupied bucket) can win under the strict `<`. `below` grows by
            // one bucket per split (the same left fold as forming it anew); `above` is folded anew each time, since
            // a suffix sweep would add the fluxes in another order and could flip near-tied splits.
            int occupied[k_buckets], m = 0;
            for (int b = 0; b < k_buckets; ++b)
                if (buckets[b].phi > 0.f) occupied[m++] = b;
            LightBounds below;
            for (int i = 0; i + 1 < m; ++i) {
                below = union_bounds(below, buckets[occupied[i]]);
                LightBounds above = buckets[occupied[i + 1]];
                for (int j = i + 2; j < m; ++j) above = union_bounds(above, buckets[occupied[j]]);
                const float cost = saoh_cost(below, extent, a) + saoh_cost(above, extent, a);
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = a;
                    best_bucket = occupied[i];
                }
            }
        }
    }
    size_t mid;
    if (best_axis >= 0) {
        const float lo = axis_of(centroids.lo, best_axis), ext = axis_of(cextent, best_axis);
        auto it = std::partition(items.begin() + begin, items.begin() + end, [&](const auto& item) {
            int b = int(k_buckets * ((axis_of(item.second.bounds.centroid(), best_axis) - lo) / ext));
            return std::clamp(b, 0, k_buckets - 1) <= best_bucket;
        });
        mid = size_t(it - items.begin());
    } else {
        mid = begin;
    }
    if (mid == begin || mid == end) {  // no useful split: halve by count along the widest centroid axis
        const int a = cextent.x >= cextent.y && cextent.x >= cextent.z ? 0 : cextent.y >= cextent.z ? 1 : 2;
        mid = (begin + end) / 2;
        std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                         [&](const auto& x, const auto& y) {
                             return axis_of(x.second.bounds.centroid(), a) < axis_of(y.second.bounds.centroid(), a);
                         });
    }
    build(items, begin, mid, node_index, depth + 1);
    const uint32_t second = build(items, mid, end, node_index, depth + 1);
    Node& node = m_nodes[node_index];
    node.index = second;
    node.lb = union_bounds(m_nodes[node_index + 1].lb, m_nodes[second].lb);
    node.importance = LightImportance(node.lb);
    return node_index;
}

void TreeLightSampler::index_leaves() {
    // Nodes are stored in preorder (a node's first child follows it), so leaves in index order are depth-first
    // and every subtree's leaves are one contiguous run of ranks.
    m_rank_of_light.assign(m_leaf_of_light.size(), ~0u);
    m_light_of_rank.clear();
    m_flux_prefix.assign(1, 0.0);
    for (Node& nd : m_nodes) {
        if (!nd.leaf) continue;
        nd.first_leaf = uint32_t(m_light_of_rank.size());
        m_rank_of_light[nd.index] = nd.first_leaf;
        m_light_of_rank.push_back(nd.index);
        m_flux_prefix.push_back(m_flux_prefix.back() + double(nd.lb.phi));
    }
    for (size_t i = m_nodes.size(); i-- > 0;) {  // children after parents: fill interior ranges bottom-up
        Node& nd = m_nodes[i];
        if (nd.leaf) continue;
        const Node &a = m_nodes[i + 1], &b = m_nodes[nd.index];
        nd.first_leaf = a.first_leaf;
        nd.leaf_count = a.leaf_count + b.leaf_count;
        nd.narrow = nd.lb.two_sided || nd.lb.cos_theta_o >= k_cluster_cos_o;
    }
}

bool TreeLightSampler::is_cluster(uint32_t node, const LightSampleContext& ctx) const {
    const Node& nd = m_nodes[node];
    if (!nd.narrow) return false;
    const LightImportance& im = nd.importance;
    return length_squared(ctx.p - im.centre) * (k_cluster_sin * k_cluster_sin) > im.radius2;
}

uint32_t TreeLightSampler::pick_in_cluster(const Node& node, float u, float* pmf) const {
    const double lo = m_flux_prefix[node.first_leaf], hi = m_flux_prefix[node.first_leaf + node.leaf_count];
    const double target = lo + double(u) * (hi - lo);
    const auto begin = m_flux_prefix.begin() + node.first_leaf + 1;
    const auto it = std::upper_bound(begin, begin + (node.leaf_count - 1), target);
    const auto rank = uint32_t(it - m_flux_prefix.begin()) - 1;
    *pmf = cluster_pmf(node, rank);
    return rank;
}

float TreeLightSampler::cluster_pmf(const Node& node, uint32_t rank) const {
    const double lo = m_flux_prefix[node.first_leaf], hi = m_flux_prefix[node.first_leaf + node.leaf_count];
    return float((m_flux_prefix[rank + 1] - m_flux_prefix[rank]) / (hi - lo));
}

void TreeLightSampler::child_importances(uint32_t node, const LightSampleContext& ctx, float* c0, float* c1) const {
    const Node& a = m_nodes[node + 1];
    const Node& b = m_nodes[m_nodes[node].index];
    *c0 = a.importance(ctx.p, ctx.n);
    *c1 = b.importance(ctx.p, ctx.n);
    if (!(*c0 + *c1 > 0.f)) {
        // The parent's looser bounds admitted the point but neither child's does: no light below can contribute.
        // Split ∝ flux so that the pmf still sums to one (those lights' samples will carry no radiance).
        *c0 = a.lb.phi;
        *c1 = b.lb.phi;
    }
}

uint32_t TreeLightSampler::select(const LightSampleContext& ctx, float u, float* pmf) const {
    *pmf = 0.f;
    const auto n_inf = uint32_t(m_infinite.size());
    if (n_inf > 0 && u < m_p_infinite) {
        const uint32_t k = std::min(uint32_t(u / m_p_infinite * float(n_inf)), n_inf - 1);
        *pmf = m_p_infinite / float(n_inf);
        return m_infinite[k];
    }
    if (m_nodes.empty()) return 0;
    u = std::min((u - m_p_infinite) / (1.f - m_p_infinite), k_one_minus_epsilon);
    float p = 1.f - m_p_infinite;
    uint32_t node = 0;
    for (;;) {
        const Node& nd = m_nodes[node];
        if (nd.leaf) {
            *pmf = p;
            return nd.index;
        }
        if (is_cluster(node, ctx)) {
            float in_cluster;
            const uint32_t rank = pick_in_cluster(nd, u, &in_cluster);
            *pmf = p * in_cluster;
            return m_light_of_rank[rank];
        }
        float c0, c1;
        child_importances(node, ctx, &c0, &c1);
        const float p0 = child_prob(c0, c1, 0);
        if (u < p0) {
            u = std::min(u / p0, k_one_minus_epsilon);
            p *= p0;
            node = node + 1;
        } else {
            const float p1 = child_prob(c0, c1, 1);
            u = std::min((u - p0) / p1, k_one_minus_epsilon);
            p *= p1;
            node = nd.index;
        }
    }
}

float TreeLightSampler::pmf(const LightSampleContext& ctx, uint32_t light) const {
    if (light >= m_leaf_of_light.size()) return 0.f;
    if (m_is_infinite[light]) return m_p_infinite / float(m_infinite.size());
    const uint32_t leaf = m_leaf_of_light[light];
    if (leaf == ~0u) return 0.f;
    // The root-to-leaf path, then the same products as select(), top-down.
    uint32_t path[128];
    std::vector<uint32_t> long_path;
    int len = 0;
    for (uint32_t nd = leaf; nd != ~0u; nd = m_nodes[nd].parent) {
        if (len < 128)
            path[len] = nd;
        else {
            if (long_path.empty()) long_path.assign(path, path + 128);
            long_path.push_back(nd);
        }
        ++len;
    }
    auto at = [&](int i) { return long_path.empty() ? path[i] : long_path[size_t(i)]; };
    float p = 1.f - m_p_infinite;
    for (int i = len - 1; i > 0; --i) {
        const uint32_t nd = at(i), child = at(i - 1);
        if (is_cluster(nd, ctx)) return p * cluster_pmf(m_nodes[nd], m_rank_of_light[light]);
        float c0, c1;
        child_importances(nd, ctx, &c0, &c1);
        p *= child_prob(c0, c1, child == nd + 1 ? 0 : 1);
    }
    return p;
}

// ---- WARD ----------------------------------------------------------------------------------------------

size_t WardList::select_tail(size_t k, float u, float* pmf) const {
    *pmf = 0.f;
    const double tail = remainder(k);
    if (k >= size() || !(tail > 0.0)) return size();
    const double target = double(u) * tail;
    // m_suffix is decreasing: find the last j with suffix[k] − suffix[j] ≤ target.
    size_t j = k;
    double below = 0.0;
    for (; j + 1 < size(); ++j) {
        below += m_candidates[j].bound;
        if (below > target) break;
    }
    *pmf = float(double(m_candidates[j].bound) / tail);
    return j;
}

namespace {
void bounds_at(const LightSet& lights, const LightSampleContext& ctx, std::vector<float>* b, double* total) {
    b->resize(lights.size());
    *total = 0.0;
    for (size_t i = 0; i < lights.size(); ++i) {
        float v = light_irradiance_bound(lights[i], ctx);
        if (!(v > 0.f) || !std::isfinite(v)) v = v > 0.f ? std::numeric_limits<float>::max() * 1e-6f : 0.f;
        (*b)[i] = v;
        *total += v;
    }
}
}  // namespace

uint32_t WardLightSampler::select(const LightSampleContext& ctx, float u, float* pmf) const {
    *pmf = 0.f;
    if (!m_lights || m_lights->empty()) return 0;
    std::vector<float> b;
    double total;
    bounds_at(*m_lights, ctx, &b, &total);
    if (!(total > 0.0)) return 0;
    const double target = double(u) * total;
    double cum = 0.0;
    uint32_t last_nonzero = 0;
    for (uint32_t i = 0; i < b.size(); ++i) {
        if (!(b[i] > 0.f)) continue;
        last_nonzero = i;
        cum += b[i];
        if (cum > target) break;
    }
    *pmf = float(double(b[last_nonzero]) / total);
    return last_nonzero;
}

float WardLightSampler::pmf(const LightSampleContext& ctx, uint32_t light) const {
    if (!m_lights || light >= m_lights->size()) return 0.f;
    std::vector<float> b;
    double total;
    bounds_at(*m_lights, ctx, &b, &total);
    if (!(total > 0.0)) return 0.f;
    return float(double(b[light]) / total);
}

WardList WardLightSampler::candidates(const LightSampleContext& ctx) const {
    WardList list;
    if (!m_lights) return list;
    std::vector<float> b;
    double total;
    bounds_at(*m_lights, ctx, &b, &total);
    for (uint32_t i = 0; i < b.size(); ++i)
        if (b[i] > 0.f) list.m_candidates.push_back({i, b[i]});
    std::stable_sort(list.m_candidates.begin(), list.m_candidates.end(),
                     [](const WardList::Candidate& x, const WardList::Candidate& y) { return x.bound > y.bound; });
    list.m_suffix.assign(list.m_candidates.size() + 1, 0.0);
    for (size_t j = list.m_candidates.size(); j-- > 0;)
        list.m_suffix[j] = list.m_suffix[j + 1] + list.m_candidates[j].bound;
    return list;
}

float WardLightSampler::adaptive_pmf(const LightSampleContext& ctx, uint32_t light, size_t tested) const {
    const WardList list = candidates(ctx);
    for (size_t r = 0; r < list.size(); ++r) {
        if (list.candidates()[r].light != light) continue;
        if (r < tested) return 1.f;
        const double tail = list.remainder(tested);
        return tail > 0.0 ? float(double(list.candidates()[r].bound) / tail) : 0.f;
    }
    return 0.f;
}

// ---- registry ------------------------------------------------------------------------------------------

LightSampler make_light_sampler(LightSelection kind, const LightSet& lights, const LightSamplerOptions&) {
    const auto n = uint32_t(lights.size());
    switch (kind) {
    case LightSelection::All:
    case LightSelection::Uniform: return LightSampler(kind, n, UniformLightSampler(n));
    case LightSelection::Area: {
        std::vector<float> area(n);
        double sum = 0.0;
        int count = 0;
        for (uint32_t i = 0; i < n; ++i) {
            area[i] = light_area(lights[i]);
            if (area[i] > 0.f) {
                sum += area[i];
                ++count;
            }
        }
        const float stand_in = count > 0 ? float(sum / count) : 1.f;
        for (float& a : area)
            if (!(a > 0.f)) a = stand_in;
        return LightSampler(kind, n, TableLightSampler(std::move(area)));
    }
    case LightSelection::Power: {
        std::vector<float> power(n);
        for (uint32_t i = 0; i < n; ++i) power[i] = light_power(lights[i]);
        return LightSampler(kind, n, TableLightSampler(std::move(power)));
    }
    case LightSelection::Tree: return LightSampler(kind, n, TreeLightSampler(lights));
    case LightSelection::Ward: return LightSampler(kind, n, WardLightSampler(lights));
    }
    throw InternalError("unknown light selection");
}

LightSampler make_light_sampler(const std::string& name, const LightSet& lights, const LightSamplerOptions& options) {
    return make_light_sampler(parse_light_selection(name), lights, options);
}

// ---- light_samples -------------------------------------------------------------------------------------

Vec2 light_sample_u_strided(Vec2 u2, uint32_t j, uint32_t k) {
    const double golden = 0.6180339887498949;
    double x = double(u2.x) + double(j) / double(k);
    double y = double(u2.y) + double(j) * golden;
    x -= std::floor(x);
    y -= std::floor(y);
    return {std::min(float(x), k_one_minus_epsilon), std::min(float(y), k_one_minus_epsilon)};
}

}  // namespace candela
