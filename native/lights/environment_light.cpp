#include "lights/environment_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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
}

Color EnvironmentMap::Le(const Vec3& d) const {
    ShaderRegisters regs(m_shaders->program_size(m_program));
    m_shaders->evaluate(m_program, ShadingInputs::world(d), regs.data());
    return vmax(regs[m_reg], Color(0.f));
}

LightSample EnvironmentMap::sample(Vec2 u) const {
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
    if (m_distribution.nu() == 0) return 0.f;
    Vec2 uv = direction_to_equirectangular(d);
    uv.x -= std::floor(uv.x);
    uv.y = std::min(uv.y, k_one_minus_epsilon);
    const float sin_theta = std::sin(k_pi * (1.f - uv.y));
    if (!(sin_theta > 0.f)) return 0.f;
    return m_distribution.pdf(uv) / (2.f * k_pi * k_pi * sin_theta);
}

}  // namespace candela
