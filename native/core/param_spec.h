// Published render settings. Each integrator (and the camera-sample settings every integrator shares) declares
// its parameters as a list of ParamSpecs — key, label, type, default, range, enum items, description, panel group
// — and reads them only through that list, so what the add-on draws, what it sends and what the core accepts
// cannot drift apart: the add-on builds its properties and sub-panels from the published lists
// (`capabilities()["integrator_params"]`), sends only the chosen integrator's keys, and a value outside the
// published range fails the frame with a message naming the setting and the allowed values.
//
// Enum items keep their position for saved .blend files (Blender stores an enum property's number): items are
// only ever appended.
#pragma once

#include <string>
#include <vector>

#include "core/params.h"

namespace candela {

enum class ParamType { Bool, Int, Float, Enum };

struct EnumItem {
    const char* id;           // the value sent and stored ("TREE")
    const char* label;        // what the menu shows ("Light Tree")
    const char* description;  // the tooltip
};

struct ParamSpec {
    const char* key;
    const char* label;
    ParamType type;
    double default_value = 0.0;     // Bool (0/1), Int, Float
    double min = 0.0, max = 0.0;    // the accepted range (Int, Float), inclusive
    double soft_max = 0.0;          // the UI slider's end (0: max)
    const char* default_item = "";  // Enum
    std::vector<EnumItem> items;    // Enum, in their stable order
    const char* description = "";
    const char* group = "";      // the sub-panel section it is drawn in ("Light Paths", "Light Sampling")
    const char* active_if = "";  // drawn greyed out unless this holds: "KEY==ID", "KEY!=ID" or "KEY>N"
};

ParamSpec bool_param(const char* key, const char* label, bool def, const char* description, const char* group = "");
ParamSpec int_param(const char* key, const char* label, int def, int min, int max, const char* description,
                    const char* group = "", int soft_max = 0);
ParamSpec float_param(const char* key, const char* label, double def, double min, double max, const char* description,
                      const char* group = "", double soft_max = 0.0);
ParamSpec enum_param(const char* key, const char* label, const char* def, std::vector<EnumItem> items,
                     const char* description, const char* group = "");
/// The same spec, drawn greyed out unless `condition` holds (ParamSpec::active_if).
ParamSpec active_if(ParamSpec spec, const char* condition);

/// Validated reads of published parameters: each value is taken from `params` (marking the key used), or the
/// spec's default, and checked against the spec's type and range; a bad value throws InvalidParameter naming the
/// setting, its value and what it accepts.
class ParamReader {
public:
    ParamReader(const Params& params, const std::vector<ParamSpec>& specs) : m_params(params), m_specs(specs) {}

    bool get_bool(const char* key) const;
    int get_int(const char* key) const;
    float get_float(const char* key) const;
    double get_double(const char* key) const;
    std::string get_enum(const char* key) const;

private:
    const ParamSpec& spec(const char* key, ParamType type) const;
    const Params& m_params;
    const std::vector<ParamSpec>& m_specs;
};

/// The ids of an enum spec's items, in order.
std::vector<std::string> enum_ids(const ParamSpec& spec);

}  // namespace candela
