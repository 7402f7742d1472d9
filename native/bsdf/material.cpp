#include "bsdf/material.h"

#include "core/error.h"
#include "scene/scene_arrays.h"

namespace candela {

const std::vector<std::string>& material_columns() {
    static const std::vector<std::string> cols = {"base_r", "base_g", "base_b", "emission_r", "emission_g", "emission_b"};
    return cols;
}

const std::vector<std::string>& material_type_names() {
    static const std::vector<std::string> names = {"DIFFUSE"};
    return names;
}

std::vector<Material> load_materials(const SceneArrays& arrays) {
    const Array& types = arrays.get("material_type");
    const Array& rows = arrays.get("materials");
    const size_t cols = rows.shape[1];
    if (cols < material_columns().size())
        throw InvalidScene("'materials' has " + std::to_string(cols) + " columns, expected " +
                           std::to_string(material_columns().size()));
    std::vector<Material> out(types.shape[0]);
    for (size_t i = 0; i < out.size(); ++i) {
        const uint32_t t = types.data<uint32_t>()[i];
        if (t >= material_type_names().size())
            throw InvalidScene("material_type[" + std::to_string(i) + "] = " + std::to_string(t) + " is unknown");
        const float* r = rows.data<float>() + i * cols;
        Material& m = out[i];
        m.type = static_cast<MaterialType>(t);
        m.base_color = Color(r[0], r[1], r[2]);
        m.emission = Color(r[3], r[4], r[5]);
        if (min_component(m.base_color) < 0.f || max_component(m.base_color) > 1.f)
            throw InvalidScene("material " + std::to_string(i) + ": base colour must be within [0, 1]");
        if (min_component(m.emission) < 0.f)
            throw InvalidScene("material " + std::to_string(i) + ": emission must not be negative");
    }
    return out;
}

}  // namespace candela
