// The flat scene arrays that cross the Python ↔ native boundary (schema: docs/architecture.md), owned
// copies plus their validation. Every message names the array and the first bad index.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace candela {

enum class ElemType { F32, U32, U8 };

/// One entry of the schema: name, element type and shape; -1 is a free extent.
struct ArraySpec {
    const char* name;
    ElemType type;
    std::vector<int> shape;
    bool required;
};

/// The schema, in one place for the Python module, the CLI and the tests.
const std::vector<ArraySpec>& array_schema();
const ArraySpec* find_array_spec(const std::string& name);

struct Array {
    ElemType type = ElemType::F32;
    std::vector<size_t> shape;
    std::vector<unsigned char> bytes;

    size_t count() const;  // number of elements
    template <typename T>
    const T* data() const {
        return reinterpret_cast<const T*>(bytes.data());
    }
};

class SceneArrays {
public:
    /// Stores a copy of `count` elements of `data`; the type must be the schema's and the shape must fit it.
    void set(const std::string& name, ElemType type, std::vector<size_t> shape, const void* data);

    bool has(const std::string& name) const { return m_arrays.count(name) != 0; }
    const Array& get(const std::string& name) const;
    const Array* find(const std::string& name) const;

    /// Checks presence, cross-array sizes, index ranges and finiteness; throws InvalidScene.
    void validate() const;

    size_t rows(const std::string& name) const {
        const Array* a = find(name);
        return a ? a->shape[0] : 0;
    }
    size_t byte_size() const;

private:
    std::map<std::string, Array> m_arrays;
};

size_t element_size(ElemType t);
const char* elem_type_name(ElemType t);

}  // namespace candela
