#include "lights/environment_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/frame.h"
#include "core/math.h"
#include "core/parallel.h"

namespace candela {

EnvironmentMap::EnvironmentMap(std::shared_ptr<const ShaderLibrary> shaders, uint32_t program, uint32_t reg,
                               int threads)
    : m_shaders(std::move(shaders)), m_program(program), m_reg(reg) {
    EnvironmentBake bake = bake_environment(
        *m_shaders, m_program, [this](const Vec3& d) { return Le(d); }, threads);
    m_mean = bake.mean;
    m_maps[0] = std::move(bake.plain);
    m_maps[1] = std::move(bake.compensated);

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
            m_sun_q = m_maps[0].empty() ? 1.f : clamp(sun_power / (sun_power + map_power), 0.05f, 0.95f);
    }
}

Color EnvironmentMap::Le(const Vec3& d) const {
    ShaderRegisters regs(m_shaders->program_size(m_program));
    m_shaders->evaluate(m_program, ShadingInputs::world(d), regs.data());
    return vmax(regs[m_reg], Color(0.f));
}

LightSample EnvironmentMap::sample(Vec2 u, bool compensated) const {
    const EnvironmentDensity& map = m_maps[compensated ? 1 : 0];
    if (m_sun_q <= 0.f) return sample_map(u, map);
    LightSample s;
    if (u.x < m_sun_q) {  // the sun's cone, uniformly
        const Vec2 v{u.x / m_sun_q, u.y};
        const float cos_t = 1.f - v.x * (1.f - m_sun_cos);
        const float sin_t = std::sqrt(std::fmax(1.f - cos_t * cos_t, 0.f)), phi = 2.f * k_pi * v.y;
        s.wi = Frame(m_sun).to_world(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t));
    } else {
        s = sample_map({std::min((u.x - m_sun_q) / (1.f - m_sun_q), k_one_minus_epsilon), u.y}, map);
        if (!(s.pdf > 0.f)) return s;
    }
    s.pdf = pdf(s.wi, compensated);
    s.dist = std::numeric_limits<float>::infinity();
    s.Li = Le(s.wi);
    if (!(s.pdf > 0.f)) s = LightSample();
    return s;
}

LightSample EnvironmentMap::sample_map(Vec2 u, const EnvironmentDensity& map) const {
    LightSample s;
    if (map.empty()) return s;
    float pdf_uv = 0.f;
    const Vec2 uv = map.sample(u, &pdf_uv);
    s.pdf = map.solid_angle_pdf(uv);
    if (!(pdf_uv > 0.f) || !(s.pdf > 0.f)) return LightSample();
    s.wi = equirectangular_to_direction(uv.x, uv.y);
    s.dist = std::numeric_limits<float>::infinity();
    s.Li = Le(s.wi);
    return s;
}

float EnvironmentMap::pdf(const Vec3& d, bool compensated) const {
    const EnvironmentDensity& map = m_maps[compensated ? 1 : 0];
    if (m_sun_q <= 0.f) return pdf_map(d, map);
    const float len = length(d);
    const float cone = len > 0.f && dot(d, m_sun) >= m_sun_cos * len ? 1.f / (2.f * k_pi * (1.f - m_sun_cos)) : 0.f;
    return m_sun_q * cone + (1.f - m_sun_q) * pdf_map(d, map);
}

float EnvironmentMap::pdf_map(const Vec3& d, const EnvironmentDensity& map) const {
    if (map.empty()) return 0.f;
    Vec2 uv = direction_to_equirectangular(d);
    uv.x -= std::floor(uv.x);
    uv.y = std::min(uv.y, k_one_minus_epsilon);
    return map.solid_angle_pdf(uv);
}

}  // namespace candela
