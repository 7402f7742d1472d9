// Building shader programs, images and their scene arrays by hand for the texture and environment tests.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "bsdf/material_inputs.h"
#include "input/scene_arrays.h"
#include "texture/shader_program.h"

namespace candela::test {

struct ProgramBuilder {
    std::vector<float> texels;           // RGBA
    std::vector<uint8_t> bytes;          // RGBA, 8-bit images
    std::vector<uint32_t> texture_info;  // rows of 5
    std::vector<float> ramps;            // 256 × 4 per ramp
    std::vector<float> consts;
    std::vector<ShaderOp> ops;
    std::vector<uint32_t> program_start{0};
    std::vector<uint32_t> bindings;  // rows of 6

    /// Adds a w×h image (rows bottom-up) from RGB values (alpha 1); returns its texture index.
    uint32_t image(uint32_t w, uint32_t h, const std::vector<Color>& rgb, TexColorSpace cs = TexColorSpace::Linear);
    /// Adds an 8-bit image from RGB bytes (alpha 255).
    uint32_t byte_image(uint32_t w, uint32_t h, const std::vector<std::array<uint8_t, 3>>& rgb, TexColorSpace cs);
    uint32_t ramp(const std::vector<std::array<float, 4>>& table);  // 256 entries
    /// Appends an operation to the current program; returns its register.
    uint32_t op(ShaderOpCode code, uint32_t a = 0, uint32_t b = 0, uint32_t c = 0, std::array<uint32_t, 4> i = {});
    uint32_t constant(const Vec3& v);
    /// Ends the current program; returns its index.
    uint32_t end_program();
    void bind(InputTarget target, uint32_t row, uint32_t column, uint32_t channels, uint32_t program, uint32_t reg);

    std::shared_ptr<const ShaderLibrary> library() const;
    /// Adds every array (textures, programs, bindings) to `a`.
    void add_to(SceneArrays& a) const;
};

/// Evaluates program p of `lib` at `in`; returns register r.
Vec3 eval(const ShaderLibrary& lib, uint32_t p, uint32_t r, const ShadingInputs& in = {});

}  // namespace candela::test
