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
constexpr float k_floor = 1e-3f;  // share of the mean weight every cell keeps

/// Bake width: the widest equirectangular image the program reads (clamped), else a default.
uint32_t bake_width(const ShaderLibrary& lib, uint32_t program) {
    uint32_t w = 0;
    for (uint32_t r = 0; r < lib.program_size(program); ++r) {
        const ShaderOp& op = lib.op(program, r);
        if (op.code == ShaderOpCode::Image || op.code == ShaderOpCode::ImageAlpha)
            w = std::max(w, lib.textures()[op.i[0]].width);
    }
    if (w == 0) w = k_default_width;
    w = std::min(std::max(w, k_min_width), k_max_width);
    return w + (w & 1u);  // even, so that height = width/2 exactly
}

}  // namespace

EnvironmentMap::EnvironmentMap(std::shared_ptr<const ShaderLibrary> shaders, uint32_t program, uint32_t reg, int threads)
    : m_shaders(std::move(shaders)), m_program(program), m_reg(reg) {
    const uint32_t nu = bake_width(*m_shaders, m_program), nv = nu / 2;
    std::vector<Color> bake(size_t(nu) * nv);
    parallel_for(threads, nv, [&](size_t j) {
        const float v = (float(j) + 0.5f) / float(nv);
        for (uint32_t i = 0; i < nu; ++i) bake[j * nu + i] = Le(equirectangular_to_direction((float(i) + 0.5f) / float(nu), v));
    });
    // Weights with the sin θ Jacobian; the mean radiance integrates the bake over exact cell solid angles.
    std::vector<float> weights(bake.size());
    double mean[3] = {0.0, 0.0, 0.0}, total = 0.0;
    for (uint32_t j = 0; j < nv; ++j) {
        const float theta = k_pi * (1.f - (float(j) + 0.5f) / float(nv));
        const float sin_theta = std::sin(theta);
        // Row j spans θ from π(1 − (j+1)/nv) to π(1 − j/nv).
        const double cell_solid_angle = 2.0 * k_pi / nu *
                                        (std::cos(k_pi * (1.0 - double(j + 1) / nv)) - std::cos(k_pi * (1.0 - double(j) / nv)));
        for (uint32_t i = 0; i < nu; ++i) {
            const Color& c = bake[size_t(j) * nu + i];
            weights[size_t(j) * nu + i] = std::fmax(luminance(c), 0.f) * sin_theta;
            for (int k = 0; k < 3; ++k) mean[k] += double(c[k]) * cell_solid_angle;
            total += weights[size_t(j) * nu + i];
        }
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
                const float sin_t = std::sqrt(std::fmax(1.f - cos_t * cos_t, 0.f)), phi = 2.f * k_pi * (float(a) + 0.5f) / k_per_ring;
                sum += Le(frame.to_world(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t)));
            }
        const Color sun_mean = sum / float(k_rings * k_per_ring) * (solid_angle / (4.f * k_pi));
        const float sun_power = luminance(sun_mean), map_power = luminance(m_mean);
        m_mean += sun_mean;
        if (sun_power > 0.f) m_sun_q = m_distribution.nu() == 0 ? 1.f : clamp(sun_power / (sun_power + map_power), 0.05f, 0.95f);
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
