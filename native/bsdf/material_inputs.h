// Material inputs driven by shader programs (textures, Normal Map, Math, Mix, ColorRamp): the add-on binds
// registers of a material's program to closure columns, to the emitted radiance and to the shading normal
// (`input_bindings`, docs/architecture.md). Bindings whose register does not depend on the shading point are
// folded into the closure table at load, so a material only pays for per-hit evaluation where its inputs
// really vary.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bsdf/material.h"
#include "texture/shader_program.h"

namespace candela {

/// What a binding feeds: a closure column (1 or 3 channels), the material's emitted radiance, its shading
/// normal (world space), the world's radiance, or the material's Holdout weight (the channels' mean, clamped to
/// [0, 1]).
enum class InputTarget : uint32_t { Closure = 0, Emission, Normal, World, Holdout };
const std::vector<std::string>& input_target_names();

struct MaterialInputs {
    struct Binding {
        uint32_t closure;   // index among the material's closures
        uint32_t column;    // first column in the closure row
        uint32_t channels;  // 1 or 3
        uint32_t reg;       // program register
    };
    uint32_t program = 0;
    std::vector<ClosureType> types;       // the material's closures
    std::vector<float> rows;              // their rows (closure_columns() wide), constant inputs folded in
    std::vector<Binding> bindings;        // the inputs that vary
    int32_t emission_reg = -1;            // varying emitted radiance
    int32_t normal_reg = -1;              // shading normal
    bool normal_is_displacement = false;  // it comes from the Displacement output (bump only), not a BSDF's Normal
                                          // input: the smooth normal itself moves (no bump shadowing, as Cycles)
    int32_t holdout_reg = -1;             // varying Holdout weight

    /// The closure rows with the program's registers applied.
    void apply(const Vec3* regs, float* rows_out) const;
    /// The BSDF for one face side from evaluated registers.
    Bsdf bsdf(const Vec3* regs, bool backfacing) const;
};

/// Reads `input_bindings` for the materials: folds constant bindings into `materials` (their BSDFs and
/// emission are rebuilt) and returns the MaterialInputs of the materials whose inputs vary, setting
/// Material::inputs. *world_reg/*world_program receive the WORLD binding (−1 if none). A HOLDOUT binding that
/// does not vary is folded into `holdout` (per material, `material_holdout`; grown to the material count).
std::vector<MaterialInputs> load_material_inputs(const SceneArrays& arrays, const ShaderLibrary& shaders,
                                                 std::vector<Material>& materials, int32_t* world_program,
                                                 int32_t* world_reg, std::vector<float>* holdout = nullptr);

/// The Holdout weight a register holds: the mean of its channels, clamped to [0, 1] (Cycles' average()).
float holdout_weight(const Vec3& reg);

}  // namespace candela
