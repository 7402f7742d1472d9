// Sampling a point on all the scene's surfaces by area: the tables and the density (surface_sampler.h derives it).
#include "scene/surface_sampler.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "sampling/warp.h"

namespace candela {

namespace {

/// The ray types that make a path vertex: an object visible to none of them is never on a path.
constexpr uint8_t k_vertex_rays = k_ray_camera | k_ray_diffuse | k_ray_glossy | k_ray_transmission;

Vec3 vertex(const ObjectTriangles& t, uint32_t prim, int k) {
    const float* p = t.vertices + 3 * size_t(t.indices[3 * size_t(prim) + k]);
    return Vec3(p[0], p[1], p[2]);
}

/// (v1 − v0) × (v2 − v0) of triangle prim in the vertices' space: twice its area, along its normal.
Vec3 doubled_normal(const ObjectTriangles& t, uint32_t prim) {
    const Vec3 v0 = vertex(t, prim, 0);
    return cross(vertex(t, prim, 1) - v0, vertex(t, prim, 2) - v0);
}

}  // namespace

SurfaceSampler::SurfaceSampler(const Scene& scene, const CancelToken* cancel) : m_scene(scene) {
    const uint32_t n = scene.object_count();
    m_objects.resize(n);
    m_tables.reserve(n);              // at most one table per object
    std::vector<int32_t> mesh_table;  // instanced meshes: their shared table, by input mesh
    std::vector<float> object_weight(n, 0.f);
    size_t since_check = 0;
    auto poll = [&](size_t work) {
        since_check += work;
        if (since_check < (size_t(1) << 16)) return;
        since_check = 0;
        if (cancel && cancel->cancelled()) throw Cancelled();
    };
    for (uint32_t i = 0; i < n; ++i) {
        Object& o = m_objects[i];
        o.triangles = scene.object_triangles(i);
        o.moves = scene.object_moves(i);
        const ObjectTriangles& t = o.triangles;
        if ((t.flags & k_vertex_rays) == 0) continue;  // on no path: left out (weight 0, no table)
        if (t.instanced && t.mesh < mesh_table.size() && mesh_table[t.mesh] >= 0) {
            o.table = uint32_t(mesh_table[t.mesh]);
        } else {
            // A new table: areas in the vertices' space, and for a shared mesh the normals' moment.
            Table table;
            std::vector<float> areas(t.triangle_count);
            for (uint32_t prim = 0; prim < t.triangle_count; ++prim) {
                const Vec3 nt = doubled_normal(t, prim);
                const double len = length(nt);
                areas[prim] = float(0.5 * len);
                table.area += areas[prim];
                if (t.instanced && len > 0.0) {
                    const double x = nt.x, y = nt.y, z = nt.z;
                    const double m[6] = {x * x, y * y, z * z, x * y, x * z, y * z};
                    for (int k = 0; k < 6; ++k) table.moment[k] += m[k] / len;
                }
                poll(1);
            }
            if (!std::isfinite(table.area))
                throw InvalidScene("mesh " + std::to_string(t.mesh) + " has a surface area too large for float");
            table.triangles = Distribution1D(std::move(areas));
            o.table = uint32_t(m_tables.size());
            m_tables.push_back(std::move(table));
            if (t.instanced) {
                if (mesh_table.size() <= t.mesh) mesh_table.resize(t.mesh + 1, -1);
                mesh_table[t.mesh] = int32_t(o.table);
            }
        }
        const Table& table = m_tables[o.table];
        double area = table.area;
        if (t.instanced) {
            // ½·√(Σ|n| · tr(G·M)) with G = CᵀC, M = Σ n nᵀ/|n| (Σ|n| = 2·area): the bound of the header.
            const Affine c = t.object_to_world.normal_matrix();
            double g[3][3];
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) g[a][b] = double(dot(c.column(a), c.column(b)));
            const double* m = table.moment;
            const double trace = g[0][0] * m[0] + g[1][1] * m[1] + g[2][2] * m[2] +
                                 2.0 * (g[0][1] * m[3] + g[0][2] * m[4] + g[1][2] * m[5]);
            area = 0.5 * std::sqrt(std::max(2.0 * table.area * trace, 0.0));
        }
        if (!std::isfinite(area) || !(float(area) < 3e38f))
            throw InvalidScene("object " + std::to_string(i) + " has a surface area too large for float");
        object_weight[i] = float(area);
        m_total_area += area;
    }
    if (cancel && cancel->cancelled()) throw Cancelled();
    m_object_dist = Distribution1D(std::move(object_weight));
}

float SurfaceSampler::world_area(const Object& o, uint32_t prim) const {
    const ObjectTriangles& t = o.triangles;
    if (!t.instanced) return 0.5f * length(doubled_normal(t, prim));
    // At the thread's shutter time (a moving instance's transform then: sample() places the point there too), so
    // the density stays exact over the shutter; P(object) keeps the weights built at the shutter's middle.
    const Affine m = o.moves ? m_scene.object_to_world(uint32_t(&o - m_objects.data())) : t.object_to_world;
    const Vec3 v0 = m.point(vertex(t, prim, 0));
    return 0.5f * length(cross(m.point(vertex(t, prim, 1)) - v0, m.point(vertex(t, prim, 2)) - v0));
}

float SurfaceSampler::pdf_of(uint32_t object, uint32_t prim) const {
    const float p_object = m_object_dist.pmf(object);
    if (!(p_object > 0.f)) return 0.f;
    const Object& o = m_objects[object];
    const float p_triangle = m_tables[o.table].triangles.pmf(prim);
    const float area = world_area(o, prim);
    return p_triangle > 0.f && area > 0.f ? p_object * p_triangle / area : 0.f;
}

SurfaceSample SurfaceSampler::sample(float u_select, Vec2 u) const {
    SurfaceSample s;
    if (!(m_total_area > 0.0)) return s;
    float u_triangle = 0.f;
    const uint32_t object = uint32_t(m_object_dist.sample_discrete(u_select, nullptr, &u_triangle));
    const uint32_t prim = uint32_t(m_tables[m_objects[object].table].triangles.sample_discrete(u_triangle));
    const Vec2 b = sample_uniform_triangle(u);  // weights of corners 1 and 2
    s.hit = m_scene.surface_point(object, prim, b.x, b.y);
    s.pdf_area = pdf_of(object, prim);
    return s;
}

float SurfaceSampler::pdf(const SurfaceHit& hit) const {
    if (!(m_total_area > 0.0) || hit.object >= m_objects.size()) return 0.f;
    const uint32_t prim = hit.primitive.prim;
    if (prim >= m_objects[hit.object].triangles.triangle_count) return 0.f;
    return pdf_of(hit.object, prim);
}

size_t SurfaceSampler::bytes() const {
    size_t total = sizeof(*this) + m_objects.capacity() * sizeof(Object) + m_tables.capacity() * sizeof(Table) +
                   m_object_dist.bytes();
    for (const Table& t : m_tables) total += t.triangles.bytes();
    return total;
}

double SurfaceSampler::estimate_bytes(double unique_triangles, double objects) {
    // Per table entry: weight, cdf, pmf and (if some weight is 0) the zero-bin table, 4 bytes each; per object its
    // record, its weight's four entries and up to one table.
    return 16.0 * unique_triangles + (double(sizeof(Object)) + sizeof(Table) + 16.0) * objects + sizeof(SurfaceSampler);
}

}  // namespace candela
