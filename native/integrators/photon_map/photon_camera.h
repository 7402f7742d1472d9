// Pass 2 of Jensen's photon map (Jensen 2001, ch. 9; the course's "Pass 2"; docs/photon-mapping.md, "Pass 2"): the
// radiance a camera ray brings, its BSDFs split into traced lobes T and estimated lobes E (common/lobe_classes.h):
//
//   L = Le (seen directly or through T scatterings)
//     + at every camera vertex with E lobes, through E:
//         direct light     by the shared next-event estimation (common/direct_light.h; its only estimator here, so
//                          weight 1: no BSDF ray of E counts emission),
//         caustics         the caustic map's radiance estimate (L T⁺ E paths, used directly),
//         indirect light   final gathering: N rays sampled from E whose first hits y with E lobes read the global map
//                          and the caustic map (L(y) excluding y's emission, which next-event estimation covers);
//                          a gather ray that meets T lobes follows them (emission found after them is a caustic
//                          the caustic map holds); a hit closer than gather_distance × max_radius, where the
//                          density estimate is blotchy, is path traced one bounce further instead (next-event
//                          estimation and the caustic map at y, one more gather ray from y read from the maps);
//     + through T lobes: the camera path continues by sampling them, emission it finds weighted by MIS against
//       next-event estimation on T (non-delta T lobes only; delta scatterings count emission with weight 1).
// Every light path is counted exactly once: direct (L E), caustic (L T⁺ E) and indirect (L … E E) at the camera
// vertex partition the paths arriving through E.
#pragma once

#include <vector>

#include "core/rng.h"
#include "film/aov_film.h"
#include "integrators/common/direct_light.h"
#include "integrators/photon_map/photon_map.h"
#include "integrators/photon_map/photon_settings.h"
#include "integrators/photon_map/radiance_estimate.h"
#include "integrators/render_context.h"
#include "lights/light_sampler.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace candela {

class PhotonCameraTracer {
public:
    PhotonCameraTracer(const Scene& scene, const PhotonSettings& settings, const LightSampler& light_sampler,
                       const PhotonMap& global, const PhotonMap& caustic, float max_radius)
        : m_scene(scene),
          m_settings(settings),
          m_light_sampler(light_sampler),
          m_global(global),
          m_caustic(caustic),
          m_lookup{settings.k, max_radius, settings.kernel} {
        m_direct_e.light_sampling = LightSampling::LightOnly;
        m_direct_t.light_sampling = LightSampling::Mis;
    }

    Color Li(const Ray& camera_ray, Sampler& sampler, PathStats& stats, float* alpha, AovSample* aov) const;

private:
    /// Next-event estimation at hit seen from wo through the lobes `part` (rules: E's or T's), with the continuation
    /// density `part_pdf` for MIS (T only).
    Color direct(const SurfaceHit& hit, const Vec3& ns, const Vec3& wo, const Bsdf& part, const DirectLightRules& rules,
                 float u_select, Vec2 u_light, PathStats& stats) const;
    /// The radiance a gather ray brings from its hits (see above); `close_rule`: the first gather segment.
    Color gather(Ray ray, PrimitiveRef from, bool close_rule, Pcg32& rng, PathStats& stats,
                 std::vector<PhotonNeighbor>& scratch) const;
    /// L(y) through E at a close gather hit y, path traced one bounce further.
    Color close_hit(const SurfaceHit& hit, const ShadingPoint& sp, const Vec3& wo, uint32_t traced, Pcg32& rng,
                    PathStats& stats, std::vector<PhotonNeighbor>& scratch) const;
    /// The maps' estimate at y through E (global + caustic).
    Color map_estimate(const SurfaceHit& hit, const ShadingPoint& sp, const Vec3& wo,
                       std::vector<PhotonNeighbor>& scratch, bool global = true) const;

    const Scene& m_scene;
    const PhotonSettings& m_settings;
    const LightSampler& m_light_sampler;
    const PhotonMap& m_global;
    const PhotonMap& m_caustic;
    DensityLookup m_lookup;
    DirectLightRules m_direct_e, m_direct_t;
};

}  // namespace candela
