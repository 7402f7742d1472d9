// The split of a BSDF the irradiance cache works with (ic_tracer.h): its Lambertian lobes, whose indirect light the
// cache serves, and the others, traced on.
#pragma once

#include <new>
#include <type_traits>
#include <variant>

#include "bsdf/bsdf.h"

namespace candela {

inline const Bsdf& empty_bsdf() {
    static const Bsdf empty;
    return empty;
}

/// A BSDF split into its Lambertian lobes (reflectance rho_d; what the cache serves) and the others. The common
/// cases — all Lambertian, none Lambertian — refer to the BSDF itself instead of copying it; only a mixed BSDF is
/// copied (into raw storage: a default-constructed Bsdf would cost its lobe array's initialisation at every vertex).
class LobeSplit {
public:
    Color rho_d{0.f};
    const Bsdf* diffuse = nullptr;
    const Bsdf* other = nullptr;

    explicit LobeSplit(const Bsdf& b) {
        int lambert = 0;
        for (int i = 0; i < b.size(); ++i)
            if (std::holds_alternative<LambertBsdf>(b[i].lobe)) {
                ++lambert;
                rho_d += b[i].weight;
            }
        if (lambert == 0) {
            diffuse = &empty_bsdf();
            other = &b;
        } else if (lambert == b.size()) {
            diffuse = &b;
            other = &empty_bsdf();
        } else {
            Bsdf* d = new (m_storage[0]) Bsdf();
            Bsdf* o = new (m_storage[1]) Bsdf();
            for (int i = 0; i < b.size(); ++i)
                (std::holds_alternative<LambertBsdf>(b[i].lobe) ? d : o)->add(b[i].lobe, b[i].weight);
            diffuse = d;
            other = o;
        }
    }

private:
    static_assert(std::is_trivially_destructible_v<Bsdf>, "LobeSplit keeps BSDFs in raw storage");
    alignas(Bsdf) unsigned char m_storage[2][sizeof(Bsdf)];
};

}  // namespace candela
