// Which objects of a scene have a face lying in the plane of another object's face and overlapping it (a decal
// on a wall, an emissive quad on a ceiling, two coplanar quads): only those need Scene's coplanar tie-break, every
// other hit can take Embree's closest distance as it is. Found at scene build in O(n log n): faces are grouped by
// their quantised normal (a hash key), sorted by plane offset within a group, and only faces of different objects
// whose plane intervals chain and whose boxes overlap are compared exactly (plane distance and a 2-D
// separating-axis test in the plane).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "core/transform.h"

namespace candela {

/// Tie tolerance of coplanar hits in Scene's filter, per unit of coordinate magnitude: two hits whose planes lie
/// closer than k_coplanar_ulps·M (M the largest magnitude involved: ray origin, hit distance, the object's
/// coordinates) are a tie. Embree's hit distance comes from dot(v0 − o, Ng)/dot(d, Ng) in float, whose rounding is
/// a few ulps of M; two triangles lying in one plane (or in planes rotated and rounded to float from one plane)
/// therefore differ by ~ε·M in plane distance. 32ε·M (2e-6 M) leaves a wide margin over that and is still ~15×
/// below a gap of 1e-4 of the scene's size seen from inside the scene (M ≈ 3 sizes there).
constexpr float k_coplanar_ulps = 32.f * 0x1p-24f;

/// Plane distance, per unit of the scene's magnitude S (largest |coordinate| in camera-world space), within which
/// faces count as coplanar for detection. The filter's tie tolerance is k_coplanar_ulps·(|o| + t·|d| + mag) with a
/// ray origin |o|∞ ≤ S, a path between two scene points t·|d| ≤ 2√3·S (the diagonal of the [−S, S]³ box) and an
/// object magnitude ≤ S: at most k_coplanar_ulps·(2 + 2√3)·S = 1.04e-5·S. Twice that, so every pair the filter
/// could call a tie is detected.
constexpr double k_coplanar_detect_distance = 2.0 * double(k_coplanar_ulps) * (2.0 + 2.0 * 1.7320508075688772);
/// Normals (unit, per component) within this of each other, on top of what float rounding of the vertices
/// allows for the face's size, count as parallel.
constexpr double k_coplanar_detect_normal = 1e-4;

struct CoplanarObject {
    uint32_t tri_begin = 0, tri_end = 0;  // its rows of the triangle index array
    Affine to_world;                      // object → camera-world space
};

struct CoplanarReport {
    std::vector<uint8_t> flagged;  // per object: 1 if a face of it overlaps a coplanar face of another object
    bool fallback = false;         // more faces than max_triangles: every object flagged without looking
    size_t triangles = 0;          // faces examined (instanced faces once per instance)
    size_t exact_tests = 0;        // face pairs compared exactly
};

/// Flags the objects with a coplanar overlapping rival in another object (world space: instances are
/// transformed). Faces of one object never count against each other. Faces whose normal float rounding leaves
/// undefined to 1 % (smaller than ~5e-5 of the scene's magnitude across: a fraction of a pixel) are left out.
/// When the objects hold more than max_triangles faces in all, or the comparisons exceed a fixed budget, the
/// answer errs on the safe side: objects are flagged without the exact test. Throws Cancelled once `cancel`
/// is cancelled (checked every 65,536 faces).
CoplanarReport find_coplanar_rivals(const float* positions, const uint32_t* triangles,
                                    const std::vector<CoplanarObject>& objects, size_t max_triangles = size_t(1) << 22,
                                    const CancelToken* cancel = nullptr);

}  // namespace candela
