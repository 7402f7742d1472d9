#include "lights/environment_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/frame.h"
#include "core/math.h"
#include "core/parallel.h"

namespace candela {

namespace {

constexpr uint32_t k_max_width = 2048, k_default_width = 256, k_min_width = 32;
constexpr uint32_t k_max_sub = 4;  // sub-samples per cell and axis, at most
constexpr float k_floor = 1e-3f;   // share of the mean weight every cell keeps

/// The widest and tallest equirectangular image the program reads (0, 0: none).
void image_size(const ShaderLibrary& lib, uint32_t program, uint32_t* w, uint32_t* h) {
    *w = *h = 0;
    for (uint32_t r = 0; r < lib.program_size(program); ++r) {
        const ShaderOp& op = lib.op(program, r);
        if (op.code == ShaderOpCode::Image || op.code == ShaderOpCode::ImageAlpha) {
            *w = std::max(*w, lib.textures()[op.i[0]].width);
            *h = std::max(*h, lib.textures()[op.i[0]].height);
        }
    }
}

/// Bake width: the image's width (clamped), else a default.
uint32_t bake_width(uint32_t image_width) {
    uint32_t w = image_width == 0 ? k_default_width : image_width;
    w = std::min(std::max(w, k_min_width), k_max_width);
    return w + (w & 1u);  // even, so that height = width/2 exactly
}

/// Sub-samples per cell along one axis: 2 per texel the cell spans (ceil), at most k_max_sub. With the bake at the
/// image's resolution (cells = texels) the 2 × 2 points at a quarter and three quarters of the cell split it into
/// four squares none of which crosses a texel centre, so the filtered image is bilinear on each and the midpoint
/// rule gives its exact integral (Closest: the cell's one texel, exactly).
uint32_t sub_samples(uint32_t texels, uint32_t cells) {
    if (texels == 0) return 2;
    return std::min(k_max_sub, 2 * ((texels + cells - 1) / cells));
}

}  // namespace

EnvironmentMap::EnvironmentMap(std::shared_ptr<const ShaderLibrary> shaders, uint32_t program, uint32_t reg,
                               int threads)
    : m_shaders(std::move(shaders)), m_program(program), m_reg(reg) {
    uint32_t image_w = 0, image_h = 0;
    image_size(*m_shaders, m_program, &image_w, &image_h);
    const uint32_t nu = bake_width(image_w), nv = nu / 2;
    const uint32_t su = sub_samples(image_w, nu), sv = sub_samples(image_h, nv);
    // Cell (i, j)'s weight is the integral of luminance(L)·sin θ over the cell, by the midpoint rule on su × sv
    // points: the integral of what is rendered (the filtered image), not its value at one point. One value per cell
    // (its centre) misses the part of a bright texel's bilinear footprint that lies in the neighbouring cells — a
    // sun of a few texels then sends 44 % of its light through cells weighted like the sky (issue 22: 40-160×
    // Cycles' variance). Each row's radiance integral (exact sub-row solid angles) goes to the mean radiance.
    std::vector<float> weights(size_t(nu) * nv);
    std::vector<double> row_mean(size_t(nv) * 3, 0.0), row_total(nv, 0.0);
    parallel_for(threads, nv, [&](size_t j) {
        double m[3] = {0.0, 0.0, 0.0}, t = 0.0;
        for (uint32_t i = 0; i < nu; ++i) {
            double w = 0.0;
            for (uint32_t b = 0; b < sv; ++b) {
                const double v0 = (double(j) + double(b) / sv) / nv, v1 = (double(j) + double(b + 1) / sv) / nv;
                const float v = float((double(j) + (b + 0.5) / sv) / nv);
                const float sin_theta = std::sin(k_pi * (1.f - v));
                // Sub-cell solid angle: θ from π(1 − v1) to π(1 − v0).
                const double solid_angle =
                    2.0 * k_pi / (double(nu) * su) * (std::cos(k_pi * (1.0 - v1)) - std::cos(k_pi * (1.0 - v0)));
                for (uint32_t a = 0; a < su; ++a) {
                    const float u = float((double(i) + (a + 0.5) / su) / nu);
                    const Color c = Le(equirectangular_to_direction(u, v));
                    w += double(std::fmax(luminance(c), 0.f)) * sin_theta;
                    for (int k = 0; k < 3; ++k) m[k] += double(c[k]) * solid_angle;
                }
            }
            weights[j * nu + i] = float(w / (double(su) * sv));
            t += weights[j * nu + i];
        }
        for (int k = 0; k < 3; ++k) row_mean[j * 3 + k] = m[k];
        row_total[j] = t;
    });
    double mean[3] = {0.0, 0.0, 0.0}, total = 0.0;
    for (uint32_t j = 0; j < nv; ++j) {  // in row order: the same sums for any thread count
        for (int k = 0; k < 3; ++k) mean[k] += row_mean[size_t(j) * 3 + k];
        total += row_total[j];
    }
    const float floor_weight = float(k_floor * total / double(weights.size()));
    for (float& w : weights) w += floor_weight;
    m_mean = Color(float(mean[0] / (4.0 * k_pi)), float(mean[1] / (4.0 * k_pi)), float(mean[2] / (4.0 * k_pi)));
    if (total > 0.0) m_distribution = Distribution2D(weights, nu, nv);

    float half_angle = 0.f;
    if (m_shaders->sun_disc(m_program, &m_sun, &half_angle) && half_angle > 0.f) {
        // The disc's power from a few rings of radiance samples (limb darkening makes it uneven), added to the mean
        // the bake missed; q is its share.
        m_sun_cos = std::cos(half_angle);
        const float solid_angle = 2.f * k_pi * (1.f - m_sun_cos);
        const Frame frame(m_sun);
        Color sum(0.f);
        constexpr int k_rings = 8, k_per_ring = 8;
        for (int r = 0; r < k_rings; ++r)
            for (int a = 0; a < k_per_ring; ++a) {
                // Equal-area rings of the cone.
                const float cos_t = 1.f - (float(r) + 0.5f) / k_rings * (1.f - m_sun_cos);
                const float sin_t = std::sqrt(std::fmax(1.f - cos_t * cos_t, 0.f)),
                            phi = 2.f * k_pi * (float(a) + 0.5f) / k_per_ring;
                sum += Le(frame.to_world(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t)));
            }
        const Color sun_mean = sum / float(k_rings * k_per_ring) * (solid_angle / (4.f * k_pi));
        const float sun_power = luminance(sun_mean), map_power = luminance(m_mean);
        m_mean += sun_mean;
        if (sun_power > 0.f)
            m_sun_q = m_distribution.nu() == 0 ? 1.f : clamp(sun_power / (sun_power + map_power), 0.05f, 0.95f);
    }
}

Color EnvironmentMap::Le(const Vec3& d) const {
    ShaderRegisters regs(m_shaders->program_size(m_program));
    m_shaders->evaluate(m_program, ShadingInputs::world(d), regs.data());
    return vmax(regs[m_reg], Color(0.f));
}

LightSample EnvironmentMap::sample(Vec2 u) const {
    if (m_sun_q <= 0.f) return sample_map(u);
    LightSample s;
    if (u.x < m_sun_q) {  // the sun's cone, uniformly
        const Vec2 v{u.x / m_sun_q, u.y};
        const float cos_t = 1.f - v.x * (1.f - m_sun_cos);
        const float sin_t = std::sqrt(std::fmax(1.f - cos_t * cos_t, 0.f)), phi = 2.f * k_pi * v.y;
        s.wi = Frame(m_sun).to_world(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t));
    } else {
        s = sample_map({std::min((u.x - m_sun_q) / (1.f - m_sun_q), k_one_minus_epsilon), u.y});
        if (!(s.pdf > 0.f)) return s;
    }
    s.pdf = pdf(s.wi);
    s.dist = std::numeric_limits<float>::infinity();
    s.Li = Le(s.wi);
    if (!(s.pdf > 0.f)) s = LightSample();
    return s;
}

LightSample EnvironmentMap::sample_map(Vec2 u) const {
    LightSample s;
    if (m_distribution.nu() == 0) return s;
    float pdf_uv = 0.f;
    const Vec2 uv = m_distribution.sample(u, &pdf_uv);
    const float sin_theta = std::sin(k_pi * (1.f - uv.y));
    if (!(pdf_uv > 0.f) || !(sin_theta > 0.f)) return s;
    s.wi = equirectangular_to_direction(uv.x, uv.y);
    s.pdf = pdf_uv / (2.f * k_pi * k_pi * sin_theta);
    s.dist = std::numeric_limits<float>::infinity();
    s.Li = Le(s.wi);
    return s;
}

float EnvironmentMap::pdf(const Vec3& d) const {
    if (m_sun_q <= 0.f) return pdf_map(d);
    const float len = length(d);
    const float cone = len > 0.f && dot(d, m_sun) >= m_sun_cos * len ? 1.f / (2.f * k_pi * (1.f - m_sun_cos)) : 0.f;
    return m_sun_q * cone + (1.f - m_sun_q) * pdf_map(d);
}

float EnvironmentMap::pdf_map(const Vec3& d) const {
    if (m_distribution.nu() == 0) return 0.f;
    Vec2 uv = direction_to_equirectangular(d);
    uv.x -= std::floor(uv.x);
    uv.y = std::min(uv.y, k_one_minus_epsilon);
    const float sin_theta = std::sin(k_pi * (1.f - uv.y));
    if (!(sin_theta > 0.f)) return 0.f;
    return m_distribution.pdf(uv) / (2.f * k_pi * k_pi * sin_theta);
}

}  // namespace candela
