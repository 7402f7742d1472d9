// Small fixed-size vector types used everywhere: Vec2 (sample points, pixel coordinates) and Vec3
// (points, directions and RGB colours). Plain aggregates so they live in flat arrays.
#pragma once

#include <cmath>

namespace candela {

/// std::fmax / std::fmin: a NaN argument yields the other one. GCC emits a call to libm's fmaxf/fminf for those
/// unless math is assumed finite (x86's maxss/minss return the second operand for a NaN); these compile to a
/// compare and two selects with the same results (a zero of either sign may come back for ±0 pairs, which
/// std::fmax allows too).
inline float max_num(float a, float b) { return a > b ? a : (b == b ? b : a); }
inline float min_num(float a, float b) { return a < b ? a : (b == b ? b : a); }

struct Vec2 {
    float x = 0.f, y = 0.f;
};

struct Vec3 {
    float x = 0.f, y = 0.f, z = 0.f;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}

    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    Vec3& operator-=(const Vec3& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    Vec3& operator*=(const Vec3& o) {
        x *= o.x;
        y *= o.y;
        z *= o.z;
        return *this;
    }
    Vec3& operator*=(float s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    Vec3& operator/=(float s) { return *this *= (1.f / s); }
};

inline Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
inline Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
inline Vec3 operator*(Vec3 a, const Vec3& b) { return a *= b; }
inline Vec3 operator*(Vec3 a, float s) { return a *= s; }
inline Vec3 operator*(float s, Vec3 a) { return a *= s; }
inline Vec3 operator/(Vec3 a, float s) { return a /= s; }
inline Vec3 operator/(const Vec3& a, const Vec3& b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
inline Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }

inline float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length_squared(const Vec3& a) { return dot(a, a); }
inline float length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(const Vec3& a) { return a / length(a); }
inline float max_component(const Vec3& a) { return max_num(a.x, max_num(a.y, a.z)); }
inline float min_component(const Vec3& a) { return min_num(a.x, min_num(a.y, a.z)); }
inline Vec3 vmin(const Vec3& a, const Vec3& b) { return {min_num(a.x, b.x), min_num(a.y, b.y), min_num(a.z, b.z)}; }
inline Vec3 vmax(const Vec3& a, const Vec3& b) { return {max_num(a.x, b.x), max_num(a.y, b.y), max_num(a.z, b.z)}; }
inline Vec3 vabs(const Vec3& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline bool is_finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
inline bool is_black(const Vec3& a) { return a.x == 0.f && a.y == 0.f && a.z == 0.f; }
/// Flip v to the hemisphere of n.
inline Vec3 face_forward(const Vec3& v, const Vec3& n) { return dot(v, n) < 0.f ? -v : v; }

/// Linear Rec.709 RGB radiance / reflectance.
using Color = Vec3;

/// Rec.709 luminance of a linear colour.
inline float luminance(const Color& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace candela
