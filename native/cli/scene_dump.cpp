#include "cli/scene_dump.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw InvalidScene("cannot read '" + p.string() + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// Parses a .npy (format 1.0–3.0) header: dtype descr, fortran order, shape; returns the data offset.
size_t parse_npy_header(const std::string& bytes, const std::string& name, std::string* descr,
                        std::vector<size_t>* shape) {
    if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) throw InvalidScene(name + " is not a .npy file");
    const int major = static_cast<unsigned char>(bytes[6]);
    size_t header_len, offset;
    if (major == 1) {
        header_len = static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
        offset = 10;
    } else {
        if (bytes.size() < 12) throw InvalidScene(name + ": truncated header");
        header_len = 0;
        for (int i = 0; i < 4; ++i) header_len |= size_t(static_cast<unsigned char>(bytes[8 + i])) << (8 * i);
        offset = 12;
    }
    if (bytes.size() < offset + header_len) throw InvalidScene(name + ": truncated header");
    const std::string h = bytes.substr(offset, header_len);
    auto field = [&](const std::string& key) {
        const size_t k = h.find("'" + key + "'");
        if (k == std::string::npos) throw InvalidScene(name + ": header has no '" + key + "'");
        return h.find(':', k) + 1;
    };
    size_t p = h.find('\'', field("descr"));
    *descr = h.substr(p + 1, h.find('\'', p + 1) - p - 1);
    if (h.compare(h.find_first_not_of(' ', field("fortran_order")), 4, "True") == 0)
        throw InvalidScene(name + ": Fortran-ordered arrays are not supported");
    p = h.find('(', field("shape"));
    const std::string dims = h.substr(p + 1, h.find(')', p) - p - 1);
    shape->clear();
    std::stringstream ss(dims);
    std::string item;
    while (std::getline(ss, item, ','))
        if (item.find_first_not_of(' ') != std::string::npos) shape->push_back(std::stoull(item));
    return offset + header_len;
}

template <typename From, typename To>
std::vector<To> convert_elements(const char* data, size_t n) {
    std::vector<To> out(n);
    for (size_t i = 0; i < n; ++i) {
        From v;
        std::memcpy(&v, data + i * sizeof(From), sizeof(From));
        out[i] = static_cast<To>(v);
    }
    return out;
}

void load_npy(SceneArrays& arrays, const std::string& key, const ArraySpec& spec, const fs::path& file) {
    const std::string bytes = read_file(file);
    std::string descr;
    std::vector<size_t> shape;
    const size_t offset = parse_npy_header(bytes, file.string(), &descr, &shape);
    size_t n = 1;
    for (size_t s : shape) n *= s;
    const char* data = bytes.data() + offset;
    const std::string kind = descr.size() >= 2 ? descr.substr(descr.size() - 2) : descr;
    if (descr[0] == '>') throw InvalidScene(file.string() + ": big-endian arrays are not supported");
    size_t elem = 0;
    if (kind == "f4" || kind == "u4" || kind == "i4")
        elem = 4;
    else if (kind == "f8" || kind == "i8" || kind == "u8")
        elem = 8;
    else if (kind == "u1" || kind == "b1" || kind == "i1")
        elem = 1;
    else
        throw InvalidScene(file.string() + ": unsupported dtype '" + descr + "'");
    if (bytes.size() < offset + n * elem) throw InvalidScene(file.string() + ": truncated data");

    auto put = [&](auto vec) { arrays.set(key, spec.type, shape, vec.data()); };
    auto dispatch = [&](auto to_tag) {
        using To = decltype(to_tag);
        if (kind == "f4")
            put(convert_elements<float, To>(data, n));
        else if (kind == "f8")
            put(convert_elements<double, To>(data, n));
        else if (kind == "u4")
            put(convert_elements<uint32_t, To>(data, n));
        else if (kind == "i4")
            put(convert_elements<int32_t, To>(data, n));
        else if (kind == "i8")
            put(convert_elements<int64_t, To>(data, n));
        else if (kind == "u8")
            put(convert_elements<uint64_t, To>(data, n));
        else if (kind == "i1")
            put(convert_elements<int8_t, To>(data, n));
        else
            put(convert_elements<uint8_t, To>(data, n));
    };
    switch (spec.type) {
    case ElemType::F32: dispatch(float{}); break;
    case ElemType::U32: dispatch(uint32_t{}); break;
    case ElemType::U8: dispatch(uint8_t{}); break;
    }
}

}  // namespace

SceneDump read_scene_dump(const std::string& directory) {
    SceneDump dump;
    const fs::path dir(directory);
    if (!fs::is_directory(dir)) throw InvalidScene("scene dump '" + directory + "' is not a directory");
    const fs::path params_file = dir / "params.json";
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(read_file(params_file));
    } catch (const nlohmann::json::exception& e) {
        throw InvalidParameter(params_file.string() + ": " + e.what());
    }
    if (!j.is_object()) throw InvalidParameter(params_file.string() + " must hold a JSON object");
    for (const auto& [key, v] : j.items()) {
        if (v.is_boolean())
            dump.params.set(key, v.get<bool>());
        else if (v.is_number_integer())
            dump.params.set(key, v.get<int64_t>());
        else if (v.is_number())
            dump.params.set(key, v.get<double>());
        else if (v.is_string())
            dump.params.set(key, v.get<std::string>());
        else
            throw InvalidParameter(params_file.string() + ": parameter '" + key + "' must be a bool, number or string");
    }
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".npy") continue;
        const std::string key = entry.path().stem().string();
        const ArraySpec* spec = find_array_spec(key);
        if (!spec) {
            dump.warnings.push_back("ignored unknown array file '" + entry.path().filename().string() + "'");
            continue;
        }
        load_npy(dump.arrays, key, *spec, entry.path());
    }
    return dump;
}

}  // namespace candela
