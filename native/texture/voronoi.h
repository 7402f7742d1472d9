// Worley's cellular noise (Worley 1996, "A Cellular Texture Basis Function") as Cycles 3.4's Voronoi Texture
// defines it (docs/textures.md, "Voronoi"): one feature point per unit cell of the integer lattice at
// cell + randomness·hash(cell) (texture/hash.h), searched over the 3ⁿ cells around the query (5ⁿ for Smooth F1).
//   F1 / F2                 distance to the nearest / second nearest point, its cell's colour hash and position
//   SMOOTH_F1               a smooth minimum over the points (polynomial smooth min, width ½·smoothness)
//   DISTANCE_TO_EDGE        distance to the nearest bisector between the nearest point and another one
//   N_SPHERE_RADIUS         half the distance from the nearest point to its own nearest point
// Metrics EUCLIDEAN, MANHATTAN, CHEBYCHEV, MINKOWSKI (exponent); DISTANCE_TO_EDGE and N_SPHERE_RADIUS are
// Euclidean, and 1-D is |a − b| for all.
#pragma once

#include <cstdint>

#include "texture/hash.h"

namespace candela {

enum class VoronoiFeature : uint32_t { F1, F2, SmoothF1, DistanceToEdge, NSphereRadius };
enum class VoronoiMetric : uint32_t { Euclidean, Manhattan, Chebychev, Minkowski };

struct VoronoiParams {
    VoronoiFeature feature = VoronoiFeature::F1;
    VoronoiMetric metric = VoronoiMetric::Euclidean;
    float scale = 5.f, smoothness = 1.f, exponent = 0.5f, randomness = 1.f;
};

struct VoronoiResult {
    float distance = 0.f;
    Vec3 color{0.f};
    Vec4 position;  // up to 4 coordinates (unused ones 0), divided by the scale
    float radius = 0.f;
};

/// The Voronoi Texture at coordinates p (dims 1–4 of p are used; scaled here by params.scale).
VoronoiResult voronoi(int dims, const Vec4& p, const VoronoiParams& params);

}  // namespace candela
