#include "integrators/bdpt/strategy_images.h"

#include <cmath>

namespace candela {

std::vector<StrategyId> StrategyImages::strategies(int max_depth) {
    std::vector<StrategyId> out;
    for (int d = 0; d <= max_depth; ++d)
        for (int s = 0; s <= d + 1; ++s) {
            const int t = d + 2 - s;
            if (t == 1 && s == 0) continue;  // (0, 1) is not a strategy (a pinhole lens cannot be hit)
            out.push_back({d, s, t});
        }
    return out;
}

std::string StrategyImages::name(const StrategyId& id, bool unweighted) {
    return "BDPT d" + std::to_string(id.depth) + " s" + std::to_string(id.s) + " t" + std::to_string(id.t) +
           (unweighted ? " unweighted" : "");
}

double StrategyImages::bytes_per_pixel(int max_depth) {
    return double(strategies(max_depth).size()) * 2.0 * 3.0 * sizeof(double);
}

StrategyImages::StrategyImages(int max_depth, int width, int height, int origin_x, int origin_y)
    : m_max_depth(max_depth),
      m_width(width),
      m_height(height),
      m_origin_x(origin_x),
      m_origin_y(origin_y),
      m_ids(strategies(max_depth)) {
    m_first.assign(size_t(max_depth) + 1, -1);
    for (size_t i = 0; i < m_ids.size(); ++i)
        if (m_first[size_t(m_ids[i].depth)] < 0) m_first[size_t(m_ids[i].depth)] = int(i);
    m_sum.assign(m_ids.size() * 2 * size_t(width) * size_t(height) * 3, 0.0);
}

int StrategyImages::strategy_index(int s, int t) const {
    const int d = s + t - 2;
    if (d < 0 || d > m_max_depth || t < 1 || (t == 1 && s == 0)) return -1;
    return m_first[size_t(d)] + s;  // depth d lists s = 0 .. d + 1
}

void StrategyImages::record(Buffer& out, int s, int t, const Color& unweighted, float weight, Vec2 raster, bool splat,
                            int fx, int fy) const {
    const int k = strategy_index(s, t);
    if (k < 0) return;
    int x = fx - m_origin_x, y = fy - m_origin_y;
    if (splat) {
        x = int(std::floor(raster.x)) - m_origin_x;
        y = int(std::floor(raster.y)) - m_origin_y;
    }
    if (x < 0 || y < 0 || x >= m_width || y >= m_height) return;
    out.push_back({uint32_t(2 * k), x, y, unweighted * weight});
    out.push_back({uint32_t(2 * k + 1), x, y, unweighted});
}

void StrategyImages::merge(const Buffer& buffer, double samples) {
    const size_t plane = size_t(m_width) * size_t(m_height) * 3;
    for (const Record& r : buffer) {
        double* p = &m_sum[r.image * plane + (size_t(r.y) * size_t(m_width) + size_t(r.x)) * 3];
        p[0] += r.value.x, p[1] += r.value.y, p[2] += r.value.z;
    }
    m_samples += samples;
}

std::vector<std::pair<std::string, std::vector<float>>> StrategyImages::images() const {
    std::vector<std::pair<std::string, std::vector<float>>> out;
    const size_t plane = size_t(m_width) * size_t(m_height) * 3;
    const double scale = m_samples > 0.0 ? 1.0 / m_samples : 0.0;
    for (size_t i = 0; i < 2 * m_ids.size(); ++i) {
        std::vector<float> img(plane);
        for (size_t j = 0; j < plane; ++j) img[j] = float(m_sum[i * plane + j] * scale);
        out.emplace_back(name(m_ids[i / 2], i % 2 == 1), std::move(img));
    }
    return out;
}

}  // namespace candela
