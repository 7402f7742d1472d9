// The camera side of one vertex for one fixed w_c, evaluated toward many light-side directions w_l (SPPM's gather:
// every photon at a visible point): VertexBsdf's rule (vertex_bsdf.h)
//     f(w_c, w_l) · a(w_c, w_l),   a = |w_l·n| / |w_l·ng|   (Veach's adjoint factor, n the normal of w_c's frame),
// with the shading point, the lobe subset, the frame, w_c's local direction and the bump shadowing made once, so an
// evaluation is a change of frame, the leak test and the BSDF's f. It equals VertexBsdf::f(w_c, w_l) ·
// VertexBsdf::adjoint_factor(w_c, w_l) (tests/native/vertex_bsdf_test.cpp), and, unlike VertexBsdf, is immutable
// after construction: threads may share it.
#pragma once

#include <cmath>

#include "bsdf/bsdf.h"
#include "integrators/common/lobe_classes.h"
#include "integrators/common/surface_vertex.h"
#include "scene/scene.h"

namespace candela {

class FixedViewBsdf {
public:
    /// The vertex at `hit` seen from w_c, shaded as `sp` = Scene::shade(hit, w_c); with `subset`, only its lobes.
    FixedViewBsdf(const SurfaceHit& hit, const Vec3& w_c, const ShadingPoint& sp, const LobeSubset* subset = nullptr)
        : m_bsdf(subset ? subset->apply(sp.bsdf()) : sp.bsdf()),
          m_vertex(SurfaceVertex::at(hit, sp.ns, w_c)),
          m_wc_local(m_vertex.frame.to_local(w_c)) {
        if (sp.bent) m_bsdf.set_bump_shadowing(m_vertex.bump_shadowing(true, hit.ns));
    }

    const Bsdf& bsdf() const { return m_bsdf; }

    /// f(w_c, w_l) · a(w_c, w_l); zero where w_l leaks through the surface.
    Color f_adjoint(const Vec3& w_l) const {
        const Vec3 l = m_vertex.frame.to_local(w_l);
        const float cos_g = dot(w_l, m_vertex.ng);
        if (leaks(cos_g, l.z)) return Color(0.f);
        return m_bsdf.f(m_wc_local, l) * (std::fabs(l.z) / std::fabs(cos_g));
    }

private:
    Bsdf m_bsdf;
    SurfaceVertex m_vertex;
    Vec3 m_wc_local;
};

}  // namespace candela
