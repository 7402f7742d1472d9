#include "input/scene_arrays.h"
#include <algorithm>

#include <cmath>
#include <cstring>

#include "core/error.h"

namespace candela {

const std::vector<ArraySpec>& array_schema() {
    static const std::vector<ArraySpec> schema = {
        {"positions", ElemType::F32, {-1, 3}, true},
        {"triangles", ElemType::U32, {-1, 3}, true},
        {"normals", ElemType::F32, {-1, 3, 3}, false},
        {"vertex_normals", ElemType::F32, {-1, 3}, false},
        {"tri_smooth", ElemType::U8, {-1}, false},
        {"tri_material", ElemType::U32, {-1}, true},
        {"mesh_tri_start", ElemType::U32, {-1}, true},
        {"instance_mesh", ElemType::U32, {-1}, true},
        {"instance_transform", ElemType::F32, {-1, 4, 4}, true},
        {"instance_flags", ElemType::U8, {-1}, false},
        {"instance_pass_index", ElemType::U32, {-1}, false},
        {"instance_color", ElemType::F32, {-1, 4}, false},
        {"instance_random", ElemType::F32, {-1}, false},
        {"instance_terminator", ElemType::F32, {-1}, false},
        {"instance_motion", ElemType::F32, {-1, -1, 4, 4}, false},
        {"material_type", ElemType::U32, {-1}, true},
        {"materials", ElemType::F32, {-1, -1}, true},
        {"material_holdout", ElemType::F32, {-1}, false},
        {"closure_material", ElemType::U32, {-1}, false},
        {"closure_type", ElemType::U32, {-1}, false},
        {"closure_params", ElemType::F32, {-1, -1}, false},
        {"light_type", ElemType::U32, {-1}, false},
        {"lights", ElemType::F32, {-1, -1}, false},
        {"camera_to_world", ElemType::F32, {4, 4}, true},
        {"camera_motion", ElemType::F32, {-1, 4, 4}, false},
        {"world_color", ElemType::F32, {3}, false},
        {"uvs", ElemType::F32, {-1, 3, 2}, false},
        {"tangents", ElemType::F32, {-1, 3, 4}, false},
        {"corner_attributes", ElemType::F32, {-1, 3, -1}, false},
        {"mesh_texspace", ElemType::F32, {-1, 6}, false},
        {"textures", ElemType::F32, {-1, 4}, false},
        {"textures_u8", ElemType::U8, {-1, 4}, false},
        {"texture_info", ElemType::U32, {-1, 5}, false},
        {"ramps", ElemType::F32, {-1, 256, 4}, false},
        {"shader_consts", ElemType::F32, {-1}, false},
        {"shader_ops", ElemType::U32, {-1, 8}, false},
        {"shader_programs", ElemType::U32, {-1}, false},
        {"input_bindings", ElemType::U32, {-1, 6}, false},
    };
    return schema;
}

const ArraySpec* find_array_spec(const std::string& name) {
    for (const auto& s : array_schema())
        if (name == s.name) return &s;
    return nullptr;
}

size_t element_size(ElemType t) { return t == ElemType::U8 ? 1 : 4; }
const char* elem_type_name(ElemType t) {
    switch (t) {
    case ElemType::F32: return "float32";
    case ElemType::U32: return "uint32";
    default: return "uint8";
    }
}

size_t Array::count() const {
    size_t n = 1;
    for (size_t s : shape) n *= s;
    return n;
}

namespace {

std::string shape_str(const std::vector<size_t>& shape) {
    std::string s = "(";
    for (size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
    return s + (shape.size() == 1 ? ",)" : ")");
}

std::string spec_shape_str(const std::vector<int>& shape) {
    std::string s = "(";
    for (size_t i = 0; i < shape.size(); ++i)
        s += (i ? ", " : "") + (shape[i] < 0 ? std::string("N") : std::to_string(shape[i]));
    return s + (shape.size() == 1 ? ",)" : ")");
}

}  // namespace

void SceneArrays::set(const std::string& name, ElemType type, std::vector<size_t> shape, const void* data) {
    const ArraySpec* spec = find_array_spec(name);
    if (!spec) throw InvalidScene("unknown scene array '" + name + "'");
    if (type != spec->type)
        throw InvalidScene("scene array '" + name + "' must be " + elem_type_name(spec->type) + ", got " +
                           elem_type_name(type));
    bool ok = shape.size() == spec->shape.size();
    for (size_t i = 0; ok && i < shape.size(); ++i) ok = spec->shape[i] < 0 || size_t(spec->shape[i]) == shape[i];
    if (!ok)
        throw InvalidScene("scene array '" + name + "' has shape " + shape_str(shape) + ", expected " +
                           spec_shape_str(spec->shape));
    Array a;
    a.type = type;
    a.shape = std::move(shape);
    a.bytes.resize(a.count() * element_size(type));
    if (!a.bytes.empty()) std::memcpy(a.bytes.data(), data, a.bytes.size());
    m_arrays[name] = std::move(a);
}

const Array* SceneArrays::find(const std::string& name) const {
    auto it = m_arrays.find(name);
    return it == m_arrays.end() ? nullptr : &it->second;
}

const Array& SceneArrays::get(const std::string& name) const {
    const Array* a = find(name);
    if (!a) throw InvalidScene("scene array '" + name + "' is missing");
    return *a;
}

size_t SceneArrays::byte_size() const {
    size_t n = 0;
    for (const auto& [k, a] : m_arrays) n += a.bytes.size();
    return n;
}

void SceneArrays::validate() const {
    for (const auto& spec : array_schema())
        if (spec.required && !has(spec.name))
            throw InvalidScene(std::string("scene array '") + spec.name + "' is missing");

    const size_t V = rows("positions"), T = rows("triangles"), K = rows("material_type");
    const size_t M1 = rows("mesh_tri_start"), I = rows("instance_mesh");

    auto check_finite = [](const Array& a, const char* name, size_t per_row) {
        const float* p = a.data<float>();
        for (size_t i = 0; i < a.count(); ++i)
            if (!std::isfinite(p[i]))
                throw InvalidScene(std::string(name) + "[" + std::to_string(i / per_row) + "] is not finite");
    };
    check_finite(get("positions"), "positions", 3);
    check_finite(get("instance_transform"), "instance_transform", 16);
    check_finite(get("camera_to_world"), "camera_to_world", 16);
    check_finite(get("materials"), "materials", get("materials").shape[1]);
    if (has("lights")) check_finite(get("lights"), "lights", get("lights").shape[1]);
    if (has("normals")) check_finite(get("normals"), "normals", 9);
    if (has("vertex_normals")) check_finite(get("vertex_normals"), "vertex_normals", 3);
    if (has("world_color")) check_finite(get("world_color"), "world_color", 3);

    const uint32_t* tri = get("triangles").data<uint32_t>();
    for (size_t i = 0; i < 3 * T; ++i)
        if (tri[i] >= V)
            throw InvalidScene("triangles[" + std::to_string(i / 3) + "] refers to vertex " + std::to_string(tri[i]) +
                               " but there are only " + std::to_string(V) + " positions");
    auto check_rows = [&](const char* name, size_t want) {
        if (has(name) && rows(name) != want)
            throw InvalidScene(std::string("scene array '") + name + "' has " + std::to_string(rows(name)) +
                               " rows, expected " + std::to_string(want) + " (one per triangle)");
    };
    check_rows("tri_material", T);
    check_rows("tri_smooth", T);
    check_rows("normals", T);
    check_rows("uvs", T);
    check_rows("tangents", T);
    check_rows("corner_attributes", T);
    if (has("corner_attributes")) {
        const Array& at = get("corner_attributes");
        if (at.shape[2] % 4 != 0)
            throw InvalidScene("scene array 'corner_attributes' needs 4 floats per attribute slot, has " +
                               std::to_string(at.shape[2]) + " per corner");
        check_finite(at, "corner_attributes", std::max<size_t>(3 * at.shape[2], 1));
    }
    if (has("uvs")) check_finite(get("uvs"), "uvs", 6);
    if (has("tangents")) check_finite(get("tangents"), "tangents", 12);
    if (has("vertex_normals") && rows("vertex_normals") != V)
        throw InvalidScene("scene array 'vertex_normals' has " + std::to_string(rows("vertex_normals")) +
                           " rows, expected " + std::to_string(V) + " (one per position)");
    const uint32_t* mat = get("tri_material").data<uint32_t>();
    for (size_t i = 0; i < T; ++i)
        if (mat[i] >= K)
            throw InvalidScene("tri_material[" + std::to_string(i) + "] = " + std::to_string(mat[i]) +
                               " but there are only " + std::to_string(K) + " materials");
    if (rows("materials") != K)
        throw InvalidScene("'materials' has " + std::to_string(rows("materials")) + " rows but 'material_type' has " +
                           std::to_string(K));

    if (M1 < 1) throw InvalidScene("'mesh_tri_start' needs at least one entry (0)");
    const uint32_t* start = get("mesh_tri_start").data<uint32_t>();
    if (start[0] != 0 || start[M1 - 1] != T)
        throw InvalidScene("'mesh_tri_start' must start at 0 and end at the triangle count " + std::to_string(T));
    for (size_t m = 0; m + 1 < M1; ++m)
        if (start[m + 1] < start[m]) throw InvalidScene("'mesh_tri_start' decreases at mesh " + std::to_string(m));

    if (has("mesh_texspace") && rows("mesh_texspace") != M1 - 1)
        throw InvalidScene("'mesh_texspace' has " + std::to_string(rows("mesh_texspace")) + " rows, expected " +
                           std::to_string(M1 - 1) + " (one per mesh)");
    if (has("mesh_texspace")) check_finite(get("mesh_texspace"), "mesh_texspace", 6);
    if (rows("instance_transform") != I)
        throw InvalidScene("'instance_transform' has " + std::to_string(rows("instance_transform")) +
                           " rows but 'instance_mesh' has " + std::to_string(I));
    const uint32_t* im = get("instance_mesh").data<uint32_t>();
    for (size_t i = 0; i < I; ++i)
        if (im[i] + 1 >= M1)
            throw InvalidScene("instance_mesh[" + std::to_string(i) + "] = " + std::to_string(im[i]) +
                               " but there are only " + std::to_string(M1 - 1) + " meshes");
    for (const char* name :
         {"instance_flags", "instance_pass_index", "instance_color", "instance_random", "instance_terminator"})
        if (has(name) && rows(name) != I)
            throw InvalidScene(std::string("scene array '") + name + "' has " + std::to_string(rows(name)) +
                               " rows, expected " + std::to_string(I) + " (one per instance)");
    if (const Array* f = find("instance_flags"))
        for (size_t i = 0; i < I; ++i)
            if (f->data<uint8_t>()[i] > 63)
                throw InvalidScene("instance_flags[" + std::to_string(i) +
                                   "] = " + std::to_string(f->data<uint8_t>()[i]) +
                                   " has unknown bits (capabilities()['instance_flags'] lists them)");
    if (has("instance_color")) check_finite(get("instance_color"), "instance_color", 4);
    // Motion blur: every instance's and the camera's transform at 2 to k_max_motion_steps evenly spaced times
    // of the shutter interval.
    constexpr size_t k_max_motion_steps = 129;
    if (const Array* m = find("instance_motion")) {
        if (rows("instance_motion") != I)
            throw InvalidScene("scene array 'instance_motion' has " + std::to_string(rows("instance_motion")) +
                               " rows, expected " + std::to_string(I) + " (one per instance)");
        if (m->shape[1] < 2 || m->shape[1] > k_max_motion_steps)
            throw InvalidScene("scene array 'instance_motion' has " + std::to_string(m->shape[1]) +
                               " motion steps per instance, expected 2 to " + std::to_string(k_max_motion_steps));
        check_finite(*m, "instance_motion", 16 * size_t(m->shape[1]));
    }
    if (const Array* m = find("camera_motion")) {
        if (m->shape[0] < 2 || m->shape[0] > k_max_motion_steps)
            throw InvalidScene("scene array 'camera_motion' has " + std::to_string(m->shape[0]) +
                               " motion steps, expected 2 to " + std::to_string(k_max_motion_steps));
        check_finite(*m, "camera_motion", 16);
    }
    if (has("instance_random")) check_finite(get("instance_random"), "instance_random", 1);
    if (const Array* t = find("instance_terminator"))
        for (size_t i = 0; i < I; ++i) {
            const float v = t->data<float>()[i];
            if (!(v >= 0.f && v <= 1.f))
                throw InvalidScene("instance_terminator[" + std::to_string(i) + "] = " + std::to_string(v) +
                                   " must be a shadow terminator geometry offset in [0, 1]");
        }
    if (const Array* h = find("material_holdout")) {
        if (rows("material_holdout") != K)
            throw InvalidScene("scene array 'material_holdout' has " + std::to_string(rows("material_holdout")) +
                               " rows, expected " + std::to_string(K) + " (one per material)");
        for (size_t i = 0; i < K; ++i) {
            const float w = h->data<float>()[i];
            if (!(w >= 0.f && w <= 1.f))
                throw InvalidScene("material_holdout[" + std::to_string(i) + "] = " + std::to_string(w) +
                                   " must be a weight in [0, 1]");
        }
    }
    if (has("lights") != has("light_type") || rows("lights") != rows("light_type"))
        throw InvalidScene("'lights' and 'light_type' must be given together with the same number of rows");
}

}  // namespace candela
