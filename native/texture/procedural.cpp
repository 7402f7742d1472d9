#include "texture/procedural.h"

#include <cmath>

namespace candela {

namespace {

/// float → int for lattice indices, defined for every input (the plain conversion is undefined past ±2³¹ and
/// for NaN, which user coordinates and divisions by a zero row height can produce).
int to_int(float x) {
    if (!(x == x)) return 0;
    return int(clamp(x, -1073741824.f, 1073741824.f));
}

// The offsets of the Noise Texture's distortion and colour channels: 100 + 100·hash(seed), per coordinate.
float offset1(float seed) { return 100.f + 100.f * hash_to_float(seed); }
float offset_n(float seed, float axis) { return 100.f + 100.f * hash_to_float(seed, axis); }
Vec2 offset2(float seed) { return {offset_n(seed, 0.f), offset_n(seed, 1.f)}; }
Vec3 offset3(float seed) { return {offset_n(seed, 0.f), offset_n(seed, 1.f), offset_n(seed, 2.f)}; }
Vec4 offset4(float seed) {
    return {offset_n(seed, 0.f), offset_n(seed, 1.f), offset_n(seed, 2.f), offset_n(seed, 3.f)};
}

template <typename V>
void noise_colour(const V& p, const NoiseParams& n, bool want_color, float* fac, Vec3* color, const V& o1,
                  const V& o2) {
    *fac = fractal_noise(p, n.detail, n.roughness);
    if (want_color)
        *color = Vec3(*fac, fractal_noise(p + o1, n.detail, n.roughness), fractal_noise(p + o2, n.detail, n.roughness));
}

}  // namespace

void noise_texture(int dims, const Vec4& q, const NoiseParams& n, bool want_color, float* fac, Vec3* color) {
    const float s = n.scale, d = n.distortion;
    switch (dims) {
    case 1: {
        float p = q.w * s;
        if (d != 0.f) p += snoise(p + offset1(0.f)) * d;
        noise_colour(p, n, want_color, fac, color, offset1(1.f), offset1(2.f));
        return;
    }
    case 2: {
        Vec2 p{q.x * s, q.y * s};
        if (d != 0.f) p = p + Vec2{snoise(p + offset2(0.f)) * d, snoise(p + offset2(1.f)) * d};
        noise_colour(p, n, want_color, fac, color, offset2(2.f), offset2(3.f));
        return;
    }
    case 4: {
        Vec4 p{q.x * s, q.y * s, q.z * s, q.w * s};
        if (d != 0.f)
            p = p + Vec4{snoise(p + offset4(0.f)) * d, snoise(p + offset4(1.f)) * d, snoise(p + offset4(2.f)) * d,
                         snoise(p + offset4(3.f)) * d};
        noise_colour(p, n, want_color, fac, color, offset4(4.f), offset4(5.f));
        return;
    }
    default: {
        Vec3 p(q.x * s, q.y * s, q.z * s);
        if (d != 0.f)
            p += Vec3(snoise(p + offset3(0.f)) * d, snoise(p + offset3(1.f)) * d, snoise(p + offset3(2.f)) * d);
        noise_colour(p, n, want_color, fac, color, offset3(3.f), offset3(4.f));
        return;
    }
    }
}

void white_noise_texture(int dims, const Vec4& p, float* value, Vec3* color) {
    switch (dims) {
    case 1:
        *value = hash_to_float(p.w);
        *color = hash_to_color(p.w);
        return;
    case 2:
        *value = hash_to_float(p.x, p.y);
        *color = hash_to_color(p.x, p.y);
        return;
    case 4:
        *value = hash_to_float(p);
        *color = hash_to_color(p);
        return;
    default: {
        const Vec3 k(p.x, p.y, p.z);
        *value = hash_to_float(k);
        *color = hash_to_color(k);
        return;
    }
    }
}

float musgrave_texture(int dims, const Vec4& q, float s, const MusgraveParams& m) {
    switch (dims) {
    case 1: return musgrave(q.w * s, m);
    case 2: return musgrave(Vec2{q.x * s, q.y * s}, m);
    case 4: return musgrave(Vec4{q.x * s, q.y * s, q.z * s, q.w * s}, m);
    default: return musgrave(Vec3(q.x * s, q.y * s, q.z * s), m);
    }
}

float wave_texture(const Vec3& co, const WaveParams& w) {
    // The tiny shift keeps unit coordinates (a plane's Generated edges) off the bands' discontinuities.
    const Vec3 p = (co * w.scale + Vec3(0.000001f)) * 0.999999f;
    float n;
    if (w.type == WaveType::Bands) {
        switch (w.direction) {
        case WaveDirection::X: n = p.x * 20.f; break;
        case WaveDirection::Y: n = p.y * 20.f; break;
        case WaveDirection::Z: n = p.z * 20.f; break;
        default: n = (p.x + p.y + p.z) * 10.f; break;
        }
    } else {
        Vec3 r = p;
        switch (w.direction) {
        case WaveDirection::X: r = Vec3(0.f, p.y, p.z); break;
        case WaveDirection::Y: r = Vec3(p.x, 0.f, p.z); break;
        case WaveDirection::Z: r = Vec3(p.x, p.y, 0.f); break;
        default: break;
        }
        n = length(r) * 20.f;
    }
    n += w.phase;
    if (w.distortion != 0.f)
        n += w.distortion * (fractal_noise(p * w.detail_scale, w.detail, w.detail_roughness) * 2.f - 1.f);
    switch (w.profile) {
    case WaveProfile::Sine: return 0.5f + 0.5f * std::sin(n - 0.5f * k_pi);
    case WaveProfile::Saw: n *= k_inv_two_pi; return n - std::floor(n);
    case WaveProfile::Triangle: n *= k_inv_two_pi; return std::fabs(n - std::floor(n + 0.5f)) * 2.f;
    }
    return 0.f;
}

Vec3 magic_texture(const Vec3& co, int depth, float scale, float distortion) {
    // Blender's Magic texture: nested sines and cosines of the coordinates, `depth` levels deep.
    const Vec3 p = co * scale;
    const float d = distortion;
    float x = std::sin((p.x + p.y + p.z) * 5.f);
    float y = std::cos((-p.x + p.y - p.z) * 5.f);
    float z = -std::cos((-p.x - p.y + p.z) * 5.f);
    if (depth > 0) {
        x *= d;
        y *= d;
        z *= d;
        y = -std::cos(x - y + z) * d;
        if (depth > 1) x = std::cos(x - y - z) * d;
        if (depth > 2) z = std::sin(-x - y - z) * d;
        if (depth > 3) x = -std::cos(-x + y - z) * d;
        if (depth > 4) y = -std::sin(-x + y + z) * d;
        if (depth > 5) y = -std::cos(-x + y + z) * d;
        if (depth > 6) x = std::cos(x + y + z) * d;
        if (depth > 7) z = std::sin(x + y - z) * d;
        if (depth > 8) x = -std::cos(-x - y + z) * d;
        if (depth > 9) y = -std::sin(x - y + z) * d;
    }
    if (d != 0.f) {
        const float k = 1.f / (2.f * d);
        x *= k;
        y *= k;
        z *= k;
    }
    return {0.5f - x, 0.5f - y, 0.5f - z};
}

float checker_texture(const Vec3& co, float scale) {
    // The shift keeps unit coordinates from falling exactly on a square's edge.
    const Vec3 p = (co * scale + Vec3(0.000001f)) * 0.999999f;
    const int xi = std::abs(to_int(std::floor(p.x))), yi = std::abs(to_int(std::floor(p.y))),
              zi = std::abs(to_int(std::floor(p.z)));
    return ((xi % 2 == yi % 2) == (zi % 2 == 1)) ? 1.f : 0.f;
}

float gradient_texture(const Vec3& p, GradientType type) {
    float f = 0.f;
    switch (type) {
    case GradientType::Linear: f = p.x; break;
    case GradientType::Quadratic: {
        const float r = std::fmax(p.x, 0.f);
        f = r * r;
        break;
    }
    case GradientType::Easing: {
        const float r = clamp(p.x, 0.f, 1.f), t = r * r;
        f = 3.f * t - 2.f * t * r;
        break;
    }
    case GradientType::Diagonal: f = (p.x + p.y) * 0.5f; break;
    case GradientType::Radial: f = std::atan2(p.y, p.x) * k_inv_two_pi + 0.5f; break;
    case GradientType::QuadraticSphere: {
        const float r = std::fmax(0.999999f - length(p), 0.f);
        f = r * r;
        break;
    }
    case GradientType::Spherical: f = std::fmax(0.999999f - length(p), 0.f); break;
    }
    return clamp(f, 0.f, 1.f);
}

namespace {

/// Blender's integer noise for the brick tints, in [0, 1).
float brick_noise(uint32_t n) {
    n = (n + 1013u) & 0x7fffffffu;
    n = (n >> 13) ^ n;
    const uint32_t nn = (n * (n * n * 60493u + 19990303u) + 1376312589u) & 0x7fffffffu;
    return 0.5f * (float(nn) / 1073741824.f);
}

inline float smoothstep(float e0, float e1, float x) {
    if (x < e0) return 0.f;
    if (x >= e1) return 1.f;
    const float t = (x - e0) / (e1 - e0);
    return t * t * (3.f - 2.f * t);
}

}  // namespace

float brick_texture(const Vec3& co, const BrickParams& b, const Vec3& color1, const Vec3& color2,
                    const Vec3& mortar_color, Vec3* color) {
    const Vec3 p = co * b.scale;
    float brick_width = b.brick_width, offset = 0.f;
    const int rownum = to_int(std::floor(p.y / b.row_height));
    if (b.offset_frequency && b.squash_frequency) {
        brick_width *= (rownum % b.squash_frequency) ? 1.f : b.squash;
        offset = (rownum % b.offset_frequency) ? 0.f : brick_width * b.offset;
    }
    const int bricknum = to_int(std::floor((p.x + offset) / brick_width));
    const float x = (p.x + offset) - brick_width * float(bricknum);
    const float y = p.y - b.row_height * float(rownum);
    const float tint = clamp(brick_noise((uint32_t(rownum) << 16) + (uint32_t(bricknum) & 0xFFFFu)) + b.bias, 0.f, 1.f);
    float min_dist = std::fmin(std::fmin(x, y), std::fmin(brick_width - x, b.row_height - y));
    float mortar;
    if (min_dist >= b.mortar_size)
        mortar = 0.f;
    else if (b.mortar_smooth == 0.f)
        mortar = 1.f;
    else {
        min_dist = 1.f - min_dist / b.mortar_size;
        mortar = smoothstep(0.f, b.mortar_smooth, min_dist);
    }
    Vec3 c1 = color1;
    if (mortar != 1.f) c1 = color1 * (1.f - tint) + color2 * tint;
    *color = c1 * (1.f - mortar) + mortar_color * mortar;
    return mortar;
}

}  // namespace candela
