// The integrator interface and its registry. Registry names are the add-on's `integrator` enum identifiers;
// each entry publishes its settings (core/param_spec.h) beside the common ones every integrator reads
// (common_param_specs()), and unknown names throw InvalidParameter listing the valid ones.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/param_spec.h"
#include "core/params.h"
#include "film/film.h"
#include "integrators/render_context.h"
#include "scene/scene.h"

namespace candela {

/// How much work a render is, in the integrator's own unit (the progress the user sees: "Sample 12/64").
struct WorkBudget {
    int64_t total = 1;
    const char* unit = "sample";  // singular, lower case: "sample", "light path", "iteration", "mutation"
};

/// Scene features an integrator may or may not honour (Integrator::honoured_features). The session logs each one a
/// scene uses that the chosen integrator does not, so the user knows why the image differs from PATH's.
enum SceneFeature : uint32_t {
    k_feature_light_path = 1u << 0,           // the Light Path node's outputs (ray type and depths)
    k_feature_transparent_shadows = 1u << 1,  // shadow rays and connections through Transparent surfaces
    k_feature_terminator_offset = 1u << 2,    // the shadow terminator geometry offset of smooth low-poly meshes
    k_feature_motion_blur = 1u << 3,          // camera and object motion over the shutter
    k_feature_bump_shadowing = 1u << 4,       // the bump shadowing term at bent normals (bsdf/bsdf.h)
};
/// The log line for the features of `scene` that an integrator honouring `honoured` ignores ("" if none).
std::string unhonoured_features_note(const std::string& integrator, uint32_t honoured, const Scene& scene);

class Integrator {
public:
    virtual ~Integrator() = default;
    /// The SceneFeature bits this integrator honours (the default: none of them).
    virtual uint32_t honoured_features() const { return 0; }
    /// Renders into the film until done or cancelled (returns normally on cancel, keeping the partial image),
    /// through the progressive driver (integrators/progressive_driver.h). Must not depend on thread count or
    /// scheduling for a given seed.
    virtual void render(const Scene& scene, Film& film, RenderContext& ctx) = 0;
    virtual WorkBudget budget() const = 0;
};

struct IntegratorEntry {
    const char* name;         // the add-on's enum identifier ("PATH")
    const char* label;        // what the menu shows ("Path Tracing")
    const char* description;  // the tooltip
    std::unique_ptr<Integrator> (*create)(const Params&);
    const std::vector<ParamSpec>& (*specs)();  // its own settings, in the order its panels draw them
    /// The memory its own data will take for these params and a film of `film_pixels` (photon maps, caches,
    /// splat buffers), for the session's estimate; null: nothing beyond the scene and the film. It may throw
    /// InvalidParameter naming the setting whose budget cannot fit.
    double (*memory_bytes)(const Params& params, double film_pixels) = nullptr;
    /// Renders in the 3D viewport (published as capabilities()["viewport_integrators"]): progressive from its first
    /// pass — every pass refines the whole image and the film shows a valid image between passes — and nothing
    /// per render that a restart after each view change would have to repeat at a cost a coarse level cannot
    /// amortise (a photon map, a cache, a Markov chain's burn-in). The viewport renders the others with PATH, with
    /// a note in its header.
    bool viewport = false;
    /// Every estimate it makes ends in a connection to the camera (Camera::connectable()): it refuses a camera
    /// that has none (the orthographic pinhole, a panorama), and the viewport falls back to PATH for such a view.
    bool needs_camera_connection = false;
    /// Renders through a panoramic camera (Camera::is_panoramic()); false: it refuses one by name (LIGHT and
    /// BDPT, whose t = 1 connections invert a perspective or orthographic viewplane), and the viewport falls back
    /// to PATH for a panoramic camera view.
    bool panoramic = true;
};

const std::vector<IntegratorEntry>& integrator_registry();
const IntegratorEntry& find_integrator(const std::string& name);
/// The integrator `params` asks for ("integrator", default PATH), built from its settings.
std::unique_ptr<Integrator> make_integrator(const Params& params);

}  // namespace candela
