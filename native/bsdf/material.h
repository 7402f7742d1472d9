// Materials as the scene arrays describe them: a fallback diffuse colour, emitted radiance, and the weighted
// closure list of the material's Cycles node tree (closure table; columns published by capabilities()).
// A material whose inputs are constants (after folding constant shader programs) has its BSDF built once for
// each face side at load time; one whose inputs vary over the surface (textures) also has MaterialInputs
// (bsdf/material_inputs.h), from which the scene builds the BSDF at each hit.
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
    int32_t inputs = -1;     // index of the material's MaterialInputs if its inputs vary over the surface

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

/// The BSDF of n closures for one face side: types[i] with row i (closure_columns() floats, weight included).
Bsdf closure_list_bsdf(const ClosureType* types, const float* rows, size_t n, bool backfacing);
/// Brings a closure row computed by a shader program into the range the closures accept (weights and
/// colours ≥ 0, IOR > 0, non-finite values → 0) instead of rejecting it: textures are user data.
void sanitize_closure_row(float* row);

}  // namespace candela
