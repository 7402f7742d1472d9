// Multiple importance sampling of the one-bounce indirect light over the course's three path generators (option
// generators_mis). A one-bounce path y → z → x (y on an emitter, z a surface point scattering non-delta, x the
// receiver) is produced by each generator with its own density, all in the measure  dA(z) × dσ_z(y)  (area at z
// times solid angle at z toward y — or, for lights no ray can hit, the counting measure over the light):
//     receiver gathering   p_RG   = p_x(x→z) · |cos_z|/d²_xz · Y(y | z)
//     surface sampling     p_SURF = p_A(z) · Y(y | z)
//     source shooting      p_SS   = P(e) · p_pos(y) · p_dir(y→z) · |cos_z| / |cos_y|      (a finite emitting surface)
//                                 = P(e) · p_dir(ω) · p_disk · |cos_z|                       (the world, a distant light)
//                                 = P(e) · p_dir(c→z) · |cos_z| / d²_cz                      (point and spot lights, centre c)
//                                 = P(e) · |cos_z| / (πR²)                                   (the sun)
// with Y(y | z) the density with which z's light estimate finds y: next-event estimation's k·pmf(light | z)·p_light
// (k·pmf for unhittable lights), or, for emitters next-event estimation does not sample (a constant world), z's own
// BSDF sampling toward y. The weights w_g = p_g^β / Σ p^β (balance β = 1, power β = 2; Veach 1997, eqs. 9.12–9.13)
// are one function of the path whichever generator produced it, so they sum to one and the combination stays
// unbiased (Veach 1997, §9.2.2). Where a density is only a stand-in — the nominal light-selection pmf for Ward's
// adaptive selection, the light's centre for point and spot lights with a radius (next-event estimation samples a
// disk facing z, emission a sphere) — the weights stay a partition of unity and only their optimality is affected.
#pragma once

#include <cstdint>

#include "integrators/common/direct_light.h"
#include "integrators/common/vertex_bsdf.h"
#include "integrators/generators/generator_settings.h"
#include "lights/emitter_set.h"
#include "lights/light_sampler.h"
#include "scene/surface_sampler.h"

namespace candela {

/// The light end of a one-bounce path.
struct OneBounceLight {
    int light = -1;    // LightSet index (next-event estimation samples it), or −1
    int emitter = -1;  // EmitterSet index (emission samples it), or −1
    Vec3 w{0.f};       // unit direction z → y
    float dist = 0.f;  // |y − z| (infinity for distant lights)
    Vec3 n{0.f};       // the emitting surface's unit normal at y (zero for points and distant lights)
};

/// The light end of a next-event sample of light `li` from z (its normal taken from the light's surface).
OneBounceLight one_bounce_light_of_sample(const LightSet& lights, uint32_t li, const Vec3& wi, float dist);

class OneBounceWeights {
public:
    OneBounceWeights(const Scene& scene, const LightSampler& light_sampler, const EmitterSet& emitters,
                     const SurfaceSampler* surfaces, const GeneratorSettings& settings)
        : m_scene(scene),
          m_light_sampler(light_sampler),
          m_emitters(emitters),
          m_surfaces(surfaces),
          m_settings(settings) {}

    /// The weight of `generator`'s estimate of the path y → z → x: x the receiver seen from wo_x, z the surface
    /// point (its vertex BSDF; its camera side is toward x), y `light`.
    float weight(PathGenerator generator, const VertexBsdf& x, const Vec3& wo_x, const VertexBsdf& z,
                 const OneBounceLight& light) const;

private:
    float light_density(const VertexBsdf& z, const Vec3& w_c, const OneBounceLight& y) const;
    float source_density(const VertexBsdf& z, const OneBounceLight& y) const;

    const Scene& m_scene;
    const LightSampler& m_light_sampler;
    const EmitterSet& m_emitters;
    const SurfaceSampler* m_surfaces;
    const GeneratorSettings& m_settings;
};

}  // namespace candela
