#include "ic_analytic.h"

#include <cmath>

#include "core/math.h"

namespace candela::test {

double polygon_irradiance(const std::vector<Vec3>& corners, const Vec3& x, const Vec3& n) {
    double sum = 0.0;
    const size_t k = corners.size();
    for (size_t i = 0; i < k; ++i) {
        const Vec3 a = normalize(corners[i] - x), b = normalize(corners[(i + 1) % k] - x);
        const double c = std::fmax(-1.0, std::fmin(1.0, double(dot(a, b))));
        const Vec3 u = normalize(cross(a, b));
        sum += std::acos(c) * double(dot(n, u));
    }
    return 0.5 * std::fabs(sum);
}

double disk_irradiance(double r, double h, double d) {
    if (d < 1e-9) return M_PI * r * r / (r * r + h * h);
    const double H = h / d, R = r / d;
    const double z = 1.0 + H * H + R * R;
    return 0.5 * M_PI * (1.0 - (1.0 + H * H - R * R) / std::sqrt(z * z - 4.0 * R * R));
}

HemisphereSamples analytic_gather(const AnalyticField& field, const Vec3& x, const Frame& frame,
                                  const GatherStrata& strata, Pcg32& rng) {
    HemisphereSamples s;
    s.strata = strata;
    const size_t n = size_t(strata.count());
    s.dir.resize(n);
    s.L.resize(n);
    s.r.resize(n);
    for (int j = 0; j < strata.M; ++j)
        for (int k = 0; k < strata.N; ++k) {
            const size_t i = size_t(j * strata.N + k);
            const float u1 = rng.next_float(), u2 = rng.next_float();
            s.dir[i] = gather_direction(strata, j, k, u1, u2);
            const AnalyticHit h = field(x, frame.to_world(s.dir[i]));
            s.L[i] = h.L;
            s.r[i] = h.distance >= 1e29f ? std::numeric_limits<float>::infinity() : h.distance;
        }
    return s;
}

namespace {

const std::vector<Vec3>& room_polygon(RoomEmitter e) {
    static const std::vector<Vec3> rect = {{-0.3f, -0.2f, AnalyticRoom::k_height},
                                           {0.5f, -0.2f, AnalyticRoom::k_height},
                                           {0.5f, 0.4f, AnalyticRoom::k_height},
                                           {-0.3f, 0.4f, AnalyticRoom::k_height}};
    static const std::vector<Vec3> tri = {{-0.4f, -0.3f, AnalyticRoom::k_height},
                                          {0.5f, -0.2f, AnalyticRoom::k_height},
                                          {0.1f, 0.6f, AnalyticRoom::k_height}};
    return e == RoomEmitter::Rectangle ? rect : tri;
}

bool inside_polygon(const std::vector<Vec3>& poly, float x, float y) {
    // Convex, either winding: the point is on the same side of every edge.
    int sign = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        const float c = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
        const int s = c > 0.f ? 1 : (c < 0.f ? -1 : 0);
        if (s != 0) {
            if (sign != 0 && s != sign) return false;
            sign = s;
        }
    }
    return true;
}

}  // namespace

AnalyticHit AnalyticRoom::trace(const Vec3& o, const Vec3& d) const {
    AnalyticHit h;
    float t = 1e30f;
    if (d.z > 0.f) t = (k_height - o.z) / d.z;
    for (int axis = 0; axis < 2; ++axis) {
        const float od = axis == 0 ? o.x : o.y, dd = axis == 0 ? d.x : d.y;
        if (dd > 0.f) t = std::fmin(t, (k_half - od) / dd);
        if (dd < 0.f) t = std::fmin(t, (-k_half - od) / dd);
    }
    if (!(t < 1e29f)) return h;
    h.distance = t;
    const Vec3 p = o + d * t;
    if (d.z > 0.f && std::fabs(p.z - k_height) < 1e-4f) {
        const bool lit = emitter == RoomEmitter::Disk ? (sqr(p.x - 0.2f) + sqr(p.y - 0.1f) < sqr(0.4f))
                                                      : inside_polygon(room_polygon(emitter), p.x, p.y);
        if (lit) h.L = Color(1.f);
    }
    return h;
}

double AnalyticRoom::exact(const Vec3& x) const {
    if (emitter == RoomEmitter::Disk)
        return disk_irradiance(0.4, k_height - x.z, std::hypot(double(x.x) - 0.2, double(x.y) - 0.1));
    return polygon_irradiance(room_polygon(emitter), x, Vec3(0.f, 0.f, 1.f));
}

}  // namespace candela::test
