#include "lights/environment_bake.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/math.h"
#include "core/parallel.h"
#include "texture/shader_program.h"

namespace candela {

namespace {

constexpr uint32_t k_max_width = 2048, k_max_bilinear = 2048, k_default_width = 256, k_min_width = 32;
constexpr uint32_t k_max_sub = 4;  // sub-samples per cell and axis, at most
constexpr float k_floor = 1e-3f;   // share of the mean luminance every direction keeps in the plain map
// The compensated map keeps L − mean only where it exceeds 10⁻⁴ of the mean: a constant image's knots equal its
// computed mean up to rounding, and must give an empty map, not one shaped by rounding noise.
constexpr float k_compensation_margin = 1e-4f;

/// max(x − mean, 0), 0 within the margin.
float compensate(float x, float mean) {
    const float d = x - mean;
    return d > k_compensation_margin * mean ? d : 0.f;
}

/// Whether register `reg` of the program is the plain view direction (so an image it indexes has its texel grid
/// on the map's: the knots at texel centres). A mapped or rotated vector is not.
bool plain_direction(const ShaderLibrary& lib, uint32_t program, uint32_t reg) {
    const ShaderOp& v = lib.op(program, reg);
    if (v.code != ShaderOpCode::Coord || v.i[1] != 0) return false;
    const CoordKind kind = CoordKind(v.i[0]);
    return kind == CoordKind::Generated || kind == CoordKind::Incoming || kind == CoordKind::Object;
}

/// The images the program reads: the widest and tallest, and whether all have one size, are read with Linear (or
/// Cubic) interpolation and are indexed by the plain view direction — the case of the bilinear map. (A rotated
/// image's filtered radiance is not bilinear on the map's grid: the integrated piecewise-constant map, with 2 × 2
/// points per texel, then cannot miss a bright texel between knots.)
struct ImagesRead {
    uint32_t w = 0, h = 0;
    bool bilinear = false;
};

ImagesRead images_read(const ShaderLibrary& lib, uint32_t program) {
    ImagesRead r;
    bool any = false, same = true, linear = true;
    for (uint32_t k = 0; k < lib.program_size(program); ++k) {
        const ShaderOp& op = lib.op(program, k);
        if (op.code != ShaderOpCode::Image && op.code != ShaderOpCode::ImageAlpha) continue;
        const ImageTexture& t = lib.textures()[op.i[0]];
        if (any && (t.width != r.w || t.height != r.h)) same = false;
        r.w = std::max(r.w, t.width);
        r.h = std::max(r.h, t.height);
        linear =
            linear && TexInterpolation(op.i[1]) != TexInterpolation::Closest && plain_direction(lib, program, op.a);
        any = true;
    }
    r.bilinear = any && same && linear && r.w >= 2 && r.h >= 2 && r.w <= k_max_bilinear && r.h <= k_max_bilinear;
    return r;
}

/// Bake width of the piecewise-constant map: the image's width (clamped), else a default.
uint32_t bake_width(uint32_t image_width) {
    uint32_t w = image_width == 0 ? k_default_width : image_width;
    w = std::min(std::max(w, k_min_width), k_max_width);
    return w + (w & 1u);  // even, so that height = width/2 exactly
}

/// Sub-samples per cell along one axis: 2 per texel the cell spans (ceil), at most k_max_sub. With cells = texels
/// the 2 × 2 points at a quarter and three quarters of the cell split it into four squares none of which crosses
/// a texel centre, so the filtered image is bilinear on each and the midpoint rule gives its exact integral
/// (Closest: the cell's one texel, exactly).
uint32_t sub_samples(uint32_t texels, uint32_t cells) {
    if (texels == 0) return 2;
    return std::min(k_max_sub, 2 * ((texels + cells - 1) / cells));
}

/// Bilinear maps: knots at the texel centres, knot value luminance(L) (the density's sin θ factor is the
/// distribution's own). The knot rows at the poles take the radiance the filter gives there (with Repeat, the mean
/// of the first and last texel rows), extrapolated from a point just off the pole (at the pole u is undefined). The
/// mean radiance is the integral of the interpolant of L (BilinearSphereDistribution::row_weights).
EnvironmentBake bake_bilinear(const std::function<Color(const Vec3&)>& Le, uint32_t nu, uint32_t nv, int threads) {
    const size_t rows = size_t(nv) + 2;
    std::vector<Color> radiance(rows * nu, Color(0.f));
    parallel_for(threads, nv, [&](size_t j) {
        const float v = (float(j) + 0.5f) / float(nv);
        for (uint32_t i = 0; i < nu; ++i)
            radiance[(j + 1) * nu + i] = Le(equirectangular_to_direction((float(i) + 0.5f) / float(nu), v));
    });
    // L(ε) = L_pole + (ε / half a texel)·(L_row − L_pole) on the half-row between the pole and the first centre.
    const float eps = 1e-3f / float(nv), f = 2.f * eps * float(nv);
    for (uint32_t i = 0; i < nu; ++i) {
        const float u = (float(i) + 0.5f) / float(nu);
        const Color south = Le(equirectangular_to_direction(u, eps)),
                    north = Le(equirectangular_to_direction(u, 1.f - eps));
        radiance[i] = vmax((south - radiance[nu + i] * f) / (1.f - f), Color(0.f));
        radiance[(rows - 1) * nu + i] = vmax((north - radiance[size_t(nv) * nu + i] * f) / (1.f - f), Color(0.f));
    }
    const std::vector<double> weight = BilinearSphereDistribution::row_weights(nv);
    double mean[3] = {0.0, 0.0, 0.0};
    for (size_t k = 0; k < rows; ++k) {  // in row order: the same sums for any thread count
        double row[3] = {0.0, 0.0, 0.0};
        for (uint32_t i = 0; i < nu; ++i)
            for (int c = 0; c < 3; ++c) row[c] += double(std::fmax(radiance[k * nu + i][c], 0.f));
        for (int c = 0; c < 3; ++c) mean[c] += weight[k] * row[c] / double(nu);
    }
    // ∫ L dω = 2π² ∫∫ L·sin θ du dv, over 4π.
    const double scale = 2.0 * k_pi * k_pi / (4.0 * k_pi);
    EnvironmentBake bake;
    bake.mean = Color(float(mean[0] * scale), float(mean[1] * scale), float(mean[2] * scale));
    const float mean_lum = luminance(bake.mean);
    if (!(mean_lum > 0.f)) return bake;
    std::vector<float> plain(rows * nu), compensated(rows * nu);
    for (size_t k = 0; k < radiance.size(); ++k) {
        const float l = std::fmax(luminance(radiance[k]), 0.f);
        plain[k] = l + k_floor * mean_lum;
        compensated[k] = compensate(l, mean_lum);
    }
    bake.plain = EnvironmentDensity(BilinearSphereDistribution(std::move(plain), nu, nv));
    bake.compensated = EnvironmentDensity(BilinearSphereDistribution(std::move(compensated), nu, nv));
    return bake;
}

/// Piecewise-constant maps: cell (i, j) gets W = ∫ luminance(L)·sin θ du dv over the cell by the midpoint rule on
/// su × sv points, the integral of what is rendered (the filtered image), and S = ∫ sin θ du dv by the same rule;
/// plain: W + floor·S, compensated: max(W − mean·S, 0). Each row's radiance integral (exact sub-row solid angles)
/// goes to the mean radiance.
EnvironmentBake bake_constant(const std::function<Color(const Vec3&)>& Le, uint32_t image_w, uint32_t image_h,
                              int threads) {
    const uint32_t nu = bake_width(image_w), nv = nu / 2;
    const uint32_t su = sub_samples(image_w, nu), sv = sub_samples(image_h, nv);
    std::vector<float> weights(size_t(nu) * nv), sines(nv);
    std::vector<double> row_mean(size_t(nv) * 3, 0.0);
    parallel_for(threads, nv, [&](size_t j) {
        double m[3] = {0.0, 0.0, 0.0}, s_sum = 0.0;
        for (uint32_t b = 0; b < sv; ++b) s_sum += std::sin(k_pi * (1.0 - (double(j) + (b + 0.5) / sv) / nv));
        sines[j] = float(s_sum / sv);
        for (uint32_t i = 0; i < nu; ++i) {
            double w = 0.0;
            for (uint32_t b = 0; b < sv; ++b) {
                const double v0 = (double(j) + double(b) / sv) / nv, v1 = (double(j) + double(b + 1) / sv) / nv;
                const float v = float((double(j) + (b + 0.5) / sv) / nv);
                const float sin_theta = std::sin(k_pi * (1.f - v));
                // Sub-cell solid angle: θ from π(1 − v1) to π(1 − v0).
                const double solid_angle =
                    2.0 * k_pi / (double(nu) * su) * (std::cos(k_pi * (1.0 - v1)) - std::cos(k_pi * (1.0 - v0)));
                for (uint32_t a = 0; a < su; ++a) {
                    const float u = float((double(i) + (a + 0.5) / su) / nu);
                    const Color c = Le(equirectangular_to_direction(u, v));
                    w += double(std::fmax(luminance(c), 0.f)) * sin_theta;
                    for (int k = 0; k < 3; ++k) m[k] += double(std::fmax(c[k], 0.f)) * solid_angle;
                }
            }
            weights[j * nu + i] = float(w / (double(su) * sv));
        }
        for (int k = 0; k < 3; ++k) row_mean[j * 3 + k] = m[k];
    });
    double mean[3] = {0.0, 0.0, 0.0};
    for (uint32_t j = 0; j < nv; ++j)  // in row order: the same sums for any thread count
        for (int k = 0; k < 3; ++k) mean[k] += row_mean[size_t(j) * 3 + k];
    EnvironmentBake bake;
    bake.mean = Color(float(mean[0] / (4.0 * k_pi)), float(mean[1] / (4.0 * k_pi)), float(mean[2] / (4.0 * k_pi)));
    const float mean_lum = luminance(bake.mean);
    if (!(mean_lum > 0.f)) return bake;
    std::vector<float> plain(weights.size()), compensated(weights.size());
    for (uint32_t j = 0; j < nv; ++j)
        for (uint32_t i = 0; i < nu; ++i) {
            const size_t c = size_t(j) * nu + i;
            plain[c] = weights[c] + k_floor * mean_lum * sines[j];
            compensated[c] = compensate(weights[c], mean_lum * sines[j]);
        }
    bake.plain = EnvironmentDensity(Distribution2D(plain, nu, nv));
    bake.compensated = EnvironmentDensity(Distribution2D(compensated, nu, nv));
    return bake;
}

}  // namespace

EnvironmentBake bake_environment(const ShaderLibrary& lib, uint32_t program,
                                 const std::function<Color(const Vec3&)>& Le, int threads) {
    const ImagesRead images = images_read(lib, program);
    if (images.bilinear) return bake_bilinear(Le, images.w, images.h, threads);
    return bake_constant(Le, images.w, images.h, threads);
}

}  // namespace candela
