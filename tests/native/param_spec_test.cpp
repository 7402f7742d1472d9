// Published settings (core/param_spec.h): each integrator reads exactly the keys it publishes (and the common
// ones), with the published defaults, and refuses a value outside the published range with a message naming it.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/error.h"
#include "integrators/integrator.h"
#include "integrators/pixel_sampling.h"

namespace candela::test {
namespace {

void set_default(Params& p, const ParamSpec& s) {
    switch (s.type) {
    case ParamType::Bool: p.set(s.key, s.default_value != 0.0); break;
    case ParamType::Int: p.set(s.key, int64_t(s.default_value)); break;
    case ParamType::Float: p.set(s.key, s.default_value); break;
    case ParamType::Enum: p.set(s.key, std::string(s.default_item)); break;
    }
}

TEST(ParamSpec, EveryIntegratorReadsExactlyWhatItPublishes) {
    for (const IntegratorEntry& e : integrator_registry()) {
        Params p;
        for (const ParamSpec& s : common_param_specs()) set_default(p, s);
        for (const ParamSpec& s : e.specs()) set_default(p, s);
        ASSERT_NO_THROW(e.create(p)) << e.name;
        EXPECT_TRUE(p.unused_keys().empty()) << e.name << " does not read '" << p.unused_keys().front() << "'";
    }
}

TEST(ParamSpec, PublishedSpecsAreWellFormed) {
    for (const IntegratorEntry& e : integrator_registry()) {
        std::set<std::string> keys;
        for (const ParamSpec& s : common_param_specs()) keys.insert(s.key);
        for (const ParamSpec& s : e.specs()) {
            EXPECT_TRUE(keys.insert(s.key).second) << e.name << " publishes '" << s.key << "' twice (or a common key)";
            EXPECT_STRNE(s.label, "") << s.key;
            EXPECT_STRNE(s.description, "") << s.key;
            if (s.type == ParamType::Int || s.type == ParamType::Float) {
                EXPECT_LE(s.min, s.default_value) << s.key;
                EXPECT_LE(s.default_value, s.max) << s.key;
            }
            if (s.type == ParamType::Enum) {
                const auto ids = enum_ids(s);
                EXPECT_NE(std::find(ids.begin(), ids.end(), std::string(s.default_item)), ids.end()) << s.key;
            }
        }
    }
}

// A value just outside the published range fails the integrator's construction (before any work) with a message
// naming the key and the range.
TEST(ParamSpec, AValueOutsideThePublishedRangeIsRefusedByName) {
    for (const IntegratorEntry& e : integrator_registry()) {
        std::vector<ParamSpec> specs = common_param_specs();
        specs.insert(specs.end(), e.specs().begin(), e.specs().end());
        for (const ParamSpec& s : specs) {
            if (s.type != ParamType::Int && s.type != ParamType::Float) continue;
            for (double bad : {s.min - 1.0, s.max + 1.0}) {
                if (s.type == ParamType::Int && (bad < -9e18 || bad > 9e18)) continue;
                Params p;
                if (s.type == ParamType::Int)
                    p.set(s.key, int64_t(bad));
                else
                    p.set(s.key, bad);
                try {
                    e.create(p);
                    ADD_FAILURE() << e.name << " accepted " << s.key << " = " << bad;
                } catch (const InvalidParameter& err) {
                    EXPECT_NE(std::string(err.what()).find(s.key), std::string::npos) << err.what();
                    EXPECT_NE(std::string(err.what()).find("range"), std::string::npos) << err.what();
                }
            }
        }
        Params wrong_type;
        wrong_type.set("samples", std::string("many"));
        EXPECT_THROW(e.create(wrong_type), InvalidParameter);
        Params unknown_item;
        unknown_item.set("sampler", std::string("BLUE_NOISE"));
        EXPECT_THROW(e.create(unknown_item), InvalidParameter);
    }
}

TEST(ParamSpec, ReadingAnUnpublishedKeyIsABug) {
    Params p;
    const std::vector<ParamSpec> specs = {int_param("a", "A", 1, 0, 2, "a setting")};
    const ParamReader read(p, specs);
    EXPECT_EQ(read.get_int("a"), 1);
    EXPECT_THROW(read.get_int("b"), InternalError);
    EXPECT_THROW(read.get_float("a"), InternalError);  // read with another type than published
}

}  // namespace
}  // namespace candela::test
