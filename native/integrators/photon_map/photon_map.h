// The photon map: a kd-tree over stored photons with k-nearest and radius queries (Jensen 2001, ch. 6), built on
// Debian's nanoflann (a kd-tree with custom result sets: the normal check and the tie rule run inside its search).
//
// Build. nanoflann builds one tree on one thread without a way to stop it, so the map is a forest: a median split
// of the photons (on the axis of their widest extent, until a part holds at most k_cell_photons) partitions the
// space into cells, in parallel and with a cancel check at every split, and every cell gets its own nanoflann tree,
// the cells built in parallel as the stage's work items ("Building photon map" counts the photons of the cells
// done). A cancel is therefore seen within one cell's build (a few milliseconds). Within a cell photon indices are
// 16-bit, so the forest adds 2 bytes per photon of index and nanoflann's nodes (32 bytes per node, leaves of up to
// 32 photons: about 3 bytes per photon) to the photon's 18 (docs/photon-mapping.md, "Memory").
//
// Queries. A query walks the top-level splits nearest side first, pruning cells whose bounds lie beyond the current
// k-th distance, and searches each cell's tree with a shared result set, so the answer is the forest's k nearest.
// The result is exactly the brute-force one: photons ordered by (squared distance, index), distance ≤ the maximum
// inclusive, and ties at the k-th distance resolved toward the lower index (the result set sees candidates at
// distance equal to its current worst, which nanoflann's strict comparison would drop). Every query and build is a
// function of the photons alone, so the map and its answers are the same for every thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/parallel.h"
#include "core/vec.h"
#include "integrators/photon_map/photon.h"
#include "integrators/render_context.h"

namespace candela {

struct PhotonNeighbor {
    uint32_t index = 0;  // in the map (PhotonMap::operator[])
    float dist2 = 0.f;   // squared distance to the query point in the lookup's metric (PhotonFilter::metric)
};

/// The distance a lookup at x measures, and which photons it accepts (Jensen's disc: the search sphere compressed
/// along the surface normal n, so photons of other surfaces — the wall at a corner, the far side of a thin wall —
/// count less or not at all):
///     d_e² = d² + (1/t² − 1)·((p − x)·n)²,
/// the distance in a flattened ellipsoid of half-thickness t·r for radius r (t = 1, or a zero normal: the sphere).
/// On a flat surface d_e = d. For a surface that does not transmit, a photon must also have arrived from n's side.
struct PhotonFilter {
    Vec3 normal{0.f};     // unit, on the side the lookup looks from; zero: the sphere, no side check
    float flatten = 0.f;  // 1/t² − 1
    bool front_only = false;

    /// d_e² of photon p for a lookup at x whose Euclidean squared distance is d2; +∞ if it is not accepted.
    float metric(const Photon& p, const Vec3& x, float d2) const {
        if (normal.x == 0.f && normal.y == 0.f && normal.z == 0.f) return d2;
        if (front_only && !(dot(decode_direction(p.dir), normal) > 0.f)) return std::numeric_limits<float>::infinity();
        const float offset = dot(p.position() - x, normal);
        return d2 + flatten * (offset * offset);
    }
};

class PhotonMap {
public:
    /// Photons per cell of the forest at most (16-bit indices inside a cell).
    static constexpr size_t k_cell_photons = 32768;

    PhotonMap();
    ~PhotonMap();
    PhotonMap(PhotonMap&&) noexcept;
    PhotonMap& operator=(PhotonMap&&) noexcept;

    /// Builds the map over `photons` (reordered), on `threads` threads; `stage` (optional) counts the photons of the
    /// cells built. Throws Cancelled if `cancel` fires (the map is then empty).
    void build(std::vector<Photon> photons, int threads, StageProgress* stage, const CancelToken* cancel);

    size_t size() const { return m_photons.size(); }
    bool empty() const { return m_photons.empty(); }
    const Photon& operator[](size_t i) const { return m_photons[i]; }
    /// The photons' bytes plus the index's (nanoflann's index arrays and nodes, the cells, the splits).
    double memory_bytes() const;
    size_t cells() const;

    /// The k ≥ 1 nearest accepted photons within max_dist2 (inclusive) of x in the filter's metric d_e², ordered by
    /// (d_e², index), in out[0 .. n) (PhotonNeighbor::dist2 is d_e²); returns n ≤ k.
    int nearest(const Vec3& x, int k, float max_dist2, const PhotonFilter& filter, PhotonNeighbor* out) const;
    /// Every accepted photon with d_e² ≤ max_dist2, ordered by (d_e², index).
    void within(const Vec3& x, float max_dist2, const PhotonFilter& filter, std::vector<PhotonNeighbor>& out) const;

    // What the estimate needs besides the photons (set by the tracer that filled the map): the flux of a photon is
    // decode_flux(p.flux)·flux_scale, and the map estimates flux per emitted path: divide by emitted_paths.
    float flux_scale = 1.f;
    double emitted_paths = 0.0;

    Color flux(const Photon& p) const { return decode_flux(p.flux) * flux_scale; }

private:
    struct Forest;
    std::vector<Photon> m_photons;
    std::unique_ptr<Forest> m_forest;
};

}  // namespace candela
