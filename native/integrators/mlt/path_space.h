// The function Metropolis light transport samples (Kelemen et al. 2002; Veach 1997, ch. 11): a primary-sample state
// u ↦ the contributions of one bidirectional sample and its scalar importance I(u) = luminance of their sum.
//
// PSSMLT (MLT): u's first two coordinates (Dim::Filter) place the camera ray uniformly over the full frame widened by
// the camera margin m (half the filter's support: the footprints of border pixels), area A = (W + 2m)(H + 2m)
// pixels; the lens (Dim::Lens) and every bounce read theirs by the usual dimension indices; the whole bidirectional
// sample (every strategy, MIS-weighted) is the path (integrators/bdpt/bdpt_tracer.h). With u uniform, the camera-side
// contributions filtered into pixel j have mean (1/A)·∫ f_j·L, and the t = 1 splats (normalised by the frame's
// area A_f = W·H, as the camera's importance is: scene/camera.h) (1/A_f)·∫ f_j·L: the splats are scaled by A_f/A so
// that E_u[g_j(u)] = I_j / A for the image I_j and the whole sample g_j.
//
// MMLT (Hachisuka et al. 2014): the state also has a path depth k (scattering vertices, fixed per chain) and
// coordinate strategy_dim() chooses s uniformly among the k + 2 strategies of that depth (k = 0: (0, 2) only);
// the path is that strategy's alone, MIS-weighted and multiplied by the number of strategies, so that summed over
// depths its expectation is the whole bidirectional sample's.
//
// Motion blur: in a moving scene u also has a shutter time τ (coordinate shutter_dim(), uniform over [0, 1]); the
// state's path, all its strategies and splats, sees the scene at τ. The integrand is then over the path space ×
// the shutter, and the image its time average.
#pragma once

#include <vector>

#include "integrators/bdpt/bdpt_tracer.h"
#include "sampling/primary_sample_sampler.h"

namespace candela {

/// One evaluated state: its contributions on the full frame (raster positions) and I.
struct MltSample {
    std::vector<BdptTracer::Contribution> contributions;  // `raster` set for every entry
    float importance = 0.f;                               // I(u): luminance of the summed contributions
    void clear() {
        contributions.clear();
        importance = 0.f;
    }
};

/// MMLT's strategy choice at depth k (scattering vertices): s of the strategies (s, t = k + 2 − s) — the k + 2 with
/// s = 0 … k + 1 for k ≥ 1, (0, 2) alone for k = 0 — chosen uniformly by one primary coordinate u ∈ [0, 1).
struct StrategyChoice {
    int s = 0;
    float pmf = 1.f;  // its probability
};
int mmlt_strategy_count(int depth);
StrategyChoice mmlt_choose_strategy(int depth, float u);
/// The probability mmlt_choose_strategy gives s at `depth` (0 for an s it never chooses).
float mmlt_strategy_pmf(int depth, int s);

class PathSpace {
public:
    PathSpace(const Scene& scene, const BdptSettings& settings, const EmitterSet& emitters);

    /// f(u): the whole bidirectional sample (depth < 0) or depth `depth`'s strategy chosen by u (MMLT).
    void evaluate(PrimarySampleSampler& u, int depth, PathStats& stats, MltSample& out) const;
    /// The area in pixels the camera rays are spread over (A above), and the frame's (A_f).
    double raster_area() const { return m_area; }
    double frame_area() const { return m_frame_area; }
    /// Scattering vertices of the longest path (MMLT's depths are 0 … max_depth()).
    int max_depth() const { return m_tracer.context().settings.max_bounces + 1; }
    /// The primary coordinate of MMLT's strategy choice: past every coordinate the subpaths read.
    uint32_t strategy_dim() const;
    /// The primary coordinate of the shutter time (motion blur, scene/shutter_time.h): uniform over the shutter,
    /// moved by small steps like every coordinate (wrapping around, a symmetric proposal on the circle), fresh at
    /// large steps; past the strategy choice.
    uint32_t shutter_dim() const;

private:
    BdptTracer m_tracer;
    const Camera& m_camera;
    float m_margin;
    bool m_motion;  // the scene moves: the state carries a shutter time (shutter_dim)
    double m_area, m_frame_area;
};

}  // namespace candela
