#include "bsdf/material_inputs.h"

#include <cmath>

#include "core/error.h"
#include "input/scene_arrays.h"

namespace candela {

const std::vector<std::string>& input_target_names() {
    static const std::vector<std::string> names = {"CLOSURE", "EMISSION", "NORMAL", "WORLD", "HOLDOUT"};
    return names;
}

float holdout_weight(const Vec3& reg) {
    const float w = (reg.x + reg.y + reg.z) / 3.f;
    return std::isfinite(w) ? clamp(w, 0.f, 1.f) : 0.f;
}

void MaterialInputs::apply(const Vec3* regs, float* rows_out) const {
    const size_t stride = closure_columns().size();
    std::copy(rows.begin(), rows.end(), rows_out);
    for (const Binding& b : bindings) {
        float* r = rows_out + b.closure * stride + b.column;
        const Vec3& v = regs[b.reg];
        for (uint32_t k = 0; k < b.channels; ++k) r[k] = v[int(k)];
    }
    for (size_t c = 0; c < types.size(); ++c) sanitize_closure_row(rows_out + c * stride);
}

Bsdf MaterialInputs::bsdf(const Vec3* regs, bool backfacing) const {
    constexpr size_t k_inline_floats = 16 * 32;
    float inline_rows[k_inline_floats];
    std::vector<float> heap;
    float* out = inline_rows;
    if (rows.size() > k_inline_floats) {
        heap.resize(rows.size());
        out = heap.data();
    }
    apply(regs, out);
    return closure_list_bsdf(types.data(), out, types.size(), backfacing);
}

namespace {

struct RawBinding {
    InputTarget target;
    uint32_t row, column, channels, program, reg;
};

}  // namespace

std::vector<MaterialInputs> load_material_inputs(const SceneArrays& arrays, const ShaderLibrary& shaders,
                                                 std::vector<Material>& materials, int32_t* world_program,
                                                 int32_t* world_reg, std::vector<float>* holdout) {
    *world_program = *world_reg = -1;
    std::vector<MaterialInputs> out;
    const Array* bind = arrays.find("input_bindings");
    if (!bind || bind->shape[0] == 0) return out;

    const size_t stride = closure_columns().size();
    const size_t n_closures = arrays.rows("closure_type");
    const Array* owner = arrays.find("closure_material");
    const Array* ctype = arrays.find("closure_type");
    const Array* params = arrays.find("closure_params");

    // Each material's closures in table order: global closure index → (material, local index).
    std::vector<std::vector<uint32_t>> closures_of(materials.size());
    std::vector<uint32_t> local_index(n_closures, 0);
    for (uint32_t c = 0; c < n_closures; ++c) {
        const uint32_t m = owner->data<uint32_t>()[c];  // checked by load_materials
        local_index[c] = uint32_t(closures_of[m].size());
        closures_of[m].push_back(c);
    }

    // Read and check every binding, grouped by material.
    std::vector<std::vector<RawBinding>> by_material(materials.size());
    const uint32_t* r = bind->data<uint32_t>();
    for (size_t i = 0; i < bind->shape[0]; ++i, r += 6) {
        const std::string where = "input_bindings[" + std::to_string(i) + "]";
        if (r[0] >= input_target_names().size())
            throw InvalidScene(where + ": target " + std::to_string(r[0]) + " is unknown");
        RawBinding b{InputTarget(r[0]), r[1], r[2], r[3], r[4], r[5]};
        if (b.program >= shaders.program_count())
            throw InvalidScene(where + ": program " + std::to_string(b.program) + " does not exist");
        if (b.reg >= shaders.program_size(b.program))
            throw InvalidScene(where + ": register " + std::to_string(b.reg) + " is past the end of program " +
                               std::to_string(b.program));
        uint32_t material = 0;
        switch (b.target) {
        case InputTarget::Closure:
            if (b.row >= n_closures)
                throw InvalidScene(where + ": closure " + std::to_string(b.row) + " does not exist");
            if (!(b.channels == 1 || b.channels == 3)) throw InvalidScene(where + ": channels must be 1 or 3");
            if (b.column + b.channels > stride)
                throw InvalidScene(where + ": columns " + std::to_string(b.column) + "+" + std::to_string(b.channels) +
                                   " are past the closure table's " + std::to_string(stride) + " columns");
            material = owner->data<uint32_t>()[b.row];
            break;
        case InputTarget::Emission:
        case InputTarget::Normal:
        case InputTarget::Holdout:
            if (b.row >= materials.size())
                throw InvalidScene(where + ": material " + std::to_string(b.row) + " does not exist");
            material = b.row;
            break;
        case InputTarget::World:
            if (*world_program >= 0) throw InvalidScene(where + ": the world has a second binding");
            *world_program = int32_t(b.program);
            *world_reg = int32_t(b.reg);
            continue;
        }
        if (!by_material[material].empty() && by_material[material][0].program != b.program)
            throw InvalidScene(where + ": material " + std::to_string(material) +
                               " binds registers of two programs; a material has one program");
        by_material[material].push_back(b);
    }

    for (size_t m = 0; m < materials.size(); ++m) {
        if (by_material[m].empty()) continue;
        MaterialInputs in;
        in.program = by_material[m][0].program;
        for (uint32_t c : closures_of[m]) {
            in.types.push_back(ClosureType(ctype->data<uint32_t>()[c]));
            const float* row = params->data<float>() + size_t(c) * params->shape[1];
            in.rows.insert(in.rows.end(), row, row + stride);
        }
        // Fold what does not vary: one evaluation anywhere gives its value everywhere.
        ShaderRegisters regs(shaders.program_size(in.program));
        shaders.evaluate(in.program, ShadingInputs{}, regs.data());
        Material& mat = materials[m];
        for (const RawBinding& b : by_material[m]) {
            const bool varying = shaders.varying(in.program, b.reg);
            switch (b.target) {
            case InputTarget::Closure:
                if (varying) {
                    in.bindings.push_back({local_index[b.row], b.column, b.channels, b.reg});
                } else {
                    float* dst = in.rows.data() + local_index[b.row] * stride + b.column;
                    for (uint32_t k = 0; k < b.channels; ++k) dst[k] = regs[b.reg][int(k)];
                }
                break;
            case InputTarget::Emission:
                if (varying) {
                    in.emission_reg = int32_t(b.reg);
                    mat.emission = Color(0.f);  // per hit (Scene::shade); its triangles are lights (Scene::emission)
                } else {
                    mat.emission = vmax(regs[b.reg], Color(0.f));
                }
                break;
            case InputTarget::Normal:
                if (varying) {  // a constant normal input is ignored
                    in.normal_reg = int32_t(b.reg);
                    in.normal_is_displacement = b.column == 1;
                }
                break;
            case InputTarget::Holdout:
                if (varying) {
                    in.holdout_reg = int32_t(b.reg);
                } else if (holdout) {
                    if (holdout->size() < materials.size()) holdout->resize(materials.size(), 0.f);
                    (*holdout)[m] = holdout_weight(regs[b.reg]);
                }
                break;
            case InputTarget::World: break;
            }
        }
        for (size_t c = 0; c < in.types.size(); ++c) sanitize_closure_row(in.rows.data() + c * stride);
        if (!in.types.empty()) {
            mat.front = closure_list_bsdf(in.types.data(), in.rows.data(), in.types.size(), false);
            mat.back = closure_list_bsdf(in.types.data(), in.rows.data(), in.types.size(), true);
        }
        if (!in.bindings.empty() || in.emission_reg >= 0 || in.normal_reg >= 0 || in.holdout_reg >= 0) {
            mat.inputs = int32_t(out.size());
            out.push_back(std::move(in));
        }
    }
    return out;
}

}  // namespace candela
