// Ray types and per-object ray visibility, as Blender's Object > Visibility > Ray Visibility settings
// (Cycles' PATH_RAY_* visibility bits): a ray hits an object only if the object is visible to the ray's type.
// A camera ray is CAMERA; a continuation ray is the type of the scattering that produced it (diffuse or glossy
// reflection, any transmission; a transparent pass-through keeps the type of the ray it continues); a shadow ray
// is SHADOW. An untyped ray (k_ray_all) hits every object visible to any ray type.
#pragma once

#include <cstdint>

namespace candela {

enum RayType : uint8_t {
    k_ray_camera = 1u << 0,
    k_ray_diffuse = 1u << 1,
    k_ray_glossy = 1u << 2,
    k_ray_transmission = 1u << 3,
    k_ray_shadow = 1u << 4,
    k_ray_all = 0x1Fu,
};

/// `instance_flags` bits: the ray types the object is visible to, plus holdout (the object cuts a hole with
/// alpha 0 into the image where the camera sees it, Blender's Object > Visibility > Holdout).
enum ObjectFlag : uint8_t {
    k_object_holdout = 1u << 5,
    k_object_default = k_ray_all,
    k_object_all_flags = k_ray_all | k_object_holdout,
};

}  // namespace candela
