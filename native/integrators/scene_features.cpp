// What the session tells the user when the chosen integrator cannot honour a feature the scene uses
// (Integrator::honoured_features, docs/light_paths.md).
#include <string>

#include "integrators/integrator.h"

namespace candela {

std::string unhonoured_features_note(const std::string& integrator, uint32_t honoured, const Scene& scene) {
    std::string what;
    auto note = [&](uint32_t feature, bool used, const char* text) {
        if (used && !(honoured & feature)) what += (what.empty() ? "" : "; ") + std::string(text);
    };
    note(k_feature_light_path, scene.reads_light_path(),
         "the Light Path node's outputs are not defined for its paths and read 0 (Is Camera Ray, Is Shadow Ray, Is "
         "Diffuse Ray, Is Glossy Ray, the depths, Ray Length)");
    note(k_feature_transparent_shadows, scene.has_transparent_materials(),
         "Transparent surfaces block its shadow rays and connections (no transparent shadows) and its paths count "
         "passing through them as bounces");
    note(k_feature_terminator_offset, scene.has_terminator_offsets(),
         "the shadow terminator offset of smooth meshes is not applied");
    note(k_feature_bump_shadowing, scene.has_bent_normals(),
         "the bump shadowing term at Bump and Normal Map normals is not applied everywhere (its images of bumped "
         "surfaces are brighter toward the terminator than PATH's)");
    note(k_feature_motion_blur, scene.has_motion(),
         "motion blur is not rendered: the camera and every object are at the shutter's middle");
    // Every integrator: a moving emitter's triangles are lights at fixed places.
    if (scene.has_still_moving_emitters())
        what += std::string(what.empty() ? "" : "; ") +
                "moving emitting objects are rendered still at the shutter's middle (their triangles are lights)";
    return what.empty() ? std::string() : integrator + ": " + what;
}

}  // namespace candela
