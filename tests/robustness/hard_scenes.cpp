#include "hard_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"

namespace candela::test {

uint32_t ShadedBuilder::add_vertex(Vec3 p) {
    positions.insert(positions.end(), {p.x, p.y, p.z});
    return uint32_t(positions.size() / 3 - 1);
}

void ShadedBuilder::add_triangle(uint32_t a, uint32_t b, uint32_t c, uint32_t material, const Vec3* n) {
    triangles.insert(triangles.end(), {a, b, c});
    tri_material.push_back(material);
    // Triangles added through MeshBuilder's helpers before this one are flat.
    normals.resize(9 * (triangles.size() / 3 - 1), 0.f);
    smooth.resize(triangles.size() / 3 - 1, 0);
    for (int k = 0; k < 3; ++k) {
        const Vec3 v = n ? n[k] : Vec3(0.f);
        normals.insert(normals.end(), {v.x, v.y, v.z});
    }
    smooth.push_back(n ? 1 : 0);
}

uint32_t ShadedBuilder::add_quad(Vec3 p0, Vec3 e1, Vec3 e2, uint32_t material) {
    const uint32_t a = add_vertex(p0), b = add_vertex(p0 + e1), c = add_vertex(p0 + e1 + e2), d = add_vertex(p0 + e2);
    add_triangle(a, b, c, material);
    add_triangle(a, c, d, material);
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

uint32_t ShadedBuilder::add_box(Vec3 lo, Vec3 hi, uint32_t material, bool smooth_normals) {
    const Vec3 c = (lo + hi) * 0.5f;
    uint32_t v[8];
    Vec3 n[8];
    for (int i = 0; i < 8; ++i) {
        const Vec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        v[i] = add_vertex(p);
        n[i] = normalize(p - c);
    }
    // Faces as corner indices in counter-clockwise order seen from outside.
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces)
        for (const auto& t : {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}}) {
            const Vec3 tn[3] = {n[t[0]], n[t[1]], n[t[2]]};
            add_triangle(v[t[0]], v[t[1]], v[t[2]], material, smooth_normals ? tn : nullptr);
        }
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

uint32_t ShadedBuilder::add_smooth_sphere(float radius, int segments, int rings, uint32_t material) {
    const uint32_t base = uint32_t(positions.size() / 3);
    std::vector<Vec3> dirs;
    for (int r = 0; r <= rings; ++r) {
        const float theta = k_pi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.f * k_pi * s / segments;
            const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            dirs.push_back(d);
            add_vertex(d * radius);
        }
    }
    auto idx = [&](int r, int s) { return uint32_t(r * segments + (s % segments)); };
    auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
        const Vec3 n[3] = {dirs[a], dirs[b], dirs[c]};
        add_triangle(base + a, base + b, base + c, material, n);
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = idx(r, s), b = idx(r, s + 1), c = idx(r + 1, s), d = idx(r + 1, s + 1);
            if (r > 0) tri(a, c, b);
            if (r + 1 < rings) tri(b, c, d);
        }
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

uint32_t ShadedBuilder::add_smooth_cylinder(float radius, float z0, float z1, int segments, uint32_t material) {
    std::vector<uint32_t> bottom, top;
    std::vector<Vec3> radial;
    for (int s = 0; s < segments; ++s) {
        const float phi = 2.f * k_pi * s / segments;
        const Vec3 d(std::cos(phi), std::sin(phi), 0.f);
        radial.push_back(d);
        bottom.push_back(add_vertex(Vec3(d.x * radius, d.y * radius, z0)));
        top.push_back(add_vertex(Vec3(d.x * radius, d.y * radius, z1)));
    }
    const uint32_t cb = add_vertex(Vec3(0.f, 0.f, z0)), ct = add_vertex(Vec3(0.f, 0.f, z1));
    for (int s = 0; s < segments; ++s) {
        const int t = (s + 1) % segments;
        const Vec3 n0[3] = {radial[s], radial[t], radial[t]}, n1[3] = {radial[s], radial[t], radial[s]};
        add_triangle(bottom[s], bottom[t], top[t], material, n0);
        add_triangle(bottom[s], top[t], top[s], material, n1);
        add_triangle(cb, bottom[t], bottom[s], material);  // caps: flat, facing −z and +z
        add_triangle(ct, top[s], top[t], material);
    }
    mesh_tri_start.push_back(uint32_t(triangles.size() / 3));
    return uint32_t(mesh_tri_start.size() - 2);
}

void ShadedBuilder::add_area_light(Vec3 center, Vec3 u, Vec3 v, Vec3 dir, Color strength) {
    std::vector<float> row(20, 0.f);
    const float values[15] = {strength.x, strength.y, strength.z, center.x, center.y, center.z, dir.x, dir.y,
                              dir.z,      u.x,        u.y,        u.z,      v.x,      v.y,      v.z};
    std::copy(values, values + 15, row.begin());
    add_light(3, row);
}

SceneArrays ShadedBuilder::arrays(const float* camera_rows16) const {
    SceneArrays a = MeshBuilder::arrays(camera_rows16);
    const size_t T = triangles.size() / 3;
    std::vector<float> n = normals;
    std::vector<uint8_t> sm = smooth;
    n.resize(9 * T, 0.f);
    sm.resize(T, 0);
    a.set("normals", ElemType::F32, {T, 3, 3}, n.data());
    a.set("tri_smooth", ElemType::U8, {T}, sm.data());
    return a;
}

std::vector<float> scale_translate(Vec3 s, Vec3 o) {
    return {s.x, 0, 0, o.x, 0, s.y, 0, o.y, 0, 0, s.z, o.z, 0, 0, 0, 1};
}

double pixel_luminance(const RenderResult& r, size_t i) {
    return 0.2126 * r.rgba[4 * i] + 0.7152 * r.rgba[4 * i + 1] + 0.0722 * r.rgba[4 * i + 2];
}

size_t count_disagreeing_pixels(const RenderResult& a, const RenderResult& b, double k,
                                const std::vector<uint8_t>* mask) {
    size_t bad = 0;
    for (size_t i = 0; i < a.noise.size(); ++i) {
        if (mask && !(*mask)[i]) continue;
        const double la = pixel_luminance(a, i), lb = pixel_luminance(b, i);
        const double bound = k * std::hypot(double(a.noise[i]), double(b.noise[i])) + 1e-5 * std::max(la, lb);
        bad += !(std::fabs(la - lb) <= bound);
    }
    return bad;
}

size_t count_speckles(const RenderResult& r, const std::vector<uint8_t>& mask, double k) {
    size_t bad = 0;
    const int w = r.width, h = r.height;
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            const size_t i = size_t(y) * w + x;
            std::vector<double> nb;
            double sigma_n = 0.0;
            bool inside = mask[i] != 0;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const size_t j = size_t(y + dy) * w + (x + dx);
                    inside &= mask[j] != 0;
                    if (j == i) continue;
                    nb.push_back(pixel_luminance(r, j));
                    sigma_n = std::max(sigma_n, double(r.noise[j]));
                }
            if (!inside) continue;
            std::sort(nb.begin(), nb.end());
            const double median = 0.5 * (nb[3] + nb[4]);
            const double v = pixel_luminance(r, i);
            const double structure = 2.0 * (nb[6] - nb[1]);
            bad += !(std::fabs(v - median) <=
                     k * std::hypot(double(r.noise[i]), sigma_n) + structure + 1e-5 * std::fabs(median));
        }
    return bad;
}

std::vector<uint8_t> covered_interior(const RenderResult& t) {
    const int w = t.width, h = t.height;
    std::vector<uint8_t> m(size_t(w) * h, 0);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            bool all = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) all &= t.rgba[4 * (size_t(y + dy) * w + x + dx) + 3] == 1.f;
            m[size_t(y) * w + x] = all;
        }
    return m;
}

std::vector<uint8_t> mask_and(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    std::vector<uint8_t> m(a.size());
    for (size_t i = 0; i < a.size(); ++i) m[i] = a[i] && b[i];
    return m;
}

size_t mask_count(const std::vector<uint8_t>& m) { return size_t(std::count(m.begin(), m.end(), uint8_t(1))); }

void masked_mean(const RenderResult& r, const std::vector<uint8_t>& mask, double* mean, double* se) {
    double sum = 0.0, var = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        sum += pixel_luminance(r, i);
        var += double(r.noise[i]) * r.noise[i];
        ++n;
    }
    *mean = n ? sum / n : 0.0;
    *se = n ? std::sqrt(var) / n : 0.0;
}

}  // namespace candela::test
