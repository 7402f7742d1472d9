#include "bsdf/material.h"

#include <cmath>

#include "core/error.h"
#include "input/scene_arrays.h"

namespace candela {

const std::vector<std::string>& material_columns() {
    static const std::vector<std::string> cols = {"base_r",     "base_g",     "base_b",
                                                  "emission_r", "emission_g", "emission_b"};
    return cols;
}

const std::vector<std::string>& closure_columns() {
    static const std::vector<std::string> cols = {"weight_r",
                                                  "weight_g",
                                                  "weight_b",
                                                  "color_r",
                                                  "color_g",
                                                  "color_b",
                                                  "roughness",
                                                  "anisotropy",
                                                  "ior",
                                                  "distribution",
                                                  "metallic",
                                                  "specular",
                                                  "specular_tint",
                                                  "sheen",
                                                  "sheen_tint",
                                                  "clearcoat",
                                                  "clearcoat_roughness",
                                                  "transmission",
                                                  "transmission_roughness",
                                                  "subsurface",
                                                  "subsurface_r",
                                                  "subsurface_g",
                                                  "subsurface_b"};
    return cols;
}

const std::vector<std::string>& material_type_names() {
    static const std::vector<std::string> names = {"DIFFUSE"};
    return names;
}

const std::vector<std::string>& closure_type_names() {
    static const std::vector<std::string> names = {"DIFFUSE",     "GLOSSY",      "GLASS",     "REFRACTION",
                                                   "TRANSLUCENT", "TRANSPARENT", "PRINCIPLED"};
    return names;
}

namespace {

/// One closure row by column name.
struct ClosureRow {
    const float* v;
    float operator[](int column) const { return v[column]; }
    Color rgb(int first) const { return Color(v[first], v[first + 1], v[first + 2]); }
};

enum Col {
    WeightR = 0,
    ColorR = 3,
    Roughness = 6,
    Anisotropy,
    Ior,
    Distribution,
    Metallic,
    Specular,
    SpecularTint,
    Sheen,
    SheenTint,
    Clearcoat,
    ClearcoatRoughness,
    Transmission,
    TransmissionRoughness,
    Subsurface,
    SubsurfaceR
};

/// Cycles' anisotropic roughness (Anisotropic BSDF node): α = roughness², stretched by the anisotropy.
Microfacet microfacet(float roughness, float anisotropy, uint32_t distribution) {
    const float a = sqr(clamp(roughness, 0.f, 1.f));
    const float k = clamp(anisotropy, -0.99f, 0.99f);
    Microfacet m;
    m.type = distribution == 1 ? MicrofacetDistribution::Beckmann : MicrofacetDistribution::GGX;
    if (k < 0.f) {
        m.alpha_x = a / (1.f + k);
        m.alpha_y = a * (1.f + k);
    } else {
        m.alpha_x = a * (1.f - k);
        m.alpha_y = a / (1.f - k);
    }
    return m;
}

/// The closure as a (possibly multi-lobe) BSDF, colour included, for one face side.
Bsdf closure_bsdf(ClosureType type, const ClosureRow& r, bool backfacing) {
    const Color color = r.rgb(ColorR);
    const uint32_t distribution = uint32_t(r[Distribution] + 0.5f);
    switch (type) {
    case ClosureType::Diffuse:
        return r[Roughness] > 0.f ? Bsdf(OrenNayarBsdf{clamp(r[Roughness], 0.f, 1.f)}, color)
                                  : Bsdf(LambertBsdf{}, color);
    case ClosureType::Glossy:
        return Bsdf(MicrofacetReflection{microfacet(r[Roughness], r[Anisotropy], distribution), SpecularFresnel{}},
                    color);
    case ClosureType::Glass:
    case ClosureType::Refraction:
        return glass_bsdf(color, r[Roughness], r[Ior], backfacing,
                          distribution == 1 ? MicrofacetDistribution::Beckmann : MicrofacetDistribution::GGX,
                          type == ClosureType::Refraction);
    case ClosureType::Translucent: return Bsdf(TranslucentBsdf{}, color);
    case ClosureType::Transparent: return Bsdf(TransparentBsdf{}, color);
    case ClosureType::Principled: {
        PrincipledParams p;
        p.base_color = color;
        p.subsurface = r[Subsurface];
        p.subsurface_color = r.rgb(SubsurfaceR);
        p.metallic = r[Metallic];
        p.specular = r[Specular];
        p.specular_tint = r[SpecularTint];
        p.roughness = r[Roughness];
        p.anisotropic = r[Anisotropy];
        p.sheen = r[Sheen];
        p.sheen_tint = r[SheenTint];
        p.clearcoat = r[Clearcoat];
        p.clearcoat_roughness = r[ClearcoatRoughness];
        p.ior = r[Ior];
        p.transmission = r[Transmission];
        p.transmission_roughness = r[TransmissionRoughness];
        p.backfacing = backfacing;
        return principled_bsdf(p);
    }
    }
    return Bsdf();
}

void check_closure(ClosureType type, const ClosureRow& r, const std::string& where) {
    for (size_t c = 0; c < closure_columns().size(); ++c)
        if (!std::isfinite(r[int(c)])) throw InvalidScene(where + ": " + closure_columns()[c] + " is not finite");
    if (min_component(r.rgb(WeightR)) < 0.f) throw InvalidScene(where + ": negative weight");
    if (min_component(r.rgb(ColorR)) < 0.f) throw InvalidScene(where + ": negative colour");
    if ((type == ClosureType::Glass || type == ClosureType::Refraction || type == ClosureType::Principled) &&
        !(r[Ior] > 0.f))
        throw InvalidScene(where + ": IOR must be positive");
}

}  // namespace

Bsdf closure_list_bsdf(const ClosureType* types, const float* rows, size_t n, bool backfacing) {
    const size_t stride = closure_columns().size();
    Bsdf out;
    for (size_t c = 0; c < n; ++c) {
        const ClosureRow row{rows + c * stride};
        Bsdf piece = closure_bsdf(types[c], row, backfacing);
        piece.scale(row.rgb(WeightR));
        out = add(out, piece);
    }
    return out;
}

void sanitize_closure_row(float* row) {
    for (size_t c = 0; c < closure_columns().size(); ++c)
        if (!std::isfinite(row[c])) row[c] = 0.f;
    for (int c : {int(WeightR), int(WeightR) + 1, int(WeightR) + 2, int(ColorR), int(ColorR) + 1, int(ColorR) + 2,
                  int(SubsurfaceR), int(SubsurfaceR) + 1, int(SubsurfaceR) + 2})
        row[c] = std::fmax(row[c], 0.f);
    row[Ior] = std::fmax(row[Ior], 1e-5f);
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
        m.base_color = Color(r[0], r[1], r[2]);
        m.emission = Color(r[3], r[4], r[5]);
        if (min_component(m.base_color) < 0.f || max_component(m.base_color) > 1.f)
            throw InvalidScene("material " + std::to_string(i) + ": base colour must be within [0, 1]");
        if (min_component(m.emission) < 0.f)
            throw InvalidScene("material " + std::to_string(i) + ": emission must not be negative");
    }

    // Closures replace the fallback diffuse colour of the materials that have any.
    std::vector<bool> has_closures(out.size(), false);
    if (arrays.has("closure_type")) {
        const Array& ctype = arrays.get("closure_type");
        const Array& owner = arrays.get("closure_material");
        const Array& params = arrays.get("closure_params");
        const size_t n = ctype.shape[0], pcols = params.shape[1];
        if (owner.shape[0] != n || params.shape[0] != n)
            throw InvalidScene("'closure_type', 'closure_material' and 'closure_params' need the same number of rows");
        if (pcols < closure_columns().size())
            throw InvalidScene("'closure_params' has " + std::to_string(pcols) + " columns, expected " +
                               std::to_string(closure_columns().size()));
        for (size_t c = 0; c < n; ++c) {
            const uint32_t mat = owner.data<uint32_t>()[c], type = ctype.data<uint32_t>()[c];
            const std::string where = "closure " + std::to_string(c) + " of material " + std::to_string(mat);
            if (mat >= out.size())
                throw InvalidScene(where + ": there are only " + std::to_string(out.size()) + " materials");
            if (type >= closure_type_names().size())
                throw InvalidScene(where + ": unknown closure type " + std::to_string(type));
            const ClosureRow row{params.data<float>() + c * pcols};
            check_closure(ClosureType(type), row, where);
            Material& m = out[mat];
            if (!has_closures[mat]) m.front = m.back = Bsdf();
            has_closures[mat] = true;
            for (const bool backfacing : {false, true}) {
                Bsdf piece = closure_bsdf(ClosureType(type), row, backfacing);
                piece.scale(row.rgb(WeightR));
                Bsdf& target = backfacing ? m.back : m.front;
                target = add(target, piece);
            }
        }
    }
    for (size_t i = 0; i < out.size(); ++i)
        if (!has_closures[i]) out[i].front = out[i].back = Bsdf(LambertBsdf{}, out[i].base_color);
    return out;
}

}  // namespace candela
