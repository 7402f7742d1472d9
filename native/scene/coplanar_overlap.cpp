#include "scene/coplanar_overlap.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace candela {
namespace {

using D3 = std::array<double, 3>;

D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const D3& a) { return std::sqrt(dot(a, a)); }
double max_abs(const D3& a) { return std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])}); }

constexpr double k_eps = 0x1p-24;
constexpr double k_sqrt3 = 1.7320508075688772;
/// Hash cell of a unit normal's component. Faces whose normal uncertainty exceeds k_normal_cap are left out, so a
/// face's interval n ± uncertainty spans at most two cells per component (2·0.01 < 0.04).
constexpr double k_normal_cell = 0.04;
constexpr double k_normal_cap = 0.01;
/// Shifts the cells so the common components 0, ±1/2, ±1/√2, ±√3/2, ±1 lie well inside one.
constexpr double k_cell_shift = 0.37 * k_normal_cell;
/// Box comparisons and face scans before the search stops looking and flags overlapping objects outright.
constexpr size_t k_budget = 30'000'000;

D3 world_point(const float* p, const Affine& xf) {
    D3 out;
    for (int r = 0; r < 3; ++r)
        out[r] = double(xf.m[r][0]) * p[0] + double(xf.m[r][1]) * p[1] + double(xf.m[r][2]) * p[2] + double(xf.m[r][3]);
    return out;
}

struct Face {
    D3 v[3];
    D3 n;              // unit normal
    double area2 = 0;  // |e1 × e2|
    double tn = 0;     // how far (per component) float rounding may have turned n, plus the allowance
    bool ok = false;
};

Face make_face(const float* positions, const uint32_t* triangles, const CoplanarObject& o, uint32_t t) {
    Face f;
    double mag = 0.0;
    for (int k = 0; k < 3; ++k) {
        f.v[k] = world_point(positions + 3 * size_t(triangles[3 * size_t(t) + k]), o.to_world);
        mag = std::max(mag, max_abs(f.v[k]));
    }
    const D3 e1 = sub(f.v[1], f.v[0]), e2 = sub(f.v[2], f.v[0]);
    const D3 c = cross(e1, e2);
    const double len = norm(c);
    if (!(len > 0.0) || !std::isfinite(len) || !std::isfinite(mag)) return f;
    f.n = {c[0] / len, c[1] / len, c[2] / len};
    f.area2 = len;
    // The renderer sees the vertices in float: each coordinate off by up to ~2ε·mag (the input's rounding and the
    // transform's), each edge by ≤ 4√3·ε·mag, the cross product by ≤ 4√3·ε·mag·(|e1| + |e2|), which turns the unit
    // normal by at most that over |e1 × e2|. Twice that bound (8√3 < 16), plus the detection's allowance.
    f.tn = k_coplanar_detect_normal + 16.0 * k_eps * mag * (norm(e1) + norm(e2)) / len;
    f.ok = f.tn <= k_normal_cap;
    return f;
}

/// One face under one normal cell: the hash key, the face, and the interval its plane offset d = n·x may take.
struct Entry {
    uint32_t key, object, tri;
    float d_lo, d_hi;
};

struct Item {
    Face f;
    D3 lo, hi;  // box, padded by the distance tolerance
    bool ready = false;
};

struct Box {
    D3 lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity()};
    D3 hi = {-lo[0], -lo[1], -lo[2]};
};

bool boxes_overlap(const D3& alo, const D3& ahi, const D3& blo, const D3& bhi) {
    for (int a = 0; a < 3; ++a)
        if (alo[a] > bhi[a] || blo[a] > ahi[a]) return false;
    return true;
}

/// A face of one side of an object pair, in the sweep along x.
struct Ref {
    double lo_x;
    const Item* item;
    bool side;
};

class Search {
public:
    Search(const float* positions, const uint32_t* triangles, const std::vector<CoplanarObject>& objects,
           CoplanarReport* report, const CancelToken* cancel)
        : m_positions(positions), m_triangles(triangles), m_objects(objects), m_report(report), m_cancel(cancel) {}

    void run() {
        collect();
        check_cancel();
        if (!(m_td > 0.0)) return;
        std::sort(m_entries.begin(), m_entries.end(),
                  [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.d_lo < b.d_lo; });
        // Within one normal cell, faces whose offset intervals chain form a cluster; only clusters holding two
        // objects or more are looked at further.
        const size_t n = m_entries.size();
        for (size_t c0 = 0; c0 < n;) {
            size_t c1 = c0 + 1;
            float hi = m_entries[c0].d_hi;
            bool several = false;
            while (c1 < n && m_entries[c1].key == m_entries[c0].key && m_entries[c1].d_lo <= hi) {
                hi = std::max(hi, m_entries[c1].d_hi);
                several |= m_entries[c1].object != m_entries[c0].object;
                ++c1;
            }
            if (several) cluster(c0, c1);
            c0 = c1;
        }
    }

private:
    void collect() {
        // A face and its coplanar rival must land in a common cell under one orientation: the sign is fixed by a
        // generic direction g, and faces nearly perpendicular to g (where rounding could flip the sign of n·g for
        // one face and not its rival: |n·g − n'·g| ≤ √3·(tn + tn') ≤ 2√3·k_normal_cap) go in under both signs.
        const D3 g = {0.5377, 0.7031, 0.4652};
        const double flip_band = 2.0 * k_sqrt3 * k_normal_cap * norm(g);
        m_entries.reserve(size_t(double(m_report->triangles) * 1.2));
        m_boxes.assign(m_objects.size(), Box{});
        double scene_magnitude = 0.0;
        for (uint32_t i = 0; i < m_objects.size(); ++i) {
            const CoplanarObject& o = m_objects[i];
            Box& box = m_boxes[i];
            for (uint32_t t = o.tri_begin; t < o.tri_end; ++t) {
                if ((t & 0xFFFFu) == 0) check_cancel();  // ~10 ms of work between checks
                const Face f = make_face(m_positions, m_triangles, o, t);
                if (!f.ok) continue;
                for (int k = 0; k < 3; ++k)
                    for (int a = 0; a < 3; ++a) {
                        box.lo[a] = std::min(box.lo[a], f.v[k][a]);
                        box.hi[a] = std::max(box.hi[a], f.v[k][a]);
                        scene_magnitude = std::max(scene_magnitude, std::fabs(f.v[k][a]));
                    }
                const double s = dot(f.n, g);
                if (s >= -flip_band) add(f, i, t, 1.0);
                if (s <= flip_band) add(f, i, t, -1.0);
            }
        }
        // The scene's magnitude is known only now: widen every offset interval by the distance tolerance, outward
        // in float.
        m_td = k_coplanar_detect_distance * scene_magnitude;
        // Normal cells holding faces of one object only can hold no rival pair: drop them before sorting (on a
        // large mesh most cells are its own).
        m_entries.erase(std::remove_if(m_entries.begin(), m_entries.end(),
                                       [&](const Entry& e) { return m_cell_object[cell_index(e.key)] != k_several; }),
                        m_entries.end());
        for (Entry& e : m_entries) {
            const double d = e.d_lo, r = double(e.d_hi) + m_td;
            e.d_lo = std::nextafter(float(d - r), -std::numeric_limits<float>::infinity());
            e.d_hi = std::nextafter(float(d + r), std::numeric_limits<float>::infinity());
        }
        for (Box& b : m_boxes)
            for (int a = 0; a < 3; ++a) {
                b.lo[a] -= m_td;
                b.hi[a] += m_td;
            }
    }

    /// Adds the face's entries; d_lo holds the plane offset and d_hi its uncertainty from the normal (the distance
    /// tolerance is added once the scene's magnitude is known).
    void add(const Face& f, uint32_t object, uint32_t tri, double sign) {
        const D3 n = {sign * f.n[0], sign * f.n[1], sign * f.n[2]};
        const D3 c = {(f.v[0][0] + f.v[1][0] + f.v[2][0]) / 3.0, (f.v[0][1] + f.v[1][1] + f.v[2][1]) / 3.0,
                      (f.v[0][2] + f.v[1][2] + f.v[2][2]) / 3.0};
        // d = n·c is off the common plane's offset by the centroid's distance from it (≤ the distance tolerance) and
        // by the normal's error (≤ √3·tn in length) times the lever arm |c| (rounded up by 1e-6 for float).
        const float d = float(dot(n, c)), r = float((k_sqrt3 * f.tn * norm(c)) * (1.0 + 1e-6) + 1e-6 * std::fabs(d));
        int cell_lo[3], cell_hi[3];
        for (int a = 0; a < 3; ++a) {
            cell_lo[a] = int(std::floor((n[a] - f.tn + 1.0 + k_cell_shift) / k_normal_cell));
            cell_hi[a] = int(std::floor((n[a] + f.tn + 1.0 + k_cell_shift) / k_normal_cell));
        }
        for (int x = cell_lo[0]; x <= cell_hi[0]; ++x)
            for (int y = cell_lo[1]; y <= cell_hi[1]; ++y)
                for (int z = cell_lo[2]; z <= cell_hi[2]; ++z) {
                    const uint32_t key = uint32_t(x) | uint32_t(y) << 8 | uint32_t(z) << 16;
                    m_entries.push_back({key, object, tri, d, r});
                    int32_t& first = m_cell_object[cell_index(key)];
                    if (first == k_none)
                        first = int32_t(object);
                    else if (first != int32_t(object))
                        first = k_several;
                }
    }

    void cluster(size_t c0, size_t c1) {
        // By object (the offsets' order has done its job: a counting sort, keeping it within each object);
        // objects meet where their whole boxes overlap.
        m_slot.resize(m_objects.size(), -1);
        m_counts.clear();
        std::vector<uint32_t> present;
        for (size_t i = c0; i < c1; ++i) {
            int32_t& slot = m_slot[m_entries[i].object];
            if (slot < 0) {
                slot = int32_t(present.size());
                present.push_back(m_entries[i].object);
                m_counts.push_back(0);
            }
            ++m_counts[size_t(slot)];
        }
        size_t offset = 0;
        for (size_t& c : m_counts) offset += std::exchange(c, offset);
        m_scratch.resize(c1 - c0);
        for (size_t i = c0; i < c1; ++i) m_scratch[m_counts[size_t(m_slot[m_entries[i].object])]++] = m_entries[i];
        std::copy(m_scratch.begin(), m_scratch.end(), m_entries.begin() + c0);
        for (uint32_t o : present) m_slot[o] = -1;
        m_items.assign(c1 - c0, Item{});
        m_cluster = c0;
        struct Group {
            uint32_t object;
            size_t begin, end;  // rows of the cluster
        };
        std::vector<Group> groups;
        for (size_t i = c0; i < c1; ++i) {
            if (groups.empty() || groups.back().object != m_entries[i].object)
                groups.push_back({m_entries[i].object, i - c0, i - c0});
            groups.back().end = i - c0 + 1;
        }
        std::sort(groups.begin(), groups.end(),
                  [&](const Group& a, const Group& b) { return m_boxes[a.object].lo[0] < m_boxes[b.object].lo[0]; });
        for (size_t a = 0; a < groups.size(); ++a) {
            const Box& ba = m_boxes[groups[a].object];
            for (size_t b = a + 1; b < groups.size() && m_boxes[groups[b].object].lo[0] <= ba.hi[0]; ++b) {
                ++m_work;
                const Box& bb = m_boxes[groups[b].object];
                if (boxes_overlap(ba.lo, ba.hi, bb.lo, bb.hi))
                    pair(groups[a].object, groups[a].begin, groups[a].end, groups[b].object, groups[b].begin,
                         groups[b].end);
            }
        }
    }

    /// Row i of the current cluster with its face and padded box (computed on first use).
    const Item& item(size_t i) {
        Item& it = m_items[i];
        if (!it.ready) {
            const Entry& e = m_entries[m_cluster + i];
            it.f = make_face(m_positions, m_triangles, m_objects[e.object], e.tri);
            for (int a = 0; a < 3; ++a) {
                it.lo[a] = std::min({it.f.v[0][a], it.f.v[1][a], it.f.v[2][a]}) - m_td;
                it.hi[a] = std::max({it.f.v[0][a], it.f.v[1][a], it.f.v[2][a]}) + m_td;
            }
            it.ready = true;
        }
        return it;
    }

    void pair(uint32_t oa, size_t a0, size_t a1, uint32_t ob, size_t b0, size_t b1) {
        std::vector<uint8_t>& flagged = m_report->flagged;
        if (flagged[oa] && flagged[ob]) return;
        if (m_work > k_budget) {  // out of budget: the boxes overlap, assume the faces do
            flagged[oa] = flagged[ob] = 1;
            return;
        }
        // Each side's faces inside the other side's box, swept along x.
        const Box &ba = m_boxes[oa], &bb = m_boxes[ob];
        m_refs.clear();
        for (size_t i = a0; i < a1; ++i) {
            const Item& it = item(i);
            if (boxes_overlap(it.lo, it.hi, bb.lo, bb.hi)) m_refs.push_back({it.lo[0], &it, false});
        }
        for (size_t i = b0; i < b1; ++i) {
            const Item& it = item(i);
            if (boxes_overlap(it.lo, it.hi, ba.lo, ba.hi)) m_refs.push_back({it.lo[0], &it, true});
        }
        m_work += (a1 - a0) + (b1 - b0);
        std::sort(m_refs.begin(), m_refs.end(), [](const Ref& x, const Ref& y) { return x.lo_x < y.lo_x; });
        for (size_t i = 0; i < m_refs.size(); ++i) {
            const Item& x = *m_refs[i].item;
            for (size_t j = i + 1; j < m_refs.size() && m_refs[j].lo_x <= x.hi[0]; ++j) {
                ++m_work;
                if (m_refs[j].side == m_refs[i].side) continue;
                const Item& y = *m_refs[j].item;
                if (!boxes_overlap(x.lo, x.hi, y.lo, y.hi)) continue;
                ++m_report->exact_tests;
                if (coplanar_overlap(x.f, y.f)) {
                    flagged[oa] = flagged[ob] = 1;
                    return;
                }
            }
        }
    }

    /// Exact test: parallel within both faces' normal uncertainty, the smaller face within the distance tolerance
    /// of the larger's plane, and interiors overlapping by more than the tolerance in that plane (faces that only
    /// touch along an edge are no tie: a ray meets both only on the shared edge).
    bool coplanar_overlap(const Face& a, const Face& b) const {
        const Face& big = a.area2 >= b.area2 ? a : b;
        const Face& small = a.area2 >= b.area2 ? b : a;
        double same = 0.0, opposite = 0.0;
        for (int k = 0; k < 3; ++k) {
            same = std::max(same, std::fabs(big.n[k] - small.n[k]));
            opposite = std::max(opposite, std::fabs(big.n[k] + small.n[k]));
        }
        if (std::min(same, opposite) > big.tn + small.tn) return false;
        // 2·tolerance: the larger face's own vertices may each be a tolerance off the common plane.
        for (int k = 0; k < 3; ++k)
            if (std::fabs(dot(big.n, sub(small.v[k], big.v[0]))) > 2.0 * m_td) return false;
        // Separating axes in the plane, projected along the larger face's dominant normal axis (a projection
        // shrinks in-plane lengths by at most √3, so the overlap must exceed tolerance/√3 there).
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (std::fabs(big.n[k]) > std::fabs(big.n[axis])) axis = k;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const double tol = m_td / k_sqrt3;
        const Face* faces[2] = {&big, &small};
        for (const Face* f : faces)
            for (int k = 0; k < 3; ++k) {
                const D3& p = f->v[k];
                const D3& q = f->v[(k + 1) % 3];
                double px = -(q[v] - p[v]), py = q[u] - p[u];
                const double len = std::hypot(px, py);
                if (!(len > 0.0)) continue;
                px /= len;
                py /= len;
                double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
                double hi[2] = {-lo[0], -lo[1]};
                for (int s = 0; s < 2; ++s)
                    for (int m = 0; m < 3; ++m) {
                        const double w = faces[s]->v[m][u] * px + faces[s]->v[m][v] * py;
                        lo[s] = std::min(lo[s], w);
                        hi[s] = std::max(hi[s], w);
                    }
                if (hi[0] <= lo[1] + tol || hi[1] <= lo[0] + tol) return false;
            }
        return true;
    }

    const float* m_positions;
    const uint32_t* m_triangles;
    const std::vector<CoplanarObject>& m_objects;
    CoplanarReport* m_report;
    const CancelToken* m_cancel;
    void check_cancel() const {
        if (m_cancel && m_cancel->cancelled()) throw Cancelled();
    }
    double m_td = 0.0;  // distance tolerance
    size_t m_work = 0;
    std::vector<Entry> m_entries;
    /// Per normal cell: the one object with faces there, k_none, or k_several.
    static constexpr int32_t k_none = -1, k_several = -2;
    static constexpr int k_cells = int(2.0 / k_normal_cell) + 3;  // cell indices per component, 0 … k_cells − 1
    static size_t cell_index(uint32_t key) {
        return (key & 0xFFu) + k_cells * (((key >> 8) & 0xFFu) + k_cells * size_t(key >> 16));
    }
    std::vector<int32_t> m_cell_object = std::vector<int32_t>(size_t(k_cells) * k_cells * k_cells, k_none);
    std::vector<int32_t> m_slot;  // per object: its bucket in the current cluster's counting sort, or −1
    std::vector<size_t> m_counts;
    std::vector<Entry> m_scratch;
    std::vector<Item> m_items;  // the current cluster's rows
    size_t m_cluster = 0;       // its first entry
    std::vector<Box> m_boxes;   // per object, padded by the distance tolerance
    std::vector<Ref> m_refs;
};

}  // namespace

CoplanarReport find_coplanar_rivals(const float* positions, const uint32_t* triangles,
                                    const std::vector<CoplanarObject>& objects, size_t max_triangles,
                                    const CancelToken* cancel) {
    CoplanarReport report;
    report.flagged.assign(objects.size(), 0);
    size_t nonempty = 0;
    for (const CoplanarObject& o : objects) {
        report.triangles += o.tri_end - o.tri_begin;
        nonempty += o.tri_end > o.tri_begin;
    }
    if (nonempty < 2) return report;
    if (report.triangles > max_triangles) {
        report.fallback = true;
        for (size_t i = 0; i < objects.size(); ++i) report.flagged[i] = objects[i].tri_end > objects[i].tri_begin;
        return report;
    }
    Search(positions, triangles, objects, &report, cancel).run();
    return report;
}

}  // namespace candela
