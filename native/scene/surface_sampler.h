// Sampling a point on all the scene's surfaces by area, for the course's surface-sampling path generator (a point
// on a light and a point on any surface, joined by two visibility checks). Instances included; Blender's area
// lights are lights, not surfaces, and are not part of it.
//
// Two levels. A distribution over the top-level objects (flattened meshes and instances) by world area, then, per
// mesh, over its triangles by area, and a uniform point in the triangle. A flattened mesh's triangles are in world
// space, so its points are uniform over it. An instanced mesh keeps one table of object-space areas shared by all
// its instances (memory stays one mesh's), so a point on triangle t of object i has the density
//     pdf = P(i) · (A_obj(t)/A_obj(mesh)) / A_world(t),
// exact for any transform; it is uniform (1/total_area) when every instance is a rotation, mirror or uniform scale,
// and near-uniform under a non-uniform scale (each triangle's world area scales by the cofactor of its normal).
// P(i) is proportional to the object's world area: exact for a flattened mesh; for an instance the bound
//     A_world ≤ ½·√(Σ|n_t| · tr(CᵀC·Σ n_t n_tᵀ/|n_t|))      (n_t = object-space (v1 − v0) × (v2 − v0), C the cofactor
// matrix of the transform: |C n_t| is the world |n_t|; Cauchy–Schwarz), equal to the true area when |C n̂| is the
// same for all normals (similarity transforms, planar meshes), from a 3 × 3 moment per mesh: O(1) per instance.
//
// Objects visible to no camera, diffuse, glossy or transmission ray (at most to shadow rays) are left out: no path
// has a vertex on them. Zero-area triangles are never drawn. Selection uses one float (u_select) for the object
// and, rescaled, the triangle: with float's 24 bits a triangle's probability is its pmf to within ~2⁻²⁴ absolute,
// exact for practical purposes below ~10⁵ triangles of similar size and a few per cent off per triangle (not on
// average over neighbours) for meshes of millions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "sampling/distribution_1d.h"
#include "scene/scene.h"

namespace candela {

struct SurfaceSample {
    SurfaceHit hit;        // filled as Scene::intersect would (t = 0): Scene::shade works on it
    float pdf_area = 0.f;  // area density (world units⁻²); 0: the scene has no surface to sample
};

/// Reads the scene's Embree buffers: it must not outlive the scene. sample() and pdf() are const and thread-safe.
class SurfaceSampler {
public:
    /// Builds the tables (O(triangles), on the calling thread); throws Cancelled if `cancel` fires.
    explicit SurfaceSampler(const Scene& scene, const CancelToken* cancel = nullptr);

    /// A point from u_select (object and triangle) and u (the point in the triangle), all uniform in [0, 1).
    /// Returns pdf_area = 0 and no hit when total_area() is 0.
    SurfaceSample sample(float u_select, Vec2 u) const;
    /// The area density sample() draws that point with (0 on objects left out and zero-area triangles).
    float pdf(const SurfaceHit& hit) const;
    /// Σ of the objects' world areas sample() weighs them by (exact unless an instance has a non-uniform scale:
    /// then its bound above).
    double total_area() const { return m_total_area; }
    /// Memory the tables take.
    size_t bytes() const;
    /// bytes() predicted before the scene is built, from the unique (not instanced) triangle count and the objects.
    static double estimate_bytes(double unique_triangles, double objects);

private:
    struct Table {  // one per Embree triangle geometry: a flattened mesh, or a mesh shared by instances
        Distribution1D triangles;
        double area = 0.0;      // Σ areas in the table's space
        double moment[6] = {};  // Σ n nᵀ/|n| (xx, yy, zz, xy, xz, yz), instanced meshes only
    };
    struct Object {
        ObjectTriangles triangles;
        uint32_t table = 0;
        bool moves = false;  // a moving instance (motion blur): its transform is read at the thread's shutter time
    };
    /// World-space area of triangle `prim` of object `object`.
    float world_area(const Object& o, uint32_t prim) const;
    float pdf_of(uint32_t object, uint32_t prim) const;

    const Scene& m_scene;
    std::vector<Object> m_objects;  // per top-level object
    std::vector<Table> m_tables;
    Distribution1D m_object_dist;
    double m_total_area = 0.0;
};

}  // namespace candela
