// AUTO's pilot render (docs/auto.md, "Pilot"): a short path-traced estimate of the image — a few samples per pixel
// on a coarser grid over the same frame (each pilot pixel averages a block of d × d film pixels, so its mean is
// the film's frame integral) — that splits every path's contribution by the class of path that carried it and
// measures where the energy and the variance come from. Classes (Heckbert's notation, read from the light):
//   emitted   L S* E        light seen by the camera, directly or through delta surfaces only;
//   direct    L D S* E      light reaching the first non-delta vertex directly (next-event estimation there, or its
//                           BSDF ray hitting the light);
//   indirect  L D (S|D)* D S* E   light reaching a later non-delta vertex directly;
//   caustic   L S+ D (S|D)* E     light reaching a non-delta vertex through at least one delta bounce.
// The estimator is a path tracer with next-event estimation and MIS (power heuristic) between light sampling and
// BSDF sampling, as PATH's defaults (integrators/path/path_tracer.h), with Russian roulette from the third bounce on:
// Σ over classes is an unbiased estimate of PATH's image mean (tested against PATH). A caustic from a small light is
// rare for a path tracer, so at a path's first non-delta vertex k caustic probes (BSDF samples followed through delta
// bounces only) estimate that vertex's caustic in place of the path's own ray (pilot.cpp). Also measured: the energy that
// next-event estimation finds blocked only by transmissive (or transparent) surfaces — light that reaches the point
// only through glass, which the path tracer must find by refraction — and the energy a Caustics switch would remove
// (paths with a delta scatter after a diffuse one: Cycles' caustics filter), and how concentrated the variance is
// in few pixels (fireflies). Deterministic for a seed: pilot pixel i uses PCG32 stream (seed, i), rows run in
// parallel and are summed in row order.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/parallel.h"
#include "scene/scene.h"

namespace candela {

enum class PathClass : int { Emitted = 0, Direct, Indirect, Caustic };
constexpr int k_path_classes = 4;
const char* path_class_name(PathClass c);

struct PilotSettings {
    int downscale = 4;     // pilot pixel = downscale × downscale film pixels
    int samples = 8;       // paths per pilot pixel
    int max_bounces = 12;  // as PATH's (0: direct lighting only)
    uint64_t seed = 0;
    int threads = 0;
    // The film's region of the full frame (a border render): the pilot covers the same region.
    int x0 = 0, y0 = 0, width = 0, height = 0;
};

/// The pilot's settings for a render of `samples` per pixel over a film of width × height (docs/auto.md): samples/8
/// paths per pilot pixel (2 to 8: two for a per-pixel variance) on a grid 4× coarser per axis when the film is at
/// least 128 pixels on its short side (2× from 32, 1× below): 1/128 of a 64-sample render's camera paths from 128
/// pixels up, 1/32 from 32, 1/8 below 32 pixels (more for under 16 samples).
PilotSettings pilot_settings_for(int x0, int y0, int width, int height, int samples, int max_bounces, uint64_t seed,
                                 int threads);

struct PilotResult {
    int pixels = 0;     // pilot pixels
    int samples = 0;    // paths per pilot pixel
    uint64_t rays = 0;  // rays cast (camera, bounce, shadow and the transmissive probes)
    double milliseconds = 0.0;
    /// Per class: the image-mean luminance it carries (Σ = total_mean), and Σ over pilot pixels of the per-path
    /// sample variance of its luminance (the image's variance budget, by class).
    std::array<double, k_path_classes> mean{}, variance{};
    double total_mean = 0.0;
    double total_variance = 0.0;                       // Σ over pixels of the per-path variance of the total
    double standard_error = 0.0;                       // of total_mean (pixels independent)
    double class_standard_error[k_path_classes] = {};  // of mean[c]
    /// Image-mean luminance next-event estimation would have added had transmissive surfaces let its shadow rays
    /// through (every blocker transmissive or transparent): light that reaches the point only through glass.
    double through_transmissive_mean = 0.0;
    /// Image-mean luminance of paths with a delta scatter after a diffuse one (what the Caustics switches remove).
    double specular_after_diffuse_mean = 0.0;
    /// The share of total_variance in the 1 % of pilot pixels (at least one) with the largest variance.
    double firefly_share = 0.0;
    /// Pilot paths that carried any caustic light: with few, the caustic shares are not measured (a small light's
    /// caustic the pilot's few paths missed), and the policy leaves the decision to the static features.
    uint64_t caustic_path_count = 0;

    double energy_share(PathClass c) const { return total_mean > 0.0 ? mean[int(c)] / total_mean : 0.0; }
    /// The class's share of Σ_c variance[c] (the classes' variances, not the total's: their covariances left out).
    double variance_share(PathClass c) const;
    double through_transmissive_share() const {
        const double all = total_mean + through_transmissive_mean;
        return all > 0.0 ? through_transmissive_mean / all : 0.0;
    }
    /// One line for the log.
    std::string summary() const;
};

/// Runs the pilot (throws nothing but what the scene's shading throws; returns early, partial, when cancelled).
PilotResult run_pilot(const Scene& scene, const PilotSettings& settings, const CancelToken* cancel = nullptr);

}  // namespace candela
