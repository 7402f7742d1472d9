// Materials as the scene arrays describe them: a fallback diffuse colour, emitted radiance, and the weighted
// closure list of the material's Cycles node tree (closure table; columns published by capabilities()).
// Inputs are constants, so each material's BSDF is built once for each face side at load time.
#pragma once

#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "core/vec.h"

namespace candela {

class SceneArrays;

enum class MaterialType : uint32_t { Diffuse = 0 };

/// Cycles shader nodes the closure table can hold (the add-on resolves Mix and Add Shader into weights).
enum class ClosureType : uint32_t { Diffuse = 0, Glossy, Glass, Refraction, Translucent, Transparent, Principled };

struct Material {
    Color base_color{0.8f};  // used when the material has no closures (no node tree)
    Color emission{0.f};     // emitted radiance, both sides (Cycles' emission closure)
    Bsdf front, back;        // the BSDF for paths arriving on the front (winding) side and on the back

    bool is_emissive() const { return !is_black(emission); }
    const Bsdf& bsdf(bool backfacing = false) const { return backfacing ? back : front; }
};

/// Column names of the `materials` and `closure_params` arrays, in order.
const std::vector<std::string>& material_columns();
const std::vector<std::string>& closure_columns();
/// Names of `material_type` and `closure_type` values, indexed by value.
const std::vector<std::string>& material_type_names();
const std::vector<std::string>& closure_type_names();

/// Reads and checks every material and closure row; messages name the material and the closure.
std::vector<Material> load_materials(const SceneArrays& arrays);

}  // namespace candela
