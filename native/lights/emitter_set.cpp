#include "lights/emitter_set.h"

#include <algorithm>
#include <cmath>

#include "sampling/warp.h"

namespace candela {

namespace {

/// A textured triangle's flux estimated at 16 stratified points (toward its normal), max'ed with a share of the
/// brightest of them: the selection weight only needs to be positive wherever the triangle can emit.
float textured_triangle_power(const TriangleLight& t, float floor) {
    double sum = 0.0, peak = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const Vec2 b = sample_uniform_triangle({(i + 0.5f) / 4.f, (j + 0.5f) / 4.f});
            const Vec3 p = t.p0 * b.x + t.p1 * b.y + t.p2 * (1.f - b.x - b.y);
            const double l = luminance(t.Le(p, b.y, 1.f - b.x - b.y, t.normal));
            sum += l;
            peak = std::max(peak, l);
        }
    const double estimate = std::max(sum / 16.0, 0.25 * peak);
    return std::max(float(2.0 * M_PI * t.area * estimate), floor);
}

}  // namespace

EmitterSet::EmitterSet(const LightSet& lights, const SceneSphere& bounds) : m_lights(&lights), m_bounds(bounds) {
    if (!is_black(lights.background())) m_background = WorldLight{lights.background(), bounds.radius, nullptr};
    m_world = lights.world_light() >= 0 ? lights.world_light() : (m_background ? int(lights.size()) : -1);
    m_weights.resize(size());
    double untextured = 0.0;
    size_t counted = 0;
    for (size_t i = 0; i < size(); ++i) {
        const auto* tri = std::get_if<TriangleLight>(&(*this)[i]);
        if (tri && tri->source) continue;
        m_weights[i] = light_emitted_power((*this)[i], bounds);
        untextured += m_weights[i];
        ++counted;
    }
    // The floor of a textured emitter whose 16 points are all dark: a millionth of an average light's power.
    const float floor = float(1e-6 * (counted ? untextured / double(counted) : 1.0));
    for (size_t i = 0; i < size(); ++i) {
        const auto* tri = std::get_if<TriangleLight>(&(*this)[i]);
        if (tri && tri->source && tri->area > 0.f) m_weights[i] = textured_triangle_power(*tri, floor);
        if (!std::isfinite(m_weights[i]) || m_weights[i] < 0.f) m_weights[i] = 0.f;
    }
    if (!m_weights.empty()) m_power = Distribution1D(m_weights);
}

EmissionSample EmitterSet::sample_le(float u_select, Vec2 u_pos, Vec2 u_dir, float u_side, uint32_t* index,
                                     float* pmf) const {
    *pmf = 0.f;
    if (empty()) return {};
    *index = select(u_select, pmf);
    if (!(*pmf > 0.f)) return {};
    return light_sample_le((*this)[*index], u_pos, u_dir, u_side, m_bounds);
}

}  // namespace candela
