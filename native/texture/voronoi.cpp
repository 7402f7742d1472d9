#include "texture/voronoi.h"

#include <cmath>

namespace candela {

namespace {

template <int N>
struct P {
    float v[N] = {};
    P operator+(const P& o) const {
        P r;
        for (int i = 0; i < N; ++i) r.v[i] = v[i] + o.v[i];
        return r;
    }
    P operator-(const P& o) const {
        P r;
        for (int i = 0; i < N; ++i) r.v[i] = v[i] - o.v[i];
        return r;
    }
    P operator*(float s) const {
        P r;
        for (int i = 0; i < N; ++i) r.v[i] = v[i] * s;
        return r;
    }
};

template <int N>
float dot(const P<N>& a, const P<N>& b) {
    float s = 0.f;
    for (int i = 0; i < N; ++i) s += a.v[i] * b.v[i];
    return s;
}
template <int N>
float euclidean(const P<N>& a, const P<N>& b) {
    return std::sqrt(dot(a - b, a - b));
}

template <int N>
P<N> mix(const P<N>& a, const P<N>& b, float t) {
    return a * (1.f - t) + b * t;
}

// The feature point offset (in [0, 1]ⁿ before the randomness) and the colour of a cell.
P<1> cell_hash(const P<1>& c) { return P<1>{{hash_to_float(c.v[0])}}; }
P<2> cell_hash(const P<2>& c) {
    const Vec2 h = hash_to_vec2(c.v[0], c.v[1]);
    return P<2>{{h.x, h.y}};
}
P<3> cell_hash(const P<3>& c) {
    const Vec3 h = hash_to_color(Vec3(c.v[0], c.v[1], c.v[2]));
    return P<3>{{h.x, h.y, h.z}};
}
P<4> cell_hash(const P<4>& c) {
    const Vec4 h = hash_to_vec4(Vec4{c.v[0], c.v[1], c.v[2], c.v[3]});
    return P<4>{{h.x, h.y, h.z, h.w}};
}
Vec3 cell_color(const P<1>& c) { return hash_to_color(c.v[0]); }
Vec3 cell_color(const P<2>& c) { return hash_to_color(c.v[0], c.v[1]); }
Vec3 cell_color(const P<3>& c) { return hash_to_color(Vec3(c.v[0], c.v[1], c.v[2])); }
Vec3 cell_color(const P<4>& c) { return hash_to_color(Vec4{c.v[0], c.v[1], c.v[2], c.v[3]}); }

template <int N>
float metric_distance(const P<N>& a, const P<N>& b, const VoronoiParams& m) {
    if (N == 1) return std::fabs(a.v[0] - b.v[0]);
    switch (m.metric) {
    case VoronoiMetric::Euclidean: return euclidean(a, b);
    case VoronoiMetric::Manhattan: {
        float s = 0.f;
        for (int i = 0; i < N; ++i) s += std::fabs(a.v[i] - b.v[i]);
        return s;
    }
    case VoronoiMetric::Chebychev: {
        float s = 0.f;
        for (int i = 0; i < N; ++i) s = std::fmax(s, std::fabs(a.v[i] - b.v[i]));
        return s;
    }
    case VoronoiMetric::Minkowski: {
        float s = 0.f;
        for (int i = 0; i < N; ++i) s += std::pow(std::fabs(a.v[i] - b.v[i]), m.exponent);
        return std::pow(s, 1.f / m.exponent);
    }
    }
    return 0.f;
}

/// Calls f(offset) for every offset in [−r, r]ⁿ, the first coordinate varying fastest.
template <int N, typename F>
void for_cells(int r, F&& f) {
    int idx[N];
    for (int i = 0; i < N; ++i) idx[i] = -r;
    while (true) {
        P<N> o;
        for (int i = 0; i < N; ++i) o.v[i] = float(idx[i]);
        f(o);
        int k = 0;
        while (k < N && ++idx[k] > r) idx[k++] = -r;
        if (k == N) return;
    }
}

inline float smoothstep(float e0, float e1, float x) {
    if (x < e0) return 0.f;
    if (x >= e1) return 1.f;
    const float t = (x - e0) / (e1 - e0);
    return t * t * (3.f - 2.f * t);
}

template <int N>
struct Found {
    float distance;
    Vec3 color;
    P<N> position;
};

template <int N>
Found<N> f1(const P<N>& cell, const P<N>& local, const VoronoiParams& m) {
    float best = 8.f;
    P<N> best_offset, best_point;
    for_cells<N>(1, [&](const P<N>& o) {
        const P<N> point = o + cell_hash(cell + o) * m.randomness;
        const float d = metric_distance(point, local, m);
        if (d < best) {
            best = d;
            best_offset = o;
            best_point = point;
        }
    });
    return {best, cell_color(cell + best_offset), best_point + cell};
}

template <int N>
Found<N> smooth_f1(const P<N>& cell, const P<N>& local, const VoronoiParams& m) {
    const float s = clamp(m.smoothness * 0.5f, 0.f, 0.5f);
    float distance = 8.f;
    Vec3 color(0.f);
    P<N> position;
    for_cells<N>(2, [&](const P<N>& o) {
        const P<N> point = o + cell_hash(cell + o) * m.randomness;
        const float d = metric_distance(point, local, m);
        const float h = smoothstep(0.f, 1.f, 0.5f + 0.5f * (distance - d) / s);
        float correction = s * h * (1.f - h);
        distance = distance * (1.f - h) + d * h - correction;
        correction /= 1.f + 3.f * s;
        color = color * (1.f - h) + cell_color(cell + o) * h - Vec3(correction);
        P<N> c;
        for (int i = 0; i < N; ++i) c.v[i] = correction;
        position = mix(position, point, h) - c;
    });
    return {distance, color, position + cell};
}

template <int N>
Found<N> f2(const P<N>& cell, const P<N>& local, const VoronoiParams& m) {
    float d1 = 8.f, d2 = 8.f;
    P<N> o1, p1, o2, p2;
    for_cells<N>(1, [&](const P<N>& o) {
        const P<N> point = o + cell_hash(cell + o) * m.randomness;
        const float d = metric_distance(point, local, m);
        if (d < d1) {
            d2 = d1;
            o2 = o1;
            p2 = p1;
            d1 = d;
            o1 = o;
            p1 = point;
        } else if (d < d2) {
            d2 = d;
            o2 = o;
            p2 = point;
        }
    });
    return {d2, cell_color(cell + o2), p2 + cell};
}

template <int N>
float distance_to_edge(const P<N>& cell, const P<N>& local, const VoronoiParams& m) {
    if (N == 1) {
        const float mid = cell_hash(cell).v[0] * m.randomness;
        const float left = -1.f + cell_hash(cell + P<N>{{-1.f}}).v[0] * m.randomness;
        const float right = 1.f + cell_hash(cell + P<N>{{1.f}}).v[0] * m.randomness;
        return std::fmin(std::fabs((mid + left) * 0.5f - local.v[0]), std::fabs((mid + right) * 0.5f - local.v[0]));
    }
    P<N> to_closest;
    float best = 8.f;
    for_cells<N>(1, [&](const P<N>& o) {
        const P<N> v = o + cell_hash(cell + o) * m.randomness - local;
        const float d = dot(v, v);
        if (d < best) {
            best = d;
            to_closest = v;
        }
    });
    best = 8.f;
    for_cells<N>(1, [&](const P<N>& o) {
        const P<N> v = o + cell_hash(cell + o) * m.randomness - local;
        const P<N> perpendicular = v - to_closest;
        const float len2 = dot(perpendicular, perpendicular);
        if (len2 > 0.0001f) {
            const float d = dot((to_closest + v) * 0.5f, perpendicular * (1.f / std::sqrt(len2)));
            best = std::fmin(best, d);
        }
    });
    return best;
}

template <int N>
float n_sphere_radius(const P<N>& cell, const P<N>& local, const VoronoiParams& m) {
    P<N> closest, closest_offset;
    float best = 8.f;
    for_cells<N>(1, [&](const P<N>& o) {
        const P<N> point = o + cell_hash(cell + o) * m.randomness;
        const float d = euclidean(point, local);
        if (d < best) {
            best = d;
            closest = point;
            closest_offset = o;
        }
    });
    best = 8.f;
    P<N> closest_to_closest;
    for_cells<N>(1, [&](const P<N>& o) {
        bool centre = true;
        for (int i = 0; i < N; ++i) centre = centre && o.v[i] == 0.f;
        if (centre) return;
        const P<N> c = o + closest_offset;
        const P<N> point = c + cell_hash(cell + c) * m.randomness;
        const float d = euclidean(closest, point);
        if (d < best) {
            best = d;
            closest_to_closest = point;
        }
    });
    return euclidean(closest_to_closest, closest) * 0.5f;
}

template <int N>
VoronoiResult run(const P<N>& coord, const VoronoiParams& m) {
    P<N> cell, local;
    for (int i = 0; i < N; ++i) {
        cell.v[i] = std::floor(coord.v[i]);
        local.v[i] = coord.v[i] - cell.v[i];
    }
    VoronoiResult r;
    Found<N> f{};
    switch (m.feature) {
    case VoronoiFeature::F1: f = f1(cell, local, m); break;
    case VoronoiFeature::F2: f = f2(cell, local, m); break;
    case VoronoiFeature::SmoothF1: f = smooth_f1(cell, local, m); break;
    case VoronoiFeature::DistanceToEdge: r.distance = distance_to_edge(cell, local, m); return r;
    case VoronoiFeature::NSphereRadius: r.radius = n_sphere_radius(cell, local, m); return r;
    }
    r.distance = f.distance;
    r.color = f.color;
    float* out[4] = {&r.position.x, &r.position.y, &r.position.z, &r.position.w};
    const float inv = m.scale != 0.f ? 1.f / m.scale : 0.f;
    for (int i = 0; i < N; ++i) *out[i] = m.scale != 0.f ? f.position.v[i] * inv : 0.f;
    return r;
}

}  // namespace

VoronoiResult voronoi(int dims, const Vec4& p, const VoronoiParams& params) {
    VoronoiParams m = params;
    m.randomness = clamp(m.randomness, 0.f, 1.f);
    const float s = m.scale;
    switch (dims) {
    case 1: return run(P<1>{{p.w * s}}, m);
    case 2: return run(P<2>{{p.x * s, p.y * s}}, m);
    case 4: return run(P<4>{{p.x * s, p.y * s, p.z * s, p.w * s}}, m);
    default: return run(P<3>{{p.x * s, p.y * s, p.z * s}}, m);
    }
}

}  // namespace candela
