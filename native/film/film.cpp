#include "film/film.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace candela {

Film::Film(int width, int height, int origin_x, int origin_y, int tile_size)
    : m_width(width), m_height(height), m_origin_x(origin_x), m_origin_y(origin_y) {
    if (width <= 0 || height <= 0) throw InvalidParameter("the film (border window) is empty");
    if (tile_size <= 0) throw InvalidParameter("tile_size must be positive");
    const size_t count = size_t(width) * size_t(height);
    m_pixels.resize(count);
    m_splats.assign(count, Color(0.f));
    for (int y = 0; y < height; y += tile_size)
        for (int x = 0; x < width; x += tile_size)
            m_tiles.push_back({x, y, std::min(x + tile_size, width), std::min(y + tile_size, height)});
    m_tile_locks = std::make_unique<std::mutex[]>(m_tiles.size());
}

void Film::add_tile(size_t tile_index, const std::vector<PixelAccum>& tile_pixels) {
    const Tile& t = m_tiles[tile_index];
    if (tile_pixels.size() != size_t(t.width()) * t.height()) throw InternalError("tile buffer size mismatch");
    std::lock_guard<std::mutex> lock(m_tile_locks[tile_index]);
    for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x)
            m_pixels[size_t(y) * m_width + x].add(tile_pixels[size_t(y - t.y0) * t.width() + (x - t.x0)]);
}

void Film::add_splats(const std::vector<SplatBuffer>& buffers) {
    std::lock_guard<std::mutex> lock(m_splat_lock);
    for (const auto& b : buffers)
        for (const auto& e : b.entries) m_splats[e.pixel] += e.value;
}

void Film::set_splat_scale(double scale) {
    std::lock_guard<std::mutex> lock(m_splat_lock);
    m_splat_scale = scale;
}

template <typename F>
void Film::for_each_tile_locked(F&& f) const {
    for (size_t i = 0; i < m_tiles.size(); ++i) {
        std::lock_guard<std::mutex> lock(m_tile_locks[i]);
        f(m_tiles[i]);
    }
}

std::vector<float> Film::combined() const {
    std::vector<float> out(size_t(m_width) * m_height * 4, 0.f);
    for_each_tile_locked([&](const Tile& t) {
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                const size_t i = size_t(y) * m_width + x;
                const PixelAccum& p = m_pixels[i];
                if (p.n == 0) continue;
                const double inv = 1.0 / p.n;
                out[4 * i] = float(p.r * inv);
                out[4 * i + 1] = float(p.g * inv);
                out[4 * i + 2] = float(p.b * inv);
                out[4 * i + 3] = float(p.a * inv);
            }
    });
    std::lock_guard<std::mutex> lock(m_splat_lock);
    for (size_t i = 0; i < m_splats.size(); ++i) {
        out[4 * i] += float(m_splats[i].x * m_splat_scale);
        out[4 * i + 1] += float(m_splats[i].y * m_splat_scale);
        out[4 * i + 2] += float(m_splats[i].z * m_splat_scale);
    }
    return out;
}

std::vector<float> Film::noise() const {
    const double scale = std::sqrt(noise_estimate().calibration);
    std::vector<float> out(size_t(m_width) * m_height, 0.f);
    for_each_tile_locked([&](const Tile& t) {
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                const size_t i = size_t(y) * m_width + x;
                out[i] = float(scale * std::sqrt(moment_variance_of_mean(m_pixels[i])));
            }
    });
    return out;
}

Film::NoiseEstimate Film::noise_estimate() const {
    NoiseTally tally;
    for_each_tile_locked([&](const Tile& t) {
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) tally.add(m_pixels[size_t(y) * m_width + x]);
    });
    return tally.result();
}

PixelAccum Film::pixel(int x, int y) const {
    if (x < 0 || y < 0 || x >= m_width || y >= m_height) throw InvalidParameter("pixel outside the film");
    for (size_t i = 0; i < m_tiles.size(); ++i) {
        const Tile& t = m_tiles[i];
        if (x >= t.x0 && x < t.x1 && y >= t.y0 && y < t.y1) {
            std::lock_guard<std::mutex> lock(m_tile_locks[i]);
            return m_pixels[size_t(y) * m_width + x];
        }
    }
    throw InternalError("pixel not covered by a tile");
}

uint32_t Film::min_samples() const {
    uint32_t n = UINT32_MAX;
    for_each_tile_locked([&](const Tile& t) {
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) n = std::min(n, m_pixels[size_t(y) * m_width + x].n);
    });
    return n == UINT32_MAX ? 0 : n;
}

}  // namespace candela
