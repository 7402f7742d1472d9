#include "integrators/photon_map/photon_map.h"

#include <immintrin.h>
#include <nanoflann.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace candela {

namespace {

/// One cell's photons as nanoflann's dataset adaptor sees them.
struct CellCloud {
    const Photon* photons = nullptr;
    size_t count = 0;
    size_t kdtree_get_point_count() const { return count; }
    /// Coordinate d of photon i, read at its offset (x, y, z lead the packed photon): no branch on d in
    /// nanoflann's build loops.
    float kdtree_get_pt(size_t i, size_t d) const {
        float v;
        std::memcpy(&v, reinterpret_cast<const unsigned char*>(photons + i) + sizeof(float) * d, sizeof v);
        return v;
    }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
};

using CellMetric = nanoflann::L2_Simple_Adaptor<float, CellCloud, float, uint16_t>;
using CellTree = nanoflann::KDTreeSingleIndexAdaptor<CellMetric, CellCloud, 3, uint16_t>;
constexpr size_t k_leaf_photons = 32;

constexpr float k_inf = std::numeric_limits<float>::infinity();

/// nanoflann result set of the k nearest accepted photons, ordered by (distance, index) across cells.
class NearestSet {
public:
    using DistanceType = float;
    using IndexType = uint16_t;

    NearestSet(const Photon* photons, const Vec3& x, int k, float max_dist2, const PhotonFilter& filter,
               PhotonNeighbor* out)
        : m_photons(photons), m_x(x), m_k(k), m_bound(std::nextafter(max_dist2, k_inf)), m_filter(filter), m_out(out) {}

    void set_base(uint32_t base) { m_base = base; }
    int size() const { return m_n; }
    bool full() const { return m_n == m_k; }
    float worstDist() const { return m_n < m_k ? m_bound : std::nextafter(m_out[m_k - 1].dist2, k_inf); }
    bool addPoint(float d2, uint16_t local) {
        const uint32_t index = m_base + local;
        // d_e ≥ d, so nanoflann's pruning by the Euclidean distance against the worst d_e stays exact.
        const float dist = m_filter.metric(m_photons[index], m_x, d2);
        if (!(dist < worstDist())) return true;
        auto before = [](float d, uint32_t i, const PhotonNeighbor& o) {
            return d < o.dist2 || (d == o.dist2 && i < o.index);
        };
        if (m_n == m_k && !before(dist, index, m_out[m_k - 1])) return true;
        int j = m_n < m_k ? m_n++ : m_k - 1;
        while (j > 0 && before(dist, index, m_out[j - 1])) {
            m_out[j] = m_out[j - 1];
            --j;
        }
        m_out[j] = {index, dist};
        return true;
    }

private:
    const Photon* m_photons;
    Vec3 m_x;
    int m_k, m_n = 0;
    float m_bound;
    const PhotonFilter& m_filter;
    PhotonNeighbor* m_out;
    uint32_t m_base = 0;
};

/// nanoflann result set of every accepted photon within the radius.
class WithinSet {
public:
    using DistanceType = float;
    using IndexType = uint16_t;

    WithinSet(const Photon* photons, const Vec3& x, float max_dist2, const PhotonFilter& filter,
              std::vector<PhotonNeighbor>& out)
        : m_photons(photons), m_x(x), m_bound(std::nextafter(max_dist2, k_inf)), m_filter(filter), m_out(out) {}
    void set_base(uint32_t base) { m_base = base; }
    float worstDist() const { return m_bound; }
    bool full() const { return true; }
    bool addPoint(float d2, uint16_t local) {
        const uint32_t index = m_base + local;
        const float dist = m_filter.metric(m_photons[index], m_x, d2);
        if (dist < m_bound) m_out.push_back({index, dist});
        return true;
    }

private:
    const Photon* m_photons;
    Vec3 m_x;
    float m_bound;
    const PhotonFilter& m_filter;
    std::vector<PhotonNeighbor>& m_out;
    uint32_t m_base = 0;
};

/// Photon coordinate `Axis` (a template argument: the median split's comparisons do not branch on it).
template <int Axis>
float coordinate(const Photon& p) {
    return Axis == 0 ? p.x : Axis == 1 ? p.y : p.z;
}

/// Reorders [begin, end) so that mid holds the photon of median coordinate on `axis`, smaller ones before it.
void median_split(Photon* begin, Photon* mid, Photon* end, int axis) {
    auto split = [&](auto less) { std::nth_element(begin, mid, end, less); };
    if (axis == 0)
        split([](const Photon& a, const Photon& b) { return coordinate<0>(a) < coordinate<0>(b); });
    else if (axis == 1)
        split([](const Photon& a, const Photon& b) { return coordinate<1>(a) < coordinate<1>(b); });
    else
        split([](const Photon& a, const Photon& b) { return coordinate<2>(a) < coordinate<2>(b); });
}

}  // namespace

struct PhotonMap::Forest {
    struct Node {
        float lo[3], hi[3];
        int32_t child[2] = {-1, -1};
        int32_t cell = -1;  // a leaf: the cell it holds
        uint32_t begin = 0, end = 0;
    };
    struct Cell {
        CellCloud cloud;
        uint32_t begin = 0;
        std::unique_ptr<CellTree> tree;
    };
    std::vector<Node> nodes;  // nodes[0] is the root
    std::vector<Cell> cells;

    /// Squared distance from x to node n's bounds (0 inside), rounded so that it never exceeds a photon's.
    float box_dist2(const Node& n, const Vec3& x) const {
        const float p[3] = {x.x, x.y, x.z};
        float d2 = 0.f;
        for (int a = 0; a < 3; ++a) {
            const float d = p[a] < n.lo[a] ? n.lo[a] - p[a] : p[a] > n.hi[a] ? p[a] - n.hi[a] : 0.f;
            d2 += d * d;
        }
        return d2;
    }

    template <class Set>
    void search(Set& set, const Vec3& x) const {
        if (nodes.empty()) return;
        const float q[3] = {x.x, x.y, x.z};
        int32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes[size_t(stack[--top])];
            if (box_dist2(n, x) > set.worstDist()) continue;
            if (n.cell >= 0) {
                const Cell& c = cells[size_t(n.cell)];
                set.set_base(c.begin);
                c.tree->findNeighbors(set, q, nanoflann::SearchParams());
                continue;
            }
            // Nearest child last on the stack, so it is searched first.
            const Node& a = nodes[size_t(n.child[0])];
            const Node& b = nodes[size_t(n.child[1])];
            const bool a_first = box_dist2(a, x) <= box_dist2(b, x);
            stack[top++] = a_first ? n.child[1] : n.child[0];
            stack[top++] = a_first ? n.child[0] : n.child[1];
        }
    }
};

PhotonMap::PhotonMap() = default;
PhotonMap::~PhotonMap() = default;
PhotonMap::PhotonMap(PhotonMap&&) noexcept = default;
PhotonMap& PhotonMap::operator=(PhotonMap&&) noexcept = default;

namespace {

/// The bounds of n photons: one unaligned 4-float load per photon (x, y, z and the flux bits, whose lane is
/// dropped), min and max in SSE lanes.
void bounds_of(const Photon* p, size_t n, float lo[3], float hi[3]) {
    __m128 l = _mm_set1_ps(k_inf), h = _mm_set1_ps(-k_inf);
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) {
        const __m128 c = _mm_loadu_ps(reinterpret_cast<const float*>(bytes + i * sizeof(Photon)));
        l = _mm_min_ps(l, c);
        h = _mm_max_ps(h, c);
    }
    alignas(16) float lv[4], hv[4];
    _mm_store_ps(lv, l);
    _mm_store_ps(hv, h);
    for (int a = 0; a < 3; ++a) {
        lo[a] = lv[a];
        hi[a] = hv[a];
    }
}

}  // namespace

void PhotonMap::build(std::vector<Photon> photons, int threads, StageProgress* stage, const CancelToken* cancel) {
    m_forest.reset();
    m_photons = std::move(photons);
    m_photons.shrink_to_fit();  // a shot grows by appending batches: up to twice its size in capacity
    if (m_photons.size() >= size_t(std::numeric_limits<uint32_t>::max()))
        throw InvalidParameter("a photon map holds fewer than 2^32 photons");
    auto forest = std::make_unique<Forest>();
    const size_t n = m_photons.size();
    const double total = 2.0 * double(n);  // the splits count for one half of the stage, the cells' trees for the other
    if (stage) stage->set_done(0);
    if (n == 0) {
        m_forest = std::move(forest);
        return;
    }
    auto cancelled = [&] { return cancel && cancel->cancelled(); };

    // The splits, level by level: every range of a level is split in parallel (median on its widest axis).
    Forest::Node root;
    root.begin = 0;
    root.end = uint32_t(n);
    bounds_of(m_photons.data(), n, root.lo, root.hi);
    forest->nodes.push_back(root);
    std::vector<int32_t> level = {0};
    int depth = 0, levels = 1;
    for (size_t m = n; m > k_cell_photons; m = (m + 1) / 2) ++levels;
    while (!level.empty()) {
        std::vector<int32_t> to_split;
        for (int32_t i : level) {
            const Forest::Node& nd = forest->nodes[size_t(i)];
            if (nd.end - nd.begin > k_cell_photons) to_split.push_back(i);
        }
        if (to_split.empty()) break;
        // Children are appended in order: node ids depend on the photons only.
        const size_t first_child = forest->nodes.size();
        forest->nodes.resize(first_child + 2 * to_split.size());
        parallel_for(
            threads, to_split.size(),
            [&](size_t j) {
                Forest::Node& nd = forest->nodes[size_t(to_split[j])];
                int axis = 0;
                for (int a = 1; a < 3; ++a)
                    if (nd.hi[a] - nd.lo[a] > nd.hi[axis] - nd.lo[axis]) axis = a;
                const uint32_t mid = nd.begin + (nd.end - nd.begin) / 2;
                Photon* base = m_photons.data();
                median_split(base + nd.begin, base + mid, base + nd.end, axis);
                const int32_t l = int32_t(first_child + 2 * j), r = l + 1;
                Forest::Node& left = forest->nodes[size_t(l)];
                Forest::Node& right = forest->nodes[size_t(r)];
                left.begin = nd.begin;
                left.end = mid;
                right.begin = mid;
                right.end = nd.end;
                bounds_of(base + left.begin, left.end - left.begin, left.lo, left.hi);
                bounds_of(base + right.begin, right.end - right.begin, right.lo, right.hi);
                nd.child[0] = l;
                nd.child[1] = r;
            },
            cancel);
        if (cancelled()) throw Cancelled();
        ++depth;
        if (stage) stage->set_done(int64_t(total * 0.5 * std::min(1.0, double(depth) / double(levels))));
        level.clear();
        for (size_t i = first_child; i < forest->nodes.size(); ++i) level.push_back(int32_t(i));
    }

    // The cells: every leaf of the splits, each with its own nanoflann tree, built in parallel.
    for (size_t i = 0; i < forest->nodes.size(); ++i) {
        Forest::Node& nd = forest->nodes[i];
        if (nd.child[0] >= 0) continue;
        nd.cell = int32_t(forest->cells.size());
        Forest::Cell c;
        c.begin = nd.begin;
        c.cloud.photons = m_photons.data() + nd.begin;
        c.cloud.count = nd.end - nd.begin;
        forest->cells.push_back(std::move(c));
    }
    std::atomic<int64_t> built{0};
    parallel_for(
        threads, forest->cells.size(),
        [&](size_t j) {
            Forest::Cell& c = forest->cells[j];
            c.tree = std::make_unique<CellTree>(3, c.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(k_leaf_photons));
            const int64_t done = built.fetch_add(int64_t(c.cloud.count)) + int64_t(c.cloud.count);
            if (stage) stage->set_done(int64_t(total * 0.5) + done);
        },
        cancel);
    if (cancelled()) throw Cancelled();
    m_forest = std::move(forest);
}

size_t PhotonMap::cells() const { return m_forest ? m_forest->cells.size() : 0; }

double PhotonMap::memory_bytes() const {
    double bytes = double(m_photons.capacity()) * double(sizeof(Photon));
    if (!m_forest) return bytes;
    bytes += double(m_forest->nodes.capacity()) * double(sizeof(Forest::Node));
    for (const Forest::Cell& c : m_forest->cells) {
        bytes += double(sizeof(Forest::Cell));
        if (!c.tree) continue;
        bytes += double(sizeof(CellTree)) + double(c.tree->vAcc.capacity()) * sizeof(uint16_t) +
                 double(c.tree->pool.usedMemory) + double(c.tree->pool.wastedMemory);
    }
    return bytes;
}

int PhotonMap::nearest(const Vec3& x, int k, float max_dist2, const PhotonFilter& filter, PhotonNeighbor* out) const {
    if (k < 1 || !m_forest) return 0;
    NearestSet set(m_photons.data(), x, k, max_dist2, filter, out);
    m_forest->search(set, x);
    return set.size();
}

void PhotonMap::within(const Vec3& x, float max_dist2, const PhotonFilter& filter,
                       std::vector<PhotonNeighbor>& out) const {
    out.clear();
    if (!m_forest) return;
    WithinSet set(m_photons.data(), x, max_dist2, filter, out);
    m_forest->search(set, x);
    std::sort(out.begin(), out.end(), [](const PhotonNeighbor& a, const PhotonNeighbor& b) {
        return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
    });
}

}  // namespace candela
