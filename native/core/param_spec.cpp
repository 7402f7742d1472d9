#include "core/param_spec.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "core/error.h"

namespace candela {

ParamSpec bool_param(const char* key, const char* label, bool def, const char* description, const char* group) {
    ParamSpec s{key, label, ParamType::Bool};
    s.default_value = def ? 1.0 : 0.0;
    s.max = 1.0;
    s.description = description;
    s.group = group;
    return s;
}

ParamSpec int_param(const char* key, const char* label, int def, int min, int max, const char* description,
                    const char* group, int soft_max) {
    ParamSpec s{key, label, ParamType::Int};
    s.default_value = def;
    s.min = min;
    s.max = max;
    s.soft_max = soft_max;
    s.description = description;
    s.group = group;
    return s;
}

ParamSpec float_param(const char* key, const char* label, double def, double min, double max, const char* description,
                      const char* group, double soft_max) {
    ParamSpec s{key, label, ParamType::Float};
    s.default_value = def;
    s.min = min;
    s.max = max;
    s.soft_max = soft_max;
    s.description = description;
    s.group = group;
    return s;
}

ParamSpec enum_param(const char* key, const char* label, const char* def, std::vector<EnumItem> items,
                     const char* description, const char* group) {
    ParamSpec s{key, label, ParamType::Enum};
    s.default_item = def;
    s.items = std::move(items);
    s.description = description;
    s.group = group;
    return s;
}

ParamSpec active_if(ParamSpec spec, const char* condition) {
    spec.active_if = condition;
    return spec;
}

std::vector<std::string> enum_ids(const ParamSpec& spec) {
    std::vector<std::string> ids;
    for (const EnumItem& item : spec.items) ids.emplace_back(item.id);
    return ids;
}

namespace {

std::string number(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

/// "parameter 'max_bounces' (Max Bounces) = 2000 is outside [0, 1024]".
[[noreturn]] void out_of_range(const ParamSpec& s, double v) {
    throw InvalidParameter("parameter '" + std::string(s.key) + "' (" + s.label + ") = " + number(v) +
                           " is outside its range [" + number(s.min) + ", " + number(s.max) + "]");
}

}  // namespace

const ParamSpec& ParamReader::spec(const char* key, ParamType type) const {
    for (const ParamSpec& s : m_specs)
        if (std::strcmp(s.key, key) == 0) {
            if (s.type != type) throw InternalError(std::string("parameter '") + key + "' is read with another type");
            return s;
        }
    throw InternalError(std::string("parameter '") + key + "' is read but not published");
}

bool ParamReader::get_bool(const char* key) const {
    const ParamSpec& s = spec(key, ParamType::Bool);
    return m_params.get<bool>(key, s.default_value != 0.0);
}

int ParamReader::get_int(const char* key) const {
    const ParamSpec& s = spec(key, ParamType::Int);
    const int64_t v = m_params.get<int64_t>(key, int64_t(s.default_value));
    if (double(v) < s.min || double(v) > s.max) out_of_range(s, double(v));
    return int(v);
}

double ParamReader::get_double(const char* key) const {
    const ParamSpec& s = spec(key, ParamType::Float);
    const double v = m_params.get<double>(key, s.default_value);
    if (!(v >= s.min && v <= s.max)) out_of_range(s, v);
    return v;
}

float ParamReader::get_float(const char* key) const { return float(get_double(key)); }

std::string ParamReader::get_enum(const char* key) const {
    const ParamSpec& s = spec(key, ParamType::Enum);
    return m_params.get_enum(key, s.default_item, enum_ids(s));
}

}  // namespace candela
