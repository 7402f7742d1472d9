// Caustic photons aimed at what can start a caustic (Jensen's projection maps, Jensen 2001 §5.3): photons of the
// caustic map are emitted only toward the bounding spheres of the objects with traced lobes (common/lobe_classes.h:
// mirrors, glass, narrow glossy), so a small glass object in a large room receives its photons instead of a share
// proportional to its solid angle. A caustic path L S⁺ D starts with a segment that hits a traced surface, and every
// such surface lies inside a target sphere, so restricting the first direction to the spheres loses no caustic
// path; the photon's flux weight divides by the density actually used, so the estimate stays unbiased.
//
// Emission from an emitter at a point y (area lights, triangles, soft point lights: y on the light; point lights: y
// the position): a target j is chosen with the emitter's probabilities s_j (∝ the solid angle the sphere subtends
// from the emitter's centre), and a direction uniformly in the cone the sphere subtends from y (all directions if y
// is inside it). The direction's density is the mixture over every target whose cone contains it,
//     p(ω) = Σ_i s_i·[ω ∈ cone_i(y)] / Ω_i(y),
// and the weight is Le(y, ω)·|cos θ_y|/(p_pos(y)·p(ω)·P(emitter)). Distant emitters (sun, world): a direction toward
// the emitter by its own sampling, then a target j ∝ r_j² and a point uniform on the disc of radius r_j across that
// direction through its centre; the ray's density per unit area across the direction is Σ_i s_i·[ray meets disc
// i]/(π r_i²). Emitters are chosen ∝ power × the share of their emission the targets can catch (at least 10⁻⁴).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/common/light_path.h"
#include "lights/emitter_set.h"
#include "sampling/distribution_1d.h"
#include "scene/scene.h"

namespace candela {

struct CausticTarget {
    Vec3 center{0.f};
    float radius = 0.f;
};

/// What the scene can do with caustics, for the photon mapper's "only what the scene calls for".
struct CausticAnalysis {
    bool any_traced_material = false;    // some material may have a traced lobe somewhere
    std::vector<CausticTarget> targets;  // the bounding spheres of the objects with traced triangles
    bool merged = false;                 // too many objects: one sphere around them all
    bool moving = false;  // some target's object moves (motion blur): its sphere is the one at the thread's time
};

/// Finds the materials that may have traced lobes (textured ones conservatively: any delta or glossy closure) and
/// the bounding spheres of the objects whose triangles use them (at most k_max_caustic_targets, else merged).
inline constexpr size_t k_max_caustic_targets = 32;
CausticAnalysis analyse_caustics(const Scene& scene, float alpha_threshold);

class CausticEmission {
public:
    CausticEmission(const EmitterSet& emitters, const std::vector<CausticTarget>& targets);

    bool empty() const { return m_targets.empty() || !(m_select.integral() > 0.f); }
    /// An emitted ray aimed at the targets (u_target chooses the target).
    LightPathStart sample(float u_select, Vec2 u_pos, Vec2 u_dir, float u_target) const;
    /// The share of the emitters' power emitted toward the targets, roughly (for the log).
    float coverage() const { return m_coverage; }

private:
    /// p(ω) of directions from y toward the targets, with the emitter's target probabilities.
    float direction_pdf(const float* s, const Vec3& y, const Vec3& w) const;
    float area_pdf(const float* s, const Vec3& origin, const Vec3& d) const;

    const EmitterSet& m_emitters;
    std::vector<CausticTarget> m_targets;
    std::vector<float> m_target_probs;  // per emitter, one row of m_targets.size()
    std::vector<Distribution1D> m_target_select;
    Distribution1D m_select;
    float m_coverage = 0.f;
};

}  // namespace candela
