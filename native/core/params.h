// Typed, defaulted render parameters (a flat name → value map, as the add-on and the scene dump pass them).
// get<T>(key, default) marks the key as used; unused_keys() lists the rest so typos reach the user.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace candela {

class Params {
public:
    using Value = std::variant<bool, int64_t, double, std::string>;

    void set(const std::string& key, Value value) { m_values[key] = Entry{std::move(value), false}; }
    bool has(const std::string& key) const { return m_values.count(key) != 0; }

    /// The value of key converted to T (bool, int, int64_t, float, double, std::string), or fallback.
    /// Throws InvalidParameter if the key exists with an incompatible type.
    template <typename T>
    T get(const std::string& key, const T& fallback) const;

    /// Like get but the key must exist.
    template <typename T>
    T require(const std::string& key) const;

    /// get<std::string> restricted to a fixed set of names; throws listing the valid names otherwise.
    std::string get_enum(const std::string& key, const std::string& fallback,
                         const std::vector<std::string>& allowed) const;

    std::vector<std::string> unused_keys() const;
    const std::map<std::string, Value> values() const;

private:
    struct Entry {
        Value value;
        mutable bool used = false;
    };
    std::map<std::string, Entry> m_values;
};

}  // namespace candela
