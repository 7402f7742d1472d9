#include "sampling/sampler.h"

#include "core/error.h"

namespace candela {

std::vector<std::string> sampler_names() { return {"RANDOM"}; }

Sampler make_sampler(const std::string& name, uint64_t seed, int /*samples_per_pixel*/) {
    if (name == "RANDOM") return IndependentSampler(seed);
    throw InvalidParameter("unknown sampler '" + name + "'");
}

}  // namespace candela
