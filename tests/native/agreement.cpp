#include "agreement.h"

#include <cmath>

namespace candela::test {

namespace {

double pixel_luminance(const RenderResult& r, size_t i) {
    return 0.2126 * r.rgba[4 * i] + 0.7152 * r.rgba[4 * i + 1] + 0.0722 * r.rgba[4 * i + 2];
}

/// Mean and variance of the mean over the seeds of the average luminance of the pixels `in` selects.
template <class In>
void seed_statistics(const std::vector<RenderResult>& set, In in, double* mean, double* var_of_mean) {
    std::vector<double> values;
    for (const RenderResult& r : set) {
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < size_t(r.width) * r.height; ++i)
            if (in(i, r)) {
                sum += pixel_luminance(r, i);
                ++n;
            }
        values.push_back(n ? sum / double(n) : 0.0);
    }
    const double m = double(values.size());
    double mu = 0.0;
    for (double v : values) mu += v;
    mu /= m;
    double ss = 0.0;
    for (double v : values) ss += (v - mu) * (v - mu);
    *mean = mu;
    *var_of_mean = m > 1 ? ss / (m - 1) / m : 0.0;
}

}  // namespace

Agreement compare_seed_sets(const std::vector<RenderResult>& a, const std::vector<RenderResult>& b, int block,
                            const std::vector<uint8_t>* mask) {
    Agreement out;
    const int w = a.front().width, h = a.front().height;
    auto masked = [&](size_t i) { return !mask || (*mask)[i] != 0; };
    double va = 0.0, vb = 0.0;
    seed_statistics(
        a, [&](size_t i, const RenderResult&) { return masked(i); }, &out.mean_a, &va);
    seed_statistics(
        b, [&](size_t i, const RenderResult&) { return masked(i); }, &out.mean_b, &vb);
    out.mean_z = (out.mean_a - out.mean_b) / std::sqrt(std::max(va + vb, 1e-300));
    for (int by = 0; by + block <= h; by += block)
        for (int bx = 0; bx + block <= w; bx += block) {
            auto in_block = [&](size_t i, const RenderResult&) {
                const int x = int(i % size_t(w)), y = int(i / size_t(w));
                return x >= bx && x < bx + block && y >= by && y < by + block && masked(i);
            };
            bool any = false;
            for (int y = by; y < by + block; ++y)
                for (int x = bx; x < bx + block; ++x) any |= masked(size_t(y) * w + x);
            if (!any) continue;
            double ma, mb, sa, sb;
            seed_statistics(a, in_block, &ma, &sa);
            seed_statistics(b, in_block, &mb, &sb);
            const double z = (sa + sb) > 0.0 ? (ma - mb) / std::sqrt(sa + sb) : (ma == mb ? 0.0 : 1e9);
            ++out.blocks;
            if (std::fabs(z) > std::fabs(out.worst_block_z)) {
                out.worst_block_z = z;
                out.worst_block = std::to_string(bx) + "," + std::to_string(by);
            }
        }
    return out;
}

SeedMean seed_mean(const std::vector<RenderResult>& set) {
    SeedMean out;
    double var = 0.0;
    seed_statistics(
        set, [](size_t, const RenderResult&) { return true; }, &out.mean, &var);
    out.standard_error = std::sqrt(var);
    return out;
}

std::vector<RenderResult> render_seeds(const SceneArrays& arrays, const Params& params, int m) {
    std::vector<RenderResult> out;
    for (int s = 1; s <= m; ++s) {
        Params p = params;
        p.set("seed", int64_t(s));
        out.push_back(render(arrays, p));
    }
    return out;
}

}  // namespace candela::test
