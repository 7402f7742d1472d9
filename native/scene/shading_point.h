// What an integrator needs of the material at a surface hit (Scene::shade): the BSDF for the side the path
// arrives from, the emitted radiance, and the shading normal after any Normal Map. For materials with
// constant inputs the BSDF is the material's own (built at load); for textured ones it is built for this
// hit and held here.
#pragma once

#include <optional>

#include "bsdf/bsdf.h"
#include "core/vec.h"

namespace candela {

struct ShadingPoint {
    Vec3 ns;               // unit shading normal on the side of the winding normal (like SurfaceHit::ns)
    Color emission{0.f};   // emitted radiance (both sides)
    bool backfacing = false;

    const Bsdf& bsdf() const { return m_own ? *m_own : *m_shared; }
    void use(const Bsdf* shared) { m_shared = shared; }
    void own(Bsdf b) { m_own.emplace(std::move(b)); }

private:
    const Bsdf* m_shared = nullptr;
    std::optional<Bsdf> m_own;
};

}  // namespace candela
