// What an integrator needs of the material at a surface hit (Scene::shade): the BSDF for the side the path
// arrives from, the emitted radiance, and the shading normal after any Normal Map. For materials with
// constant inputs the BSDF is the material's own (built at load); for textured ones it is built for this
// hit and held here.
#pragma once

#include <new>
#include <type_traits>

#include "bsdf/bsdf.h"
#include "core/vec.h"

namespace candela {

struct ShadingPoint {
    Vec3 ns;              // unit shading normal on the side of the winding normal (like SurfaceHit::ns)
    Color emission{0.f};  // emitted radiance (both sides)
    bool backfacing = false;
    bool bent = false;  // a Bump or Normal Map node moved ns off the smooth normal (bump shadowing applies)

    const Bsdf& bsdf() const { return m_owns ? *std::launder(reinterpret_cast<const Bsdf*>(m_storage)) : *m_shared; }
    void use(const Bsdf* shared) { m_shared = shared; }
    void own(const Bsdf& b) {
        new (m_storage) Bsdf(b);
        m_owns = true;
    }

private:
    // Raw storage, not std::optional<Bsdf>: a hit on a constant material (the common case) then costs no
    // initialisation of the ~500-byte BSDF (GCC zero-filled the optional's payload on every shade()).
    static_assert(std::is_trivially_destructible_v<Bsdf> && std::is_trivially_copyable_v<Bsdf>,
                  "ShadingPoint keeps its own BSDF in raw storage");
    const Bsdf* m_shared = nullptr;
    bool m_owns = false;
    alignas(Bsdf) unsigned char m_storage[sizeof(Bsdf)];
};

}  // namespace candela
