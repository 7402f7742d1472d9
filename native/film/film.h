// The film: per-pixel accumulation of camera-path samples (filter importance sampled, so each sample
// has weight 1 and lands in its own pixel) plus splats from anywhere on the image (light tracing,
// bidirectional and Metropolis contributions). Pixels live in tiles; a worker adds a whole tile's pass
// under that tile's lock, and readers copy tile by tile, so progressive display never sees half-written
// pixels. Sums are double precision and a pixel's sum depends only on its own samples, added in sample
// order: images do not depend on thread count.
//
// Splats. A work item (a batch of light paths, say) collects its contributions at raster positions in a
// SplatBuffer; buffers are merged into the film one at a time in work-item order (core/parallel_ordered.h), so
// the sums are the same for every thread count. A splat is spread over the pixels of the filter's footprint
// with the weights PixelFilter::pdf gives, the density with which filter importance sampling places camera
// samples: a pixel then receives in expectation what camera samples estimate for it, and splatted and camera
// contributions agree. Each merge also says how many samples its splats are normalised by, per noise
// replicate (`add_splats(buffer, samples)`): the image is Σ splats / Σ samples, so a light tracer counts light
// paths per pixel, a bidirectional tracer camera samples per pixel. The film keeps the splats' luminance per
// replicate too, so the noise estimate covers splatted light.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/vec.h"
#include "film/noise_estimate.h"

namespace candela {

struct PixelAccum {
    double r = 0, g = 0, b = 0, a = 0;
    double lum_sq = 0;                        // Σ luminance² (running moments: the shape of the per-pixel noise)
    double rep_lum[k_noise_replicates] = {};  // Σ luminance per replicate (noise_estimate.h)
    uint32_t rep_n[k_noise_replicates] = {};
    uint32_t n = 0;

    /// `replicate` is noise_replicate_of(sample index): which independent randomisation drew the sample.
    void add(const Color& c, float alpha, uint32_t replicate) {
        r += c.x;
        g += c.y;
        b += c.z;
        a += alpha;
        const double l = luminance(c);
        lum_sq += l * l;
        rep_lum[replicate] += l;
        ++rep_n[replicate];
        ++n;
    }
    void add(const PixelAccum& o) {
        r += o.r;
        g += o.g;
        b += o.b;
        a += o.a;
        lum_sq += o.lum_sq;
        n += o.n;
        for (uint32_t k = 0; k < k_noise_replicates; ++k) {
            rep_lum[k] += o.rep_lum[k];
            rep_n[k] += o.rep_n[k];
        }
    }
    /// Σ luminance of the samples (luminance is linear in RGB).
    double lum_sum() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
};

struct Tile {
    int x0, y0, x1, y1;  // film pixel range, x1/y1 exclusive
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

/// Splatted contributions of one pixel: their sums, and their luminance per noise replicate.
struct SplatAccum {
    double r = 0, g = 0, b = 0;
    double rep_lum[k_noise_replicates] = {};
    bool any() const { return r != 0.0 || g != 0.0 || b != 0.0; }
};

/// Contributions a work item deposits anywhere on the image, at full-frame raster positions, until the film
/// merges them (Film::add_splats). `replicate` is the noise replicate of the sample that made the contribution.
class SplatBuffer {
public:
    struct Entry {
        float x, y;
        Color value;
        uint32_t replicate;
    };
    void add(Vec2 raster, const Color& value, uint32_t replicate) {
        m_entries.push_back({raster.x, raster.y, value, replicate});
    }
    const std::vector<Entry>& entries() const { return m_entries; }
    size_t size() const { return m_entries.size(); }
    void clear() { m_entries.clear(); }

private:
    std::vector<Entry> m_entries;
};

class PixelFilter;

class Film {
public:
    /// width × height pixels; (origin_x, origin_y) is the film's position in the full frame (a border).
    Film(int width, int height, int origin_x = 0, int origin_y = 0, int tile_size = 32);

    int width() const { return m_width; }
    int height() const { return m_height; }
    int origin_x() const { return m_origin_x; }
    int origin_y() const { return m_origin_y; }
    const std::vector<Tile>& tiles() const { return m_tiles; }

    /// Adds a tile's worth of accumulated samples (row-major within the tile).
    void add_tile(size_t tile_index, const std::vector<PixelAccum>& tile_pixels);
    /// Merges one buffer of splats, spread over `filter`'s footprint (pixels outside the film are dropped), and
    /// counts `samples[r]` more samples of replicate r that the splats are normalised by.
    void add_splats(const SplatBuffer& buffer, const PixelFilter& filter, const double (&samples)[k_noise_replicates]);
    /// Samples the splats are normalised by, per replicate.
    double splat_samples(uint32_t replicate) const;
    bool has_splats() const;

    /// "Combined" as RGBA float32, rows bottom to top (Blender's order); (W·H·4) floats. A pixel is its camera
    /// samples' mean plus Σ splats / Σ splat samples; its alpha is the camera samples' (film transparency,
    /// holdouts), or 1 where only splats reached the film.
    std::vector<float> combined() const;
    /// "Noise": per pixel, the estimated standard error of the pixel's mean luminance: the running-moment
    /// figure √(s²/n) scaled by the image's replicate calibration √κ (noise_estimate.h), so that its mean
    /// square is the replicate estimate (0 until a pixel has two samples).
    std::vector<float> noise() const;

    /// Whole-image error estimate (noise_estimate.h): relative RMSE from independent replicates, its upper
    /// confidence bound and the independent-sample (moment) figure.
    using NoiseEstimate = candela::NoiseEstimate;
    NoiseEstimate noise_estimate() const;
    /// A copy of one pixel's accumulated samples (film coordinates, y from the bottom), for diagnostics and tests.
    PixelAccum pixel(int x, int y) const;
    SplatAccum splat(int x, int y) const;
    /// Samples taken per pixel (minimum over the film).
    uint32_t min_samples() const;

private:
    template <typename F>
    void for_each_tile_locked(F&& f) const;

    int m_width, m_height, m_origin_x, m_origin_y;
    std::vector<Tile> m_tiles;
    std::vector<PixelAccum> m_pixels;  // row-major, bottom row first
    std::vector<SplatAccum> m_splats;  // empty until the first add_splats
    double m_splat_samples[k_noise_replicates] = {};
    std::unique_ptr<std::mutex[]> m_tile_locks;
    mutable std::mutex m_splat_lock;
};

}  // namespace candela
