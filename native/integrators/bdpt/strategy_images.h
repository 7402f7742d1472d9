// Per-strategy images of bidirectional path tracing (option bdpt_strategy_images; Veach 1997, fig. 10.3): for every
// path depth d (scattering vertices − 1, so d = 0 is direct light) up to a chosen maximum and every strategy (s, t)
// with s + t = d + 2, two images:
//   weighted     w_{s,t} · C_{s,t}: what the strategy contributes to the render; over (s, t) these sum to the
//                image's depth-d part, so they show which strategy carries which light;
//   unweighted   C_{s,t}: what the strategy alone estimates. Where it can produce every path of depth d (no delta
//                vertex in its way, a light it can hit for s = 0, a lens it can reach for t = 1), it is an unbiased
//                image of all depth-d light by itself, and its noise shows why MIS prefers it or not.
// Contributions land in the camera sample's own pixel (t ≥ 2) or in the pixel that holds the t = 1 splat (a
// one-pixel box filter: the images are for looking at, the render keeps its filter), normalised by the camera
// samples per pixel as the render's splats are. Per-tile buffers are merged in tile order: deterministic.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/vec.h"

namespace candela {

struct StrategyId {
    int depth, s, t;
};

class StrategyImages {
public:
    struct Record {
        uint32_t image;  // 2·strategy (+1 unweighted)
        int x, y;        // film pixel
        Color value;
    };
    using Buffer = std::vector<Record>;

    /// The strategies of depths 0..max_depth, in order of depth then s (t ≥ 1): depth 0 has (0, 2) and (1, 1), an
    /// emitter joined to the lens (zero for emitters no camera ray can hit: strategy.h, lens_strategy).
    static std::vector<StrategyId> strategies(int max_depth);
    /// The pass name of strategy `id`: "BDPT d1 s1 t2" (weighted) and "BDPT d1 s1 t2 unweighted".
    static std::string name(const StrategyId& id, bool unweighted);
    /// Float32 per pixel the images take: 3 channels × 2 images per strategy.
    static double bytes_per_pixel(int max_depth);

    StrategyImages(int max_depth, int width, int height, int origin_x, int origin_y);

    int max_depth() const { return m_max_depth; }
    /// The image pair of strategy (s, t) at depth s + t − 2, or −1 if it is not recorded.
    int strategy_index(int s, int t) const;
    /// Records strategy (s, t)'s contribution at full-frame raster position `raster` (t = 1) or in full-frame pixel
    /// (fx, fy) (t ≥ 2), weighted and unweighted.
    void record(Buffer& out, int s, int t, const Color& unweighted, float weight, Vec2 raster, bool splat, int fx,
                int fy) const;
    /// Adds one tile's buffer; `samples` is the camera samples per pixel of the full frame the buffer's pass adds
    /// (the same count the render's splats are normalised by).
    void merge(const Buffer& buffer, double samples);
    /// Every image as (name, RGB float32 rows bottom to top), normalised by the samples merged so far.
    std::vector<std::pair<std::string, std::vector<float>>> images() const;

private:
    int m_max_depth, m_width, m_height, m_origin_x, m_origin_y;
    std::vector<StrategyId> m_ids;
    std::vector<int> m_first;   // m_first[depth]: index of (0, depth + 2)
    std::vector<double> m_sum;  // image-major, then pixel, then RGB
    double m_samples = 0.0;
};

}  // namespace candela
