#include "film/aov_film.h"

#include <cstdio>

#include <algorithm>

#include "core/error.h"

namespace candela {

namespace {

constexpr float k_background_depth = 1e10f;  // Cycles' Depth where nothing was hit

}  // namespace

const std::vector<std::pair<std::string, int>>& AovFilm::pass_specs() {
    static const std::vector<std::pair<std::string, int>> specs = {
        {"Depth", 1}, {"Normal", 3}, {"Albedo", 3}, {"IndexOB", 1}, {"IC Records", 1}};
    return specs;
}

std::vector<std::string> split_pass_list(const std::string& list) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start <= list.size()) {
        const size_t end = std::min(list.find(',', start), list.size());
        std::string name = list.substr(start, end - start);
        const size_t a = name.find_first_not_of(" \t"), b = name.find_last_not_of(" \t");
        if (a != std::string::npos) out.push_back(name.substr(a, b - a + 1));
        start = end + 1;
    }
    return out;
}

AovFilm::AovFilm(const Film& film, const std::vector<std::string>& passes)
    : m_width(film.width()), m_height(film.height()), m_tiles(film.tiles()) {
    for (const std::string& name : passes) {
        if (name == "Combined" || name == "Noise") continue;
        if (channels_of(name) == 0) {
            std::string valid = "Combined, Noise";
            for (const auto& s : pass_specs()) valid += ", " + s.first;
            throw InvalidParameter("passes: unknown render pass '" + name + "' (valid: " + valid +
                                   ", and BDPT's strategy images 'BDPT d<depth> s<s> t<t>[ unweighted]')");
        }
        if (!enabled(name)) m_enabled.push_back(name);
    }
    // Per-sample accumulation only for the passes accumulated from camera samples.
    if (std::any_of(m_enabled.begin(), m_enabled.end(), [](const std::string& n) { return !integrator_pass(n); }))
        m_pixels.resize(size_t(m_width) * m_height);
    m_tile_locks = std::make_unique<std::mutex[]>(m_tiles.size());
}

bool AovFilm::enabled(const std::string& name) const {
    return std::find(m_enabled.begin(), m_enabled.end(), name) != m_enabled.end();
}

void AovFilm::add_tile(size_t tile_index, const std::vector<AovAccum>& tile_pixels) {
    if (m_pixels.empty()) return;
    const Tile& t = m_tiles[tile_index];
    if (tile_pixels.size() != size_t(t.width()) * t.height()) throw InternalError("AOV tile buffer size mismatch");
    std::lock_guard<std::mutex> lock(m_tile_locks[tile_index]);
    for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) {
            AovAccum& p = m_pixels[size_t(y) * m_width + x];
            const AovAccum& q = tile_pixels[size_t(y - t.y0) * t.width() + (x - t.x0)];
            if (q.n == 0) continue;
            for (int c = 0; c < 3; ++c) {
                p.normal[c] += q.normal[c];
                p.albedo[c] += q.albedo[c];
            }
            if (p.n == 0) {  // the tile pass holding sample 0
                p.depth = q.depth;
                p.object_index = q.object_index;
            }
            p.n += q.n;
        }
}

bool AovFilm::strategy_pass(const std::string& name) {
    // "BDPT d<depth> s<s> t<t>" or the same + " unweighted" (integrators/bdpt/strategy_images.h).
    int d = -1, s = -1, t = -1, n = 0;
    if (std::sscanf(name.c_str(), "BDPT d%d s%d t%d%n", &d, &s, &t, &n) != 3 || d < 0 || s < 0 || t < 1) return false;
    const std::string rest = name.substr(size_t(n));
    return (rest.empty() || rest == " unweighted") && s + t == d + 2;
}

int AovFilm::channels_of(const std::string& name) {
    for (const auto& s : pass_specs())
        if (s.first == name) return s.second;
    return strategy_pass(name) ? 3 : 0;
}

bool AovFilm::integrator_pass(const std::string& name) { return name == "IC Records" || strategy_pass(name); }

void AovFilm::set_pass(const std::string& name, std::vector<float> values) {
    if (!enabled(name) || !integrator_pass(name)) return;
    const int ch = channels_of(name);
    if (values.size() != size_t(m_width) * m_height * size_t(ch))
        throw InternalError("integrator pass '" + name + "' has the wrong size");
    std::lock_guard<std::mutex> lock(m_integrator_lock);
    for (auto& [n, v] : m_integrator_passes)
        if (n == name) {
            v = std::move(values);
            return;
        }
    m_integrator_passes.emplace_back(name, std::move(values));
}

std::vector<float> AovFilm::get(const std::string& name, int* channels) const {
    *channels = 0;
    if (!enabled(name)) return {};
    *channels = channels_of(name);
    const int ch = *channels;
    if (integrator_pass(name)) {
        std::lock_guard<std::mutex> lock(m_integrator_lock);
        for (const auto& [n, v] : m_integrator_passes)
            if (n == name) return v;
        return std::vector<float>(size_t(m_width) * m_height * ch, 0.f);  // not written (yet): zeros
    }
    std::vector<float> out(size_t(m_width) * m_height * ch, 0.f);
    for (size_t i = 0; i < m_tiles.size(); ++i) {
        const Tile& t = m_tiles[i];
        std::lock_guard<std::mutex> lock(m_tile_locks[i]);
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                const size_t k = size_t(y) * m_width + x;
                const AovAccum& p = m_pixels[k];
                float* o = out.data() + k * ch;
                if (name == "Depth") {
                    o[0] = p.depth != 0.f ? p.depth : k_background_depth;
                } else if (name == "IndexOB") {
                    o[0] = p.object_index;
                } else if (p.n > 0) {
                    const double* sum = name == "Normal" ? p.normal : p.albedo;
                    for (int c = 0; c < 3; ++c) o[c] = float(sum[c] / p.n);
                }
            }
    }
    return out;
}

}  // namespace candela
