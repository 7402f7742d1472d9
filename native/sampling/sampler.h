// Pixel samplers: a closed family of value types behind std::variant. A sampler is positioned at
// (pixel, sample index); every value it hands out is a pure function of (seed, pixel, sample index,
// dimension), so images never depend on the thread count, the tile order or what was asked before.
//
// Dimensions are named (Dim): the camera uses Filter (2-D) and Lens (2-D, reserved), every bounce uses
// LightSelect (1-D), Light (2-D), Bsdf (2-D), Roulette (1-D) and BsdfLobe (1-D). dimension_index() maps a name and a
// bounce to a fixed coordinate index of the sample vector; a 2-D request at index d covers d and d + 1.
// A 2-D request is one 2-D pattern (a √N×√N jittered grid, an N-rooks pair, a Sobol (0,2)-sequence pair…),
// never two unrelated 1-D patterns.
//
// Samplers ("sampler" params key; the add-on's enum identifiers):
//   RANDOM      independent uniform values, hashed from (seed, pixel, index, dimension).
//   STRATIFIED  jittered: one sample per stratum; 2-D requests use an nx×ny grid (nx·ny = N with nx the
//               largest divisor ≤ √N if ny ≤ 2nx; otherwise nx = ⌊√N⌋, ny = ⌊N/nx⌋ and the few sample indices
//               beyond nx·ny are independent), 1-D requests N strata; strata are visited in a random
//               permutation per (pixel, dimension), so dimensions do not correlate.
//   NROOKS      Latin hypercube: N strata on each axis, a random permutation per (pixel, dimension, axis).
//   HALTON      Φ_{p_d}(i) in the d-th prime base, Owen-scrambled per (pixel, dimension) (hashed digit
//               permutations seeded by the preceding digits).
//   HAMMERSLEY  (i/N, Φ_2(i), Φ_3(i), …), each coordinate Owen-scrambled per (pixel, dimension).
//   SOBOL       Burley 2020: each 1-D or 2-D request is the (0,2)-sequence formed by Sobol dimensions 0 and 1,
//               with its index shuffled (base-2 Owen scramble of the index) and its values Owen-scrambled by
//               hashes of (pixel, dimension), so different requests are independent padded patterns.
// Halton and Hammersley use radical inverses for the first k_max_radical_inverse_dims dimensions (a path of
// about 40 bounces) and independent hashed values beyond; a sample index ≥ N (the fixed sample count) also
// falls back to independent values for the samplers that need N. All values are in [0, 1).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"
#include "sampling/low_discrepancy.h"
#include "sampling/sobol_x8.h"

namespace candela {

/// Named sample dimensions. Camera dimensions are absolute; the per-bounce ones are offsets to which
/// dimension_index() adds k_bounce_dimensions per bounce.
enum class Dim : uint32_t {
    Filter = 0,       // 2-D: offset inside the pixel filter
    Lens = 2,         // 2-D: point on the lens (reserved: the pinhole camera does not draw it)
    LightSelect = 4,  // 1-D per bounce: which light NEE samples
    Light = 5,        // 2-D per bounce: point on that light
    Bsdf = 7,         // 2-D per bounce: BSDF direction
    Roulette = 9,     // 1-D per bounce: Russian roulette
    BsdfLobe = 10,    // 1-D per bounce: which lobe of a multi-lobe BSDF is sampled
};
inline constexpr uint32_t k_camera_dimensions = 4;
inline constexpr uint32_t k_bounce_dimensions = 7;
/// Halton and Hammersley use radical inverses below this dimension, independent values from here on.
inline constexpr uint32_t k_max_radical_inverse_dims = 256;

/// The coordinate index of a named dimension at a bounce (camera dimensions ignore the bounce).
constexpr uint32_t dimension_index(Dim d, int bounce = 0) {
    const uint32_t base = static_cast<uint32_t>(d);
    return base < k_camera_dimensions ? base : base + k_bounce_dimensions * static_cast<uint32_t>(bounce);
}

/// State shared by every sampler: the pixel sample being drawn and the next dimension for the
/// sequential get_1d()/get_2d() interface.
class SamplerBase {
public:
    SamplerBase(uint64_t seed, int samples_per_pixel)
        : m_seed(seed), m_spp(samples_per_pixel < 1 ? 1u : uint32_t(samples_per_pixel)) {}

    void start_pixel_sample(uint32_t px, uint32_t py, uint32_t sample_index) {
        set_pixel_sample(px, py, sample_index);
        // One hash per pixel sample; every independent value is then a single SplitMix64 step from it.
        m_sample_key = mix64(m_pixel_key ^ (uint64_t(sample_index) * 0xd1b54a32d192ed03ULL + 0x73616d706c65ULL));
    }
    uint32_t take_dims(uint32_t n) {
        const uint32_t d = m_next_dim;
        m_next_dim += n;
        return d;
    }
    uint32_t samples_per_pixel() const { return m_spp; }
    /// The full-frame pixel the sampler is positioned at.
    uint32_t pixel_x() const { return uint32_t(m_pixel); }
    uint32_t pixel_y() const { return uint32_t(m_pixel >> 32); }
    /// A key unique to the current pixel sample — a function of (seed, pixel, sample index), so of the noise
    /// replicate too — for random streams an integrator draws outside the sampler's dimensions (the irradiance
    /// cache seeds a record's gather with it). It does not move the sampler.
    uint64_t sample_stream_key() const { return hash_combine(m_pixel_key, uint64_t(m_index) + 0x6b6579ULL); }

protected:
    /// start_pixel_sample without the sample key (for samplers that never draw independent values).
    void set_pixel_sample(uint32_t px, uint32_t py, uint32_t sample_index) {
        const uint64_t pixel = (uint64_t(py) << 32) | px;
        if (pixel != m_pixel || !m_have_pixel) {  // a pixel's samples come in runs: hash it once per run
            m_pixel_key = hash_values(m_seed, pixel, 0x706978656cULL);
            m_pixel = pixel;
            m_have_pixel = true;
        }
        m_index = sample_index;
        m_next_dim = k_camera_dimensions;
    }
    /// Seed of one randomisation (purpose 0–3) of one dimension of this pixel: distinct for every (dim, purpose)
    /// (a Weyl step from the random pixel key). Not itself mixed: every consumer (owen_scramble_base2,
    /// permute_index) hashes its seed first, so one hash per randomisation suffices.
    uint64_t dim_key(uint32_t dim, uint32_t purpose = 0) const {
        return m_pixel_key + ((uint64_t(dim) << 2 | (purpose & 3u)) + 1u) * 0x9e3779b97f4a7c15ULL;
    }
    /// 64 independent bits for coordinate `dim` of this pixel sample (SplitMix64 from the sample key).
    uint64_t independent_bits(uint32_t dim) const {
        return mix64(m_sample_key + (uint64_t(dim) + 1u) * 0x9e3779b97f4a7c15ULL);
    }
    float independent_1d(uint32_t dim) const { return float(independent_bits(dim) >> 40) * 0x1p-24f; }
    Vec2 independent_2d(uint32_t dim) const {
        const uint64_t h = independent_bits(dim);
        return {float(h >> 40) * 0x1p-24f, float((h >> 8) & 0xffffffu) * 0x1p-24f};
    }

    uint64_t m_seed;
    uint32_t m_spp;
    uint64_t m_pixel_key = 0;
    uint64_t m_pixel = 0;  // the (py, px) word m_pixel_key was hashed from
    bool m_have_pixel = false;
    uint64_t m_sample_key = 0;
    uint32_t m_index = 0;
    uint32_t m_next_dim = k_camera_dimensions;
};

class IndependentSampler : public SamplerBase {
public:
    using SamplerBase::SamplerBase;
    float sample_1d(uint32_t dim) const { return independent_1d(dim); }
    Vec2 sample_2d(uint32_t dim) const { return independent_2d(dim); }
};

class StratifiedSampler : public SamplerBase {
public:
    StratifiedSampler(uint64_t seed, int samples_per_pixel);
    float sample_1d(uint32_t dim) const;
    Vec2 sample_2d(uint32_t dim) const;
    uint32_t grid_x() const { return m_nx; }
    uint32_t grid_y() const { return m_ny; }

private:
    uint32_t m_nx, m_ny;  // 2-D strata grid; m_nx·m_ny ≤ N
};

class NRooksSampler : public SamplerBase {
public:
    using SamplerBase::SamplerBase;
    float sample_1d(uint32_t dim) const;
    Vec2 sample_2d(uint32_t dim) const;
};

class HaltonSampler : public SamplerBase {
public:
    using SamplerBase::SamplerBase;
    float sample_1d(uint32_t dim) const;
    Vec2 sample_2d(uint32_t dim) const { return {sample_1d(dim), sample_1d(dim + 1)}; }
};

class HammersleySampler : public SamplerBase {
public:
    using SamplerBase::SamplerBase;
    float sample_1d(uint32_t dim) const;
    Vec2 sample_2d(uint32_t dim) const { return {sample_1d(dim), sample_1d(dim + 1)}; }
};

/// The per-bounce values a path vertex uses (the named dimensions LightSelect, Light, Bsdf, Roulette, BsdfLobe).
struct BounceSample {
    float light_select = 0.5f;
    Vec2 light{0.5f, 0.5f};
    Vec2 bsdf{0.5f, 0.5f};
    float roulette = 0.5f;
    float lobe = 0.5f;
};
/// Which of BounceSample's values a vertex needs (the BSDF direction always).
enum BounceNeeds : unsigned { k_need_light_select = 1, k_need_light = 2, k_need_roulette = 4, k_need_lobe = 8 };

class SobolSampler : public SamplerBase {
public:
    SobolSampler(uint64_t seed, int samples_per_pixel) : SamplerBase(seed, samples_per_pixel) { set_filter_seeds(); }
    void start_pixel_sample(uint32_t px, uint32_t py, uint32_t sample_index) {
        set_pixel_sample(px, py, sample_index);  // no sample key: every Sobol value is a function of the index
        m_reversed_index = reverse_bits32(sample_index);
        m_premixed_index = sobol_premix(m_reversed_index);
        m_pixel_seed = uint32_t(m_pixel_key);
        m_ahead_bounce = -1;
        if (m_pixel_seed != m_cache_pixel_seed) {  // the cached seeds are a function of the pixel seed alone
            m_cached_bounces = 0;
            m_cache_pixel_seed = m_pixel_seed;
            set_filter_seeds();
        }
    }
    // Burley 2020, evaluated in the bit-reversed domain where the scrambles are burley_lsb_hash and sobol_dim0
    // is the reversal itself (sampling/sobol_x8.h spells the steps out):
    //   shuffled index  i = reverse(lsb_hash(reverse(index), s_shuffle)),
    //   x = owen_scramble(sobol_dim0(i), s_first) = reverse(lsb_hash(i, s_first)),
    //   y = owen_scramble(sobol_dim1(i), s_second) = reverse(lsb_hash(sobol_dim1_reversed(i), s_second)):
    // the same values as the textbook composition with three bit reversals instead of seven.
    float sample_1d(uint32_t dim) const { return sobol_lane(m_pixel_seed, m_reversed_index, dim, false); }
    Vec2 sample_2d(uint32_t dim) const {
        if (dim == dimension_index(Dim::Filter)) {  // every sample draws it: its seeds are kept per pixel run
            const FilterSeeds& f = m_filter_seeds;
            const uint32_t i = reverse_bits32(burley_lsb_hash_tail(m_premixed_index, f.shuffle, f.shuffle_m2));
            return {fixed_to_float(reverse_bits32(burley_lsb_hash_tail(sobol_premix(i), f.x, f.x_m2))),
                    fixed_to_float(
                        reverse_bits32(burley_lsb_hash_tail(sobol_premix(sobol_dim1_reversed(i)), f.y, f.y_m2)))};
        }
        const uint32_t i = reverse_bits32(burley_lsb_hash(m_reversed_index, sobol_seed(m_pixel_seed, dim, 1)));
        return {
            fixed_to_float(reverse_bits32(burley_lsb_hash(i, sobol_seed(m_pixel_seed, dim, 2)))),
            fixed_to_float(reverse_bits32(burley_lsb_hash(sobol_dim1_reversed(i), sobol_seed(m_pixel_seed, dim, 3))))};
    }
    /// Every per-bounce value of `bounce` in one 8-lane batch: the same values as the single draws. The batch's
    /// seeds depend on the pixel and the bounce only, and a pixel's samples come in runs: the seeds of the first
    /// k_cached_bounces bounces are computed on a run's first visit to a bounce and reused for its other samples.
    BounceSample sample_bounce(int bounce) {
        if (bounce == m_ahead_bounce) return m_ahead;  // drawn with the previous bounce of this sample
        if (unsigned(bounce) + 1u < unsigned(k_cached_bounces)) {
            // A path that reaches this bounce usually reaches the next: draw both now. The two batches are
            // independent dependency chains (~5 multiply latencies each), which the core overlaps, so the next
            // vertex gets its values without waiting for a chain of its own.
            const SobolSeedsX8& seeds = cached_bounce_seeds(bounce);
            const SobolSeedsX8& next = cached_bounce_seeds(bounce + 1);
            const BounceSample b = bounce_batch(seeds);
            m_ahead = bounce_batch(next);
            m_ahead_bounce = bounce + 1;
            return b;
        }
        if (unsigned(bounce) < unsigned(k_cached_bounces)) return bounce_batch(cached_bounce_seeds(bounce));
        return sample_bounce_uncached(bounce);
    }
    /// The same values with the seeds computed on the spot (deep bounces; tests compare the two).
    BounceSample sample_bounce_uncached(int bounce) const {
        SobolSeedsX8 seeds;
        bounce_seeds(bounce, seeds);
        return bounce_batch(seeds);
    }
    /// Bounces whose batch seeds are cached per pixel run (4·32 bytes each: the sampler is ~1.2 KB, copied only
    /// when a tile pass makes its replicate samplers). Deeper bounces compute their seeds on every draw.
    static constexpr int k_cached_bounces = 8;

protected:
    /// The scramble seeds of request `dim` in this pixel (index shuffle, first and second coordinate).
    struct Seeds {
        uint32_t shuffle, first, second;
    };
    Seeds seeds(uint32_t dim) const {
        return {sobol_seed(m_pixel_seed, dim, 1), sobol_seed(m_pixel_seed, dim, 2), sobol_seed(m_pixel_seed, dim, 3)};
    }

private:
    // The batch's lanes: LightSelect, Light x, Light y, Bsdf x, Bsdf y, Roulette, BsdfLobe, LightSelect again.
    static constexpr uint32_t k_bounce_y_lanes = (1u << 2) | (1u << 4);  // light.y, bsdf.y
    /// The seeds' hash inputs (4·dim + purpose)·φ of bounce 0's lanes; bounce b adds 4·k_bounce_dimensions·b·φ to
    /// every lane (mod 2³², like sobol_seed's own arithmetic), folded into the broadcast pixel seed.
    struct BounceWords {
        uint32_t shuffle[8], value[8];
    };
    static constexpr BounceWords bounce_words() {
        constexpr uint32_t dims[8] = {uint32_t(Dim::LightSelect), uint32_t(Dim::Light),      uint32_t(Dim::Light),
                                      uint32_t(Dim::Bsdf),        uint32_t(Dim::Bsdf),       uint32_t(Dim::Roulette),
                                      uint32_t(Dim::BsdfLobe),    uint32_t(Dim::LightSelect)};
        BounceWords w{};
        for (int k = 0; k < 8; ++k) {
            w.shuffle[k] = (4u * dims[k] + 1u) * k_sobol_seed_step;
            w.value[k] = (4u * dims[k] + (((k_bounce_y_lanes >> k) & 1u) != 0 ? 3u : 2u)) * k_sobol_seed_step;
        }
        return w;
    }
    static_assert(uint32_t(Dim::LightSelect) >= k_camera_dimensions, "every batch lane is a per-bounce dimension");
    void bounce_seeds(int bounce, SobolSeedsX8& seeds) const {
        static constexpr BounceWords words = bounce_words();
        const uint32_t base = m_pixel_seed + uint32_t(bounce) * (4u * k_bounce_dimensions * k_sobol_seed_step);
        sobol_seeds_x8_words(base, words.shuffle, words.value, seeds);
    }
    const SobolSeedsX8& cached_bounce_seeds(int bounce) {
        SobolSeedsX8& seeds = m_seed_cache[bounce];
        if (!((m_cached_bounces >> bounce) & 1u)) {
            bounce_seeds(bounce, seeds);
            m_cached_bounces |= 1u << bounce;
        }
        return seeds;
    }
    BounceSample bounce_batch(const SobolSeedsX8& seeds) const {
        float v[8];
        sobol_x8_seeded(seeds, m_premixed_index, k_bounce_y_lanes, v);
        return {v[0], {v[1], v[2]}, {v[3], v[4]}, v[5], v[6]};
    }

    struct FilterSeeds {  // seeds (and burley_m2 of them) of the Filter request: shuffle, x, y
        uint32_t shuffle, shuffle_m2, x, x_m2, y, y_m2;
    };
    void set_filter_seeds() {
        const Seeds s = seeds(dimension_index(Dim::Filter));
        m_filter_seeds = {s.shuffle, burley_m2(s.shuffle), s.first, burley_m2(s.first), s.second, burley_m2(s.second)};
    }

    uint32_t m_reversed_index = 0;    // the scrambles work on bit-reversed words: reverse the index once
    uint32_t m_premixed_index = 0;    // sobol_premix(m_reversed_index): the shuffle hash's first step
    uint32_t m_pixel_seed = 0;        // 32 random bits of the pixel key: sobol_seed() derives every scramble from it
    uint32_t m_cache_pixel_seed = 0;  // the pixel seed m_seed_cache belongs to
    uint32_t m_cached_bounces = 0;    // bit b: m_seed_cache[b] holds bounce b's seeds
    FilterSeeds m_filter_seeds{};     // of m_cache_pixel_seed
    int m_ahead_bounce = -1;          // this pixel sample's bounce whose values m_ahead holds (−1: none)
    BounceSample m_ahead;
    SobolSeedsX8 m_seed_cache[k_cached_bounces] = {};
    static_assert(k_cached_bounces <= 32, "m_cached_bounces has one bit per cached bounce");
};

/// The values of one bounce: the Sobol sampler draws them all in one batch, the others only those needed.
template <class S>
BounceSample draw_bounce(S& s, int bounce, unsigned needs) {
    if constexpr (std::is_same_v<S, SobolSampler>) {
        return s.sample_bounce(bounce);
    } else {
        BounceSample b;
        if (needs & k_need_light_select) b.light_select = s.sample_1d(dimension_index(Dim::LightSelect, bounce));
        if (needs & k_need_light) b.light = s.sample_2d(dimension_index(Dim::Light, bounce));
        b.bsdf = s.sample_2d(dimension_index(Dim::Bsdf, bounce));
        if (needs & k_need_roulette) b.roulette = s.sample_1d(dimension_index(Dim::Roulette, bounce));
        if (needs & k_need_lobe) b.lobe = s.sample_1d(dimension_index(Dim::BsdfLobe, bounce));
        return b;
    }
}

using Sampler =
    std::variant<IndependentSampler, StratifiedSampler, NRooksSampler, HaltonSampler, HammersleySampler, SobolSampler>;

/// Names accepted by make_sampler (the add-on's `sampler` enum identifiers).
std::vector<std::string> sampler_names();
/// samples_per_pixel is the N of the strata / the Hammersley set; sample indices are expected in [0, N).
Sampler make_sampler(const std::string& name, uint64_t seed, int samples_per_pixel);

inline void start_pixel_sample(Sampler& s, uint32_t px, uint32_t py, uint32_t index) {
    std::visit([&](auto& v) { v.start_pixel_sample(px, py, index); }, s);
}

/// Value of coordinate `dim` (1-D) or coordinates dim, dim + 1 (2-D) of the current pixel sample.
inline float sample_1d_at(const Sampler& s, uint32_t dim) {
    return std::visit([&](const auto& v) { return v.sample_1d(dim); }, s);
}
inline Vec2 sample_2d_at(const Sampler& s, uint32_t dim) {
    return std::visit([&](const auto& v) { return v.sample_2d(dim); }, s);
}

/// Named dimensions: the interface integrators use.
inline float get_1d(const Sampler& s, Dim d, int bounce = 0) { return sample_1d_at(s, dimension_index(d, bounce)); }
inline Vec2 get_2d(const Sampler& s, Dim d, int bounce = 0) { return sample_2d_at(s, dimension_index(d, bounce)); }
inline Vec2 get_pixel_2d(const Sampler& s) { return get_2d(s, Dim::Filter); }

/// The same on a concrete sampler type: integrators templated on it inline the draw.
template <class S, class = std::enable_if_t<!std::is_same_v<S, Sampler>>>
inline float get_1d(const S& s, Dim d, int bounce = 0) {
    return s.sample_1d(dimension_index(d, bounce));
}
template <class S, class = std::enable_if_t<!std::is_same_v<S, Sampler>>>
inline Vec2 get_2d(const S& s, Dim d, int bounce = 0) {
    return s.sample_2d(dimension_index(d, bounce));
}

/// Sequential interface: successive dimensions from k_camera_dimensions on (the same layout as the named
/// per-bounce dimensions when drawn in the order LightSelect, Light, Bsdf, Roulette, BsdfLobe).
inline float get_1d(Sampler& s) {
    return std::visit([](auto& v) { return v.sample_1d(v.take_dims(1)); }, s);
}
inline Vec2 get_2d(Sampler& s) {
    return std::visit([](auto& v) { return v.sample_2d(v.take_dims(2)); }, s);
}

}  // namespace candela
