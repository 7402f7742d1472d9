#include "core/params.h"

#include <cmath>
#include <limits>
#include <type_traits>

#include "core/error.h"

namespace candela {
namespace {

const char* type_name(const Params::Value& v) {
    switch (v.index()) {
    case 0: return "bool";
    case 1: return "int";
    case 2: return "float";
    default: return "str";
    }
}

template <typename T>
T convert(const std::string& key, const Params::Value& v) {
    auto fail = [&](const char* want) -> T {
        throw InvalidParameter("parameter '" + key + "' must be " + want + ", got " + type_name(v));
    };
    if constexpr (std::is_same_v<T, std::string>) {
        if (auto s = std::get_if<std::string>(&v)) return *s;
        return fail("a string");
    } else if constexpr (std::is_same_v<T, bool>) {
        if (auto b = std::get_if<bool>(&v)) return *b;
        if (auto i = std::get_if<int64_t>(&v)) return *i != 0;
        return fail("a bool");
    } else if constexpr (std::is_integral_v<T>) {
        int64_t i = 0;
        if (auto p = std::get_if<int64_t>(&v))
            i = *p;
        else if (auto b = std::get_if<bool>(&v))
            i = *b ? 1 : 0;
        else if (auto d = std::get_if<double>(&v); d && std::floor(*d) == *d && std::fabs(*d) < 9e15)
            i = static_cast<int64_t>(*d);
        else
            return fail("an integer");
        if (i < static_cast<int64_t>(std::numeric_limits<T>::min()) ||
            i > static_cast<int64_t>(std::numeric_limits<T>::max()))
            throw InvalidParameter("parameter '" + key + "' = " + std::to_string(i) + " is out of range");
        return static_cast<T>(i);
    } else {
        static_assert(std::is_floating_point_v<T>);
        double d = 0.0;
        if (auto p = std::get_if<double>(&v))
            d = *p;
        else if (auto i = std::get_if<int64_t>(&v))
            d = static_cast<double>(*i);
        else
            return fail("a number");
        if (!std::isfinite(d)) throw InvalidParameter("parameter '" + key + "' is not finite");
        return static_cast<T>(d);
    }
}

}  // namespace

template <typename T>
T Params::get(const std::string& key, const T& fallback) const {
    auto it = m_values.find(key);
    if (it == m_values.end()) return fallback;
    it->second.used = true;
    return convert<T>(key, it->second.value);
}

template <typename T>
T Params::require(const std::string& key) const {
    auto it = m_values.find(key);
    if (it == m_values.end()) throw InvalidParameter("missing required parameter '" + key + "'");
    it->second.used = true;
    return convert<T>(key, it->second.value);
}

std::string Params::get_enum(const std::string& key, const std::string& fallback,
                             const std::vector<std::string>& allowed) const {
    const std::string v = get<std::string>(key, fallback);
    for (const auto& a : allowed)
        if (a == v) return v;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw InvalidParameter("parameter '" + key + "' = '" + v + "' is not one of: " + list);
}

std::vector<std::string> Params::unused_keys() const {
    std::vector<std::string> out;
    for (const auto& [k, e] : m_values)
        if (!e.used) out.push_back(k);
    return out;
}

const std::map<std::string, Params::Value> Params::values() const {
    std::map<std::string, Value> out;
    for (const auto& [k, e] : m_values) out.emplace(k, e.value);
    return out;
}

#define CANDELA_PARAMS_INSTANTIATE(T)                              \
    template T Params::get<T>(const std::string&, const T&) const; \
    template T Params::require<T>(const std::string&) const;
CANDELA_PARAMS_INSTANTIATE(bool)
CANDELA_PARAMS_INSTANTIATE(int)
CANDELA_PARAMS_INSTANTIATE(int64_t)
CANDELA_PARAMS_INSTANTIATE(uint32_t)
CANDELA_PARAMS_INSTANTIATE(float)
CANDELA_PARAMS_INSTANTIATE(double)
CANDELA_PARAMS_INSTANTIATE(std::string)
#undef CANDELA_PARAMS_INSTANTIATE

}  // namespace candela
