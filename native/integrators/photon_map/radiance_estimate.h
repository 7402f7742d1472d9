// The photon map's radiance estimate (Jensen 2001, eq. 7.6; docs/photon-mapping.md, "Lookup"): the radiance
// leaving x toward w_c through the estimated lobes E of its BSDF,
//     L(x, w_c) ≈ Σ_p f_E(w_c, w_p) · a(w_c, w_p) · Φ_p · K(d_p) / N_emitted,
// over the k nearest accepted photons within the maximum radius (r the k-th distance, or the maximum radius if
// fewer were found), K the kernel normalised on the disc of radius r (density_kernel.h), Φ_p the photon's flux
// per emitted path and a Veach's adjoint factor |w_p·n|/|w_p·ng| (a photon's flux crossed the surface with the
// geometric cosine; the rendering equation at x takes the shading one: common/vertex_bsdf.h). The lookup uses
// Jensen's disc (PhotonFilter): the search sphere flattened to a quarter of its radius across the surface, and for
// a surface that does not transmit only photons that arrived from the side w_c looks from.
#pragma once

#include <vector>

#include "integrators/common/vertex_bsdf.h"
#include "integrators/photon_map/density_kernel.h"
#include "integrators/photon_map/photon_map.h"

namespace candela {

/// 1/t² − 1 for Jensen's disc of half-thickness t·r, t = 1/4.
inline constexpr float k_disc_flatten = 15.f;

struct DensityLookup {
    int k = 50;
    float max_radius = 1.f;
    DensityKernel kernel = DensityKernel::Cone;
};

/// The filter of a lookup at `hit` seen from w_c (whose BSDF `vb` uses).
inline PhotonFilter lookup_filter(const VertexBsdf& vb, const Vec3& w_c) {
    const SurfaceHit& hit = vb.hit();
    PhotonFilter f;
    f.normal = dot(w_c, hit.ng) < 0.f ? -hit.ng : hit.ng;
    f.flatten = k_disc_flatten;
    f.front_only = !(vb.shading(w_c).bsdf().flags() & k_bsdf_transmission);
    return f;
}

/// L(x, w_c) through `vb`'s lobes (the vertex is built with the estimated subset) from `map`; `scratch` holds at
/// least lookup.k neighbours.
inline Color radiance_estimate(const PhotonMap& map, const VertexBsdf& vb, const Vec3& w_c, const DensityLookup& lookup,
                               std::vector<PhotonNeighbor>& scratch) {
    if (map.empty() || !(map.emitted_paths > 0.0)) return Color(0.f);
    if (scratch.size() < size_t(lookup.k)) scratch.resize(size_t(lookup.k));
    const PhotonFilter filter = lookup_filter(vb, w_c);
    const float max2 = lookup.max_radius * lookup.max_radius;
    const int n = map.nearest(vb.hit().p, lookup.k, max2, filter, scratch.data());
    if (n == 0) return Color(0.f);
    const float r2 = n == lookup.k ? scratch[size_t(n) - 1].dist2 : max2;
    if (!(r2 > 0.f)) return Color(0.f);
    Color sum(0.f);
    // With k found, the k-th photon only sets the radius: given r, the other k − 1 are distributed over the disc
    // like the photons' density, so the estimate is unbiased for a uniform density (counting the k-th, the box
    // kernel's estimate k/(πr²) would be 1/(k − 1) too high; the cone and Gaussian weigh it 0 anyway).
    const int used = n == lookup.k && n > 1 ? n - 1 : n;
    for (int i = 0; i < used; ++i) {
        const Photon& p = map[scratch[size_t(i)].index];
        const Vec3 w_p = decode_direction(p.dir);
        const float w = kernel_weight(lookup.kernel, scratch[size_t(i)].dist2 / r2);
        if (!(w > 0.f)) continue;
        sum += vb.f(w_c, w_p) * (vb.adjoint_factor(w_c, w_p) * w) * map.flux(p);
    }
    return sum * float(1.0 / (double(k_pi) * double(r2) * map.emitted_paths));
}

}  // namespace candela
