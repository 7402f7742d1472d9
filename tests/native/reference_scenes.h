// The scenes the integrator tests share (built as scene arrays, camera at the origin looking down −Z unless a
// scene sets its own), and the closed-form answers some of them have.
#pragma once

#include <vector>

#include "core/params.h"
#include "core/vec.h"
#include "test_helpers.h"

namespace candela::test {

/// Row-major 4×4 translation.
std::vector<float> translation(float x, float y, float z);

/// A parallelogram o + s·u + t·v (s, t ∈ [0, 1]) as one mesh, wound so its geometric normal is u × v; returns the
/// mesh index.
uint32_t add_parallelogram(MeshBuilder& b, Vec3 o, Vec3 u, Vec3 v, uint32_t material);

/// A room: diffuse walls (open toward a dim world through a window), a rough glossy sphere and — with `specular` — a
/// glass sphere on the floor and a mirror; lit by `lights` (a bit mask: 1 point, 2 soft point, 4 spot, 8 sun, 16 soft
/// sun, 32 disk area light, 64 rectangle area light, 128 emissive triangle, 256 constant world).
///
/// Lights no ray can hit (point, spot, sun) light the floor through the glass and the mirror along paths a path
/// tracer cannot build (after a delta bounce it would have to hit the light): bidirectional methods render those
/// caustics and PATH does not, so agreement with PATH is tested for them without the specular objects.
SceneArrays lit_room(unsigned lights, bool specular);

/// The Cornell box (Goral et al. 1984 in its common modern form): white floor, ceiling and back wall, a red left and
/// a green right wall, a tall and a short box, a square emissive panel just under the ceiling; open toward the camera.
SceneArrays cornell_box();

/// A glass sphere (IOR 1.5) on a diffuse floor in front of a diffuse wall under one small disk area light: the
/// floor's caustic is light → glass → glass → floor, which a path tracer finds only by hitting the small light.
SceneArrays glass_caustic();

/// The glass slab (docs/verification.md §2.10) in the camera's frame: a floor (albedo k_slab_albedo) at z = −2 facing
/// the camera at the origin, a glass slab (η 1.5, 0.1 thick) behind the camera at z ∈ [0.5, 0.6], a sun of irradiance
/// 1 shining down −z through it. The floor's radiance is ρ·T·E₀/π wherever the camera looks (the slab and the floor
/// reach 1.6 and 1.5 beyond the axis, the view about 0.8): the light the floor reflects back up and the slab returns
/// adds a relative ρ·R_slab < 2·10⁻⁴ (R_slab < 0.2 for diffuse light), below the tests' resolution. All of the
/// floor's light has passed the glass: the sun's shadow rays stop at it.
constexpr float k_slab_albedo = 1.f / 1024.f;  // the floor's
constexpr double k_slab_transmittance = 12.0 / 13.0;
SceneArrays glass_slab();
/// ρ·T·E₀/π, the floor's radiance.
double slab_expected();

/// A closed, coarsely tessellated sphere (8 × 6) of albedo 0.5 with smooth (radial) shading normals, lit by a point
/// light near its centre: the camera inside sees shading normals up to 23° off the facets'.
SceneArrays smooth_lowpoly_sphere();

/// Veach's multiple-importance-sampling scene (Veach 1997, ch. 9; Bitterli's conversion, docs/verification.md §8.2):
/// four glossy plates of Beckmann α 0.01, 0.05, 0.1, 0.25 (colour 0.3) reflecting four spherical lights of equal power
/// and radii 0.9, 0.3, 0.1, 0.0333 (L·r² = 7.59909), a diffuse floor and wall. Materials 0–3 are the plates.
SceneArrays veach_scene(std::vector<float>* camera);
/// Its camera (35° horizontal field of view) on a w×h film, max_bounces 0.
Params veach_params(int w, int h);

/// Two facing plates under an area light (docs/verification.md §2.5): in the plane z = 0 a one-sided rectangle area
/// light E ([−1.5, −0.5] × [−0.5, 0.5], shining +z, radiance k_plates_radiance) and a diffuse receiver R ([0.5, 1.5] ×
/// [−0.5, 0.5], albedo k_receiver_albedo); at z = 1 a diffuse plate P ([−2, 2] × [−1.5, 1.5], albedo
/// k_plate_albedo) facing down. E and R are coplanar, so R has no direct light: all of it has bounced once off P. An
/// orthographic camera between the plates (with depth of field focused on R) looks straight down at the centre
/// square [0.75, 1.25] × [−0.25, 0.25] of R.
/// With max_bounces 1 the image is the one-bounce answer facing_plates_expected().
SceneArrays facing_plates();
Params facing_plates_params(int w, int h, int samples);
/// The mean radiance over the viewed square, by Gauss–Legendre quadrature over the square and over P of
///   L(x) = ρ_R/π ∫_P ρ_P/π · E_P(z) · cos θ_x cos θ_z / |x − z|² dA_z,
/// with E_P(z), the irradiance E gives P at z, by Lambert's polygon formula (exact); `order` points per axis on the
/// square, 8·order × 6·order on P.
double facing_plates_expected(int order = 6);

/// E/L at x (normal n) from a polygon of uniform radiance entirely above x's horizon (Lambert's formula,
/// docs/verification.md §2.4): ½·|Σ βᵢ (n·uᵢ)|.
double polygon_irradiance(const std::vector<Vec3>& poly, Vec3 x, Vec3 n);

}  // namespace candela::test
