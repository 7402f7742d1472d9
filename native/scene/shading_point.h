// What an integrator needs of the material at a surface hit (Scene::shade): the BSDF for the side the path
// arrives from, the emitted radiance, and the shading normal after any Normal Map. For materials with
// constant inputs the BSDF is the material's own (built at load); for textured ones it is built for this
// hit and held here.
#pragma once

#include <cstring>
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
    /// *this = o, copying the ~500-byte BSDF storage only when o owns its BSDF (a plain copy always moves it all).
    /// Lists every member: a member added above must be added here.
    void copy_from(const ShadingPoint& o) {
        ns = o.ns;
        emission = o.emission;
        backfacing = o.backfacing;
        bent = o.bent;
        m_shared = o.m_shared;
        m_owns = o.m_owns;
        if (m_owns) std::memcpy(m_storage, o.m_storage, sizeof(Bsdf));
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

/// ShadingPoint's members as copy_from lists them: a member added to ShadingPoint that changes its size fails here
/// (one that fits in padding does not: copy_from's comment still applies).
struct ShadingPointMembers {
    Vec3 ns;
    Color emission;
    bool backfacing, bent;
    const Bsdf* shared;
    bool owns;
    alignas(Bsdf) unsigned char storage[sizeof(Bsdf)];
};
static_assert(sizeof(ShadingPoint) == sizeof(ShadingPointMembers),
              "ShadingPoint gained a member: copy it in ShadingPoint::copy_from and list it in ShadingPointMembers");

}  // namespace candela
