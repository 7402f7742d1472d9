// Emission sampling: rays leaving the lights, for light-rooted integrators (light tracing, bidirectional path
// tracing, photon mapping, the source-shooting generator). Each light returns a ray, the radiance it carries and
// the densities of its origin (area measure) and direction (solid angle), and evaluates those densities for any
// emitted ray (MIS in BDPT). A light path starts with the flux weight
//     β₀ = Le · |cos θ| / (p_pos · p_dir),
// whose expectation over the samples is the light's flux Φ (tested against 4πI, the spot's cone integral, πAL
// for a one-sided area light, 2πAL for a two-sided triangle, E·πR² for the sun, πR²∫L dω for the world).
//
// The light models (docs/architecture.md):
//   point, spot (radius 0)   delta position; direction uniform on the sphere / in the spot's cone, Le = I(ω)
//                            (Cycles 3.4's smoothstep and extra cos θ for spots).
//   point, spot (radius r)   a sphere of radius r with radiance L = I/(πr²) (the same intensity and flux as the
//                            disk next-event estimation samples, but a fixed surface): direction d first (sphere /
//                            cone), then a point uniform on the disk of radius r across d, lifted onto the
//                            hemisphere facing d; its joint density, split as p_pos = 1/(4πr²),
//                            p_dir = 4·cos θ·p(d). Not hit by rays (as in the path tracer). The path tracer
//                            (and Cycles 3.4) light a receiver x by a disk through the centre facing x, which
//                            gives x less light than the sphere (irradiance ratio 1 + r²/d² straight under it):
//                            emission_arrives() keeps the emitted rays that x would receive from its disk.
//   area light               uniform point (rectangle, ellipse), cosine-weighted direction on its emitting side.
//   emissive triangle        uniform point, a side with probability ½, cosine-weighted direction on it; textured
//                            emission evaluated at the point toward the direction.
//   sun                      direction toward the sun (delta, or the angular disk next-event estimation samples),
//                            origin uniform on a disk of the scene's bounding radius R across it, outside the
//                            scene: p_pos = 1/(πR²).
//   world                    a direction by the world's own light sampling (environment importance, or uniform),
//                            origin on the disk as for the sun.
#pragma once

#include "core/vec.h"
#include "lights/light.h"

namespace candela {

/// A sphere enclosing everything a ray can hit (geometry and area lights) and the point lights: where light
/// from the sun and the world enters the scene for light-rooted integrators.
struct SceneSphere {
    Vec3 center{0.f};
    float radius = 1.f;
};

struct EmissionSample {
    Vec3 p;               // the ray's origin
    Vec3 n{0.f};          // the emitting surface's unit normal at p (on the side d leaves; zero for point lights)
    Vec3 d;               // unit direction of emission
    Color Le{0.f};        // radiance along d (a delta position: intensity; a delta direction: irradiance)
    float pdf_pos = 0.f;  // area density of p (1 for a delta position)
    float pdf_dir = 0.f;  // solid-angle density of d given p (1 for a delta direction)
    bool delta_pos = false, delta_dir = false;
    bool infinite = false;     // sun and world: p lies on a disk outside the scene
    float b1 = 0.f, b2 = 0.f;  // a triangle's barycentric weights of p (textured emission)

    bool valid() const { return pdf_pos > 0.f && pdf_dir > 0.f && !is_black(Le); }
    /// The flux weight a light path starts with: Le·|cos θ|/(p_pos·p_dir) (cos θ = 1 without a surface).
    Color weight() const {
        const float c = (delta_pos || infinite) ? 1.f : std::fabs(dot(n, d));
        return Le * (c / (pdf_pos * pdf_dir));
    }
};

/// Samples an emitted ray of light l: u_pos picks the origin, u_dir the direction, u_side a triangle's side.
EmissionSample light_sample_le(const Light& l, Vec2 u_pos, Vec2 u_dir, float u_side, const SceneSphere& bounds);

/// The densities light_sample_le gives the ray (p, d) with surface normal n (as sampled: on the side d leaves),
/// for any such ray of light l: 0 where the light cannot emit it.
void light_pdf_le(const Light& l, const Vec3& p, const Vec3& n, const Vec3& d, const SceneSphere& bounds,
                  float* pdf_pos, float* pdf_dir);

/// A point on an emitter drawn with the density light_sample_le gives its origins (for the strategies that connect
/// a path to a light, so that every strategy sees one density for the light vertex): uniform on area lights and
/// triangles (both sides of a triangle emit: the side is the one the connection leaves by), uniform on a soft point
/// light's sphere, the position of a point light; for the sun and the world a direction toward them, by their own
/// sampling.
struct EmitterPoint {
    Vec3 p{0.f}, n{0.f};  // point and unit normal (on the emitting side chosen); zero normal for points
    float pdf_pos =
        0.f;  // area density of p (1 for a delta position); for distant lights the solid-angle density of omega
    bool delta_pos = false, infinite = false;
    Vec3 omega{0.f};           // distant lights: the unit direction toward the light
    float b1 = 0.f, b2 = 0.f;  // a triangle's barycentric weights of p (textured emission)
    Color Le{0.f};             // distant lights: the radiance (irradiance for a delta sun) arriving along −omega
    bool valid() const { return pdf_pos > 0.f; }
};
EmitterPoint light_sample_point(const Light& l, Vec2 u_pos, Vec2 u_dir, float u_side);

/// The radiance emitter l sends from its point `pt` along unit direction d (0 toward its back). Distant lights:
/// pt.Le (the direction is pt.omega's).
Color light_radiance(const Light& l, const EmitterPoint& pt, const Vec3& d);

/// Whether rays can hit the light (area lights, triangles, the world): the others — point and spot lights, the sun
/// — are reached only by connecting to them.
bool light_hittable(const Light& l);

/// Whether light that l emitted along unit d and that first reaches a surface at x is light the path tracer's model
/// of l gives x (true for every light but a soft point or spot light). Cycles 3.4 and PATH (lights/point_light.h)
/// light x by a disk of radius r through the centre c, facing x, of radiance I/(πr²); emission samples the lines
/// that cross the sphere of radius r with that radiance (a disk that turns toward each receiver has no radiance
/// field of its own to sample). The disk's lines through x are a subset of the sphere's: those that cross the disk's
/// plane within r of c, |x − c|·tan θ ≤ r with θ the angle between −d and the direction from x to c. Dropping the
/// other emitted rays at their first surface leaves that surface exactly the disk's irradiance. (Geometry inside
/// the sphere, between the disk and the sphere's surface, is ignored: the rays leave the sphere's surface.)
bool emission_arrives(const Light& l, const Vec3& x, const Vec3& d);

/// For lights no ray can hit, the density of an emitted ray's direction d as if it left the light's centre: point
/// and spot lights the direction density of light_sample_le (whatever their radius; a soft spot's cone density
/// without the cone test, since its disk's points send light up to the disk's angular size beyond the cone and a
/// strategy that reaches such a direction needs a positive density), the sun 1 (its direction taken as a delta); 0
/// for the others. Strategies that reach such a light at different points of it (next-event estimation's disk,
/// emission's sphere) weigh their paths by this one function of the light and the direction from its centre, as if
/// the light were a point there: every strategy then computes the same weights for a path, which sum to 1.
float light_center_direction_pdf(const Light& l, const Vec3& d);

/// The light's flux Φ (luminance) as light_sample_le emits it: the spot's true cone integral, the world through
/// the bounding disk. For textured triangles, the flux of their `radiance` (an estimate).
float light_emitted_power(const Light& l, const SceneSphere& bounds);

/// ∫ attenuation(ω) dω of a spot's cone (4π for a point light without a cone).
float spot_solid_angle_integral(const SpotShape& spot);

}  // namespace candela
