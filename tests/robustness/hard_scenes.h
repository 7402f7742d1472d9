// Scene pieces and image checks for the hard-case tests (coplanar surfaces, shading normals, enclosed
// lights, mirrored objects): quads in any orientation, closed boxes, spheres and cylinders with per-corner
// shading normals (smooth shading), Blender area lights; per-pixel agreement, speckle and colour-mixture
// counts.
#pragma once

#include <cstdint>
#include <vector>

#include "test_helpers.h"

namespace candela::test {

/// MeshBuilder plus per-corner shading normals: triangles added by MeshBuilder's own helpers stay flat.
struct ShadedBuilder : MeshBuilder {
    std::vector<float> normals;   // 9 per triangle (zeros: flat)
    std::vector<uint8_t> smooth;  // 1 per triangle

    /// Quad p0, p0+e1, p0+e1+e2, p0+e2 (winding normal e1×e2) as one mesh.
    uint32_t add_quad(Vec3 p0, Vec3 e1, Vec3 e2, uint32_t material);
    /// Closed axis-aligned box as one mesh (12 triangles, winding normals outward). smooth: every corner's
    /// shading normal is the normalised corner direction (a low-poly "rounded" box, as Blender's smooth shading
    /// of a cube gives), disagreeing with the faces by 54.7°.
    uint32_t add_box(Vec3 lo, Vec3 hi, uint32_t material, bool smooth_normals);
    /// UV sphere with smooth shading (vertex normals = the true sphere normals).
    uint32_t add_smooth_sphere(float radius, int segments, int rings, uint32_t material);
    /// Closed cylinder along z, smooth sides (radial normals), flat caps.
    uint32_t add_smooth_cylinder(float radius, float z0, float z1, int segments, uint32_t material);
    /// Blender area light: rectangle centred at `center` spanning u × v, emitting toward `dir`, power `strength` W.
    void add_area_light(Vec3 center, Vec3 u, Vec3 v, Vec3 dir, Color strength);

    SceneArrays arrays(const float* camera_rows16 = nullptr) const;

private:
    void add_triangle(uint32_t a, uint32_t b, uint32_t c, uint32_t material, const Vec3* n = nullptr);
    uint32_t add_vertex(Vec3 p);
};

/// Row-major 4×4 rows of a scale-then-translate transform.
std::vector<float> scale_translate(Vec3 scale, Vec3 offset);

/// Rec.709 luminance of pixel i: the quantity the Noise pass gives the standard error of.
double pixel_luminance(const RenderResult& r, size_t i);

/// Pixels (inside `mask`, if given) whose luminances differ by more than k·sqrt(σa² + σb²) + 1e-5·max (σ: the
/// Noise passes; the relative term is float rounding). Each pixel is a mean of n samples, ≈ normal (CLT), so
/// under "same image" |z| > 6 has probability 2e-9 per pixel.
size_t count_disagreeing_pixels(const RenderResult& a, const RenderResult& b, double k,
                                const std::vector<uint8_t>* mask = nullptr);

/// Speckle: pixels (inside `mask`, with every neighbour inside it) whose luminance differs from the median of
/// their 8 neighbours by more than k·sqrt(σ² + σ_n²) + 2·spread + 1e-5·|median|, with σ the pixel's and σ_n the
/// largest neighbour's standard error, and spread the range of the neighbours without the most extreme one at
/// each end. Derivation: a pixel is the mean of n samples, ≈ normal with standard error σ (CLT). Where the true
/// image is locally linear the 8 neighbours' true values are symmetric about the centre's, so their median
/// estimates it with an error no larger than one neighbour's σ_n; |z| > 6 has probability 2e-9 per pixel, so a
/// few thousand pixels give no false alarm. Where it curves (a highlight's peak) the centre departs from the
/// median by about the second difference, which the neighbours' own spread bounds (twice it, for margin); the
/// trimmed range ignores one speckled neighbour. The relative term covers float rounding of bright pixels.
size_t count_speckles(const RenderResult& r, const std::vector<uint8_t>& mask, double k = 6.0);

/// Pixels fully covered (alpha exactly 1) in a render with film_transparent, shrunk by one pixel so no pixel
/// filter footprint reaches an edge.
std::vector<uint8_t> covered_interior(const RenderResult& transparent);
std::vector<uint8_t> mask_and(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
size_t mask_count(const std::vector<uint8_t>& m);

/// Mean luminance over the mask and its standard error (from the Noise pass; pixels are independent).
void masked_mean(const RenderResult& r, const std::vector<uint8_t>& mask, double* mean, double* se);

}  // namespace candela::test
