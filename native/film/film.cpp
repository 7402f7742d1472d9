#include "film/film.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "film/pixel_filter.h"

namespace candela {

Film::Film(int width, int height, int origin_x, int origin_y, int tile_size)
    : m_width(width), m_height(height), m_origin_x(origin_x), m_origin_y(origin_y) {
    if (width <= 0 || height <= 0) throw InvalidParameter("the film (border window) is empty");
    if (tile_size <= 0) throw InvalidParameter("tile_size must be positive");
    const size_t count = size_t(width) * size_t(height);
    m_pixels.resize(count);
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

void Film::add_splats(const SplatBuffer& buffer, const PixelFilter& filter,
                      const double (&samples)[k_noise_replicates]) {
    // The footprint of a splat at raster x: pixels p whose centre p + ½ lies within ±support/2 of x, each with
    // weight pdf(x − p − ½) per axis (the filter is separable). A Blackman–Harris of width 1.5 covers 3–4 pixels
    // per axis, a Gaussian of width 1.5 5–6.
    const float half = 0.5f * filter.support();
    constexpr int k_max_span = 64;
    std::lock_guard<std::mutex> lock(m_splat_lock);
    if (m_splats.empty()) m_splats.resize(m_pixels.size());
    for (uint32_t r = 0; r < k_noise_replicates; ++r) m_splat_samples[r] += samples[r];
    struct Footprint {
        int x0, x1, y0, y1;
        bool empty() const { return x0 > x1 || y0 > y1 || x1 - x0 >= k_max_span || y1 - y0 >= k_max_span; }
    };
    auto footprint = [&](const SplatBuffer::Entry& e) {
        const float fx = e.x - float(m_origin_x), fy = e.y - float(m_origin_y);  // film coordinates
        return Footprint{
            std::max(0, int(std::ceil(fx - half - 0.5f))), std::min(m_width - 1, int(std::floor(fx + half - 0.5f))),
            std::max(0, int(std::ceil(fy - half - 0.5f))), std::min(m_height - 1, int(std::floor(fy + half - 0.5f)))};
    };
    // The accumulators a splat lands on are far apart in memory (light paths splat anywhere): fetch those of the
    // splat k_ahead entries on while this one is added, which hides most of the cache misses.
    constexpr size_t k_ahead = 8;
    const std::vector<SplatBuffer::Entry>& entries = buffer.entries();
    for (size_t k = 0; k < entries.size(); ++k) {
        if (k + k_ahead < entries.size()) {
            const Footprint f = footprint(entries[k + k_ahead]);
            if (!f.empty())
                for (int y = f.y0; y <= f.y1; ++y) {
                    const char* row = reinterpret_cast<const char*>(&m_splats[size_t(y) * m_width + f.x0]);
                    const size_t bytes = size_t(f.x1 - f.x0 + 1) * sizeof(SplatAccum);
                    for (size_t b = 0; b < bytes; b += 64) __builtin_prefetch(row + b, 1);
                    __builtin_prefetch(row + bytes - 1, 1);
                }
        }
        const SplatBuffer::Entry& e = entries[k];
        if (!(e.replicate < k_noise_replicates) || !is_finite(e.value)) continue;
        const float fx = e.x - float(m_origin_x), fy = e.y - float(m_origin_y);  // film coordinates
        const Footprint f = footprint(e);
        const int x0 = f.x0, x1 = f.x1, y0 = f.y0, y1 = f.y1;
        if (f.empty()) continue;
        float wx[k_max_span], wy[k_max_span];
        for (int x = x0; x <= x1; ++x) wx[x - x0] = filter.pdf(fx - (float(x) + 0.5f));
        for (int y = y0; y <= y1; ++y) wy[y - y0] = filter.pdf(fy - (float(y) + 0.5f));
        const double lum = luminance(e.value);
        for (int y = y0; y <= y1; ++y) {
            if (wy[y - y0] == 0.f) continue;
            for (int x = x0; x <= x1; ++x) {
                const double w = double(wx[x - x0]) * double(wy[y - y0]);
                if (w == 0.0) continue;
                SplatAccum& a = m_splats[size_t(y) * m_width + x];
                a.r += w * e.value.x;
                a.g += w * e.value.y;
                a.b += w * e.value.z;
                a.rep_lum[e.replicate] += w * lum;
            }
        }
    }
}

double Film::splat_samples(uint32_t replicate) const {
    std::lock_guard<std::mutex> lock(m_splat_lock);
    return replicate < k_noise_replicates ? m_splat_samples[replicate] : 0.0;
}

bool Film::has_splats() const {
    std::lock_guard<std::mutex> lock(m_splat_lock);
    return !m_splats.empty();
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
    if (m_splats.empty()) return out;
    double total = 0.0;
    for (double n : m_splat_samples) total += n;
    const double scale = total > 0.0 ? 1.0 / total : 0.0;
    for (size_t i = 0; i < m_splats.size(); ++i) {
        const SplatAccum& a = m_splats[i];
        out[4 * i] = float(double(out[4 * i]) + a.r * scale);
        out[4 * i + 1] = float(double(out[4 * i + 1]) + a.g * scale);
        out[4 * i + 2] = float(double(out[4 * i + 2]) + a.b * scale);
        if (m_pixels[i].n == 0 && total > 0.0) out[4 * i + 3] = 1.f;  // only splats: an opaque pixel
    }
    return out;
}

std::vector<float> Film::noise() const {
    const double scale = std::sqrt(noise_estimate().calibration);
    std::vector<float> out(size_t(m_width) * m_height, 0.f);
    std::lock_guard<std::mutex> splat_lock(m_splat_lock);
    const bool splats = !m_splats.empty();
    for_each_tile_locked([&](const Tile& t) {
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                const size_t i = size_t(y) * m_width + x;
                if (!splats) {
                    out[i] = float(scale * std::sqrt(moment_variance_of_mean(m_pixels[i])));
                } else {
                    // Splats have no per-sample moments: the pixel's own replicate estimate (unbiased, noisier).
                    const double v = replicate_variance_of_mean(m_pixels[i], m_splats[i], m_splat_samples);
                    out[i] = v > 0.0 ? float(std::sqrt(v)) : 0.f;
                }
            }
    });
    return out;
}

Film::NoiseEstimate Film::noise_estimate() const {
    NoiseTally tally;
    std::lock_guard<std::mutex> splat_lock(m_splat_lock);
    const bool splats = !m_splats.empty();
    for_each_tile_locked([&](const Tile& t) {
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                const size_t i = size_t(y) * m_width + x;
                if (splats)
                    tally.add(m_pixels[i], m_splats[i], m_splat_samples);
                else
                    tally.add(m_pixels[i]);
            }
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

SplatAccum Film::splat(int x, int y) const {
    if (x < 0 || y < 0 || x >= m_width || y >= m_height) throw InvalidParameter("pixel outside the film");
    std::lock_guard<std::mutex> lock(m_splat_lock);
    return m_splats.empty() ? SplatAccum{} : m_splats[size_t(y) * m_width + x];
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
