// Materials as the scene arrays describe them (columns published by capabilities()), and the BSDF each
// one yields at a surface point.
#pragma once

#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "core/vec.h"

namespace candela {

class SceneArrays;

enum class MaterialType : uint32_t { Diffuse = 0 };

struct Material {
    MaterialType type = MaterialType::Diffuse;
    Color base_color{0.8f};
    Color emission{0.f};  // emitted radiance, both sides (Cycles' emission closure)

    bool is_emissive() const { return !is_black(emission); }
    Bsdf bsdf() const { return LambertBsdf{base_color}; }
};

/// Column names of the `materials` array, in order.
const std::vector<std::string>& material_columns();
/// Names of `material_type` values, indexed by value.
const std::vector<std::string>& material_type_names();

/// Reads and checks every material row (albedo in [0, 1], emission ≥ 0).
std::vector<Material> load_materials(const SceneArrays& arrays);

}  // namespace candela
