// The BSDF of a path vertex, in both directions of transport. A vertex's scattering is always the path tracer's:
//     f(w_c, w_l)  =  the BSDF of w_c's side, in the shading frame of w_c (common/surface_vertex.h), radiance mode,
//                     zero where w_l leaks through the surface,
// with w_c the direction toward the camera side of the path and w_l the one toward the light side. Camera-rooted
// sampling (the path tracer, BDPT's camera subpath) draws w_l from w_c with that BSDF's own sampling; light-rooted
// sampling (light tracing, photons, BDPT's light subpath) draws w_c from w_l with the BSDF of w_l's side in the
// shading frame of w_l, in importance mode (its density follows the adjoint BSDF), and then evaluates f(w_c, w_l)
// by the rule above. Both directions therefore see one BSDF, which is what makes light tracing, BDPT and photon
// mapping agree with PATH, shading normals included.
//
// Two details make the light side's sampling cover f's support. Where the shading normal is tilted against the
// geometric one, f is non-zero for a thin band of w_c below the shading hemisphere of w_l (f uses the geometric
// frame there): a share ε of the light side's samples is cosine-distributed about the geometric normal, and the
// density is the mixture. A delta lobe's direction is kept only where the camera side would sample it back (both
// directions choose the same frame).
//
// Adjoint shading normals (Veach 1997, §5.3): a light path's throughput over a vertex is multiplied by
//     f(w_c, w_l) · |w_c·ng| · |w_l·n| / |w_l·ng|  /  p(w_c)
// — the geometric cosine of the outgoing direction (it converts the next vertex's area to this one's solid angle)
// and the ratio of the incoming direction's cosine about n, the normal of w_c's frame (the cosine the path
// tracer's rendering equation takes at this vertex), over the geometric one the previous segment carried. With
// ns = ng it is the usual f·|cos θ|/p.
//
// A vertex can also be restricted to a subset of its lobes (common/lobe_classes.h: the traced or the estimated ones),
// on both sides: the photon tracers sample each part separately. Without a subset it is the whole BSDF.
#pragma once

#include <cmath>
#include <new>
#include <type_traits>

#include "bsdf/bsdf.h"
#include "core/math.h"
#include "integrators/common/lobe_classes.h"
#include "integrators/common/surface_vertex.h"
#include "sampling/warp.h"
#include "scene/scene.h"

namespace candela {

class VertexBsdf {
public:
    /// The vertex at `hit`, shaded from direction w (the direction the path arrived along, reversed: toward where it
    /// came from), whose shading point is `sp` (Scene::shade(hit, w)).
    /// With `subset`, only those lobes of the BSDF (on either side) are the vertex's.
    VertexBsdf(const Scene& scene, const SurfaceHit& hit, const Vec3& w, const ShadingPoint& sp,
               const LobeSubset* subset = nullptr)
        : m_scene(scene), m_hit(hit), m_subset(subset) {
        const int s = side(w);
        m_sp[s].copy_from(sp);
        if (m_subset) m_sp[s].own(m_subset->apply(sp.bsdf()));
        m_shaded[s] = true;
        classify_side(s);
    }

    const SurfaceHit& hit() const { return m_hit; }
    /// The shading point of the side w arrives from (shaded on first use).
    const ShadingPoint& shading(const Vec3& w) const {
        const int s = side(w);
        if (__builtin_expect(!m_shaded[s], 0)) shade_side(s, w);
        return m_sp[s];
    }
    bool has_non_delta(const Vec3& w) const { return shading(w).bsdf().has_non_delta(); }

    /// f(w_c, w_l) of the rule above (non-delta lobes), with bump shadowing where a Bump or Normal Map node bent the
    /// normal (bsdf/bsdf.h: it scales f only, so every sampling density here is unchanged).
    Color f(const Vec3& w_c, const Vec3& w_l) const {
        const int s = shaded_side(w_c);
        if (m_flat_lambert[s]) {
            const Vec3 n = turned_ng(s);
            return dot(w_c, n) > 0.f && dot(w_l, n) > 0.f ? m_lambert_colour[s] * Color(k_inv_pi) : Color(0.f);
        }
        const ShadingPoint& sp = m_sp[s];
        const SurfaceVertex& v = vertex(w_c, sp);
        const Vec3 l = v.frame.to_local(w_l);
        if (leaks(dot(w_l, v.ng), l.z)) return Color(0.f);
        if (sp.bent) {
            Bsdf shadowed = sp.bsdf();
            shadowed.set_bump_shadowing(v.bump_shadowing(true, m_hit.ns));
            return shadowed.f(v.frame.to_local(w_c), l);
        }
        return sp.bsdf().f(v.frame.to_local(w_c), l);
    }
    /// The density with which camera-side BSDF sampling from w_c produces w_l (0 where it leaks).
    float pdf_camera(const Vec3& w_c, const Vec3& w_l) const {
        const int s = shaded_side(w_c);
        if (m_flat_lambert[s]) {
            const Vec3 n = turned_ng(s);
            const float cos_l = dot(w_l, n);
            return dot(w_c, n) > 0.f && cos_l > 0.f ? cosine_hemisphere_pdf(cos_l) : 0.f;
        }
        const ShadingPoint& sp = m_sp[s];
        const SurfaceVertex& v = vertex(w_c, sp);
        const Vec3 l = v.frame.to_local(w_l);
        if (leaks(dot(w_l, v.ng), l.z)) return 0.f;
        return sp.bsdf().pdf(v.frame.to_local(w_c), l);
    }
    /// The density with which light-side sampling (sample_light) from w_l produces w_c (non-delta).
    float pdf_light(const Vec3& w_l, const Vec3& w_c) const {
        const int s = shaded_side(w_l);
        if (m_flat_lambert[s]) {  // ε = 0 and the Lambert density of either mode
            const Vec3 n = turned_ng(s);
            const float cos_c = dot(w_c, n);
            return dot(w_l, n) > 0.f && cos_c > 0.f ? cosine_hemisphere_pdf(cos_c) : 0.f;
        }
        const ShadingPoint& sp = m_sp[s];
        const SurfaceVertex& v = vertex(w_l, sp);
        const float eps = mixture_share(v, sp.bsdf());
        const Vec3 c = v.frame.to_local(w_c);
        float p = leaks(dot(w_c, v.ng), c.z) ? 0.f : sp.bsdf().pdf(v.frame.to_local(w_l), c, TransportMode::Importance);
        if (eps > 0.f) p = (1.f - eps) * p + eps * geometric_cosine_pdf(v, sp.bsdf(), w_c);
        return p;
    }

    struct Sample {
        Vec3 w;             // the sampled direction (world)
        Color weight{0.f};  // the throughput factor over the vertex: f·|w·ng|·(shading correction)/p
        float pdf = 0.f;    // its density (the discrete probability for a delta lobe)
        bool delta = false;
        BsdfSample bsdf;  // the BSDF's own sample (flags, η)
        bool valid() const { return pdf > 0.f && !is_black(weight); }
    };

    /// Light-side sampling: w_c drawn from w_l (u: the direction, u_lobe: the lobe, the mixture and a side).
    Sample sample_light(const Vec3& w_l, Vec2 u, float u_lobe) const {
        Sample out;
        const ShadingPoint& sp = shading(w_l);
        const Bsdf& bsdf = sp.bsdf();
        if (const Color* colour = bsdf.lone_lambert(); colour && flat(sp)) return sample_flat_lambert(w_l, *colour, u);
        const SurfaceVertex& v = vertex(w_l, sp);
        const float eps = mixture_share(v, bsdf);
        if (u_lobe < eps) {  // the cosine share about ng (non-delta)
            const float uc = u_lobe / eps;
            const bool through = (bsdf.flags() & k_bsdf_transmission) && uc >= 0.5f;
            Vec3 local = sample_cosine_hemisphere(u);
            if (through) local.z = -local.z;
            out.w = Frame(v.ng).to_world(local);
            out.pdf = pdf_light(w_l, out.w);
            if (!(out.pdf > 0.f)) return {};
            out.weight = f(out.w, w_l) * (std::fabs(dot(out.w, v.ng)) * adjoint_factor(out.w, w_l) / out.pdf);
            out.bsdf.flags = (through ? k_bsdf_transmission : k_bsdf_reflection) | k_bsdf_diffuse;
            return out;
        }
        const float u_bsdf = eps > 0.f ? min_num((u_lobe - eps) / (1.f - eps), k_one_minus_epsilon) : u_lobe;
        const Vec3 l = v.frame.to_local(w_l);
        const BsdfSample bs = bsdf.sample(l, u, u_bsdf, TransportMode::Importance);
        if (!bs.valid()) return {};
        out.w = v.frame.to_world(bs.wi);
        out.bsdf = bs;
        if (leaks(dot(out.w, v.ng), bs.wi.z)) return {};
        if (bs.is_delta()) {
            // Kept only where the camera side would sample it back: both directions choose the same frame.
            if (frame_is_shading(out.w) != frame_is_shading(w_l)) return {};
            out.delta = true;
            out.pdf = (1.f - eps) * bs.pdf;
            out.weight = bs.f * (std::fabs(dot(out.w, v.ng)) * adjoint_factor(out.w, w_l) / out.pdf);
            return out;
        }
        if (eps == 0.f && !sp.bent && side(out.w) == side(w_l) && frame_index(out.w, sp) == frame_index(w_l, sp)) {
            // w_c leaves on w_l's side into w_l's own frame: f's vertex is v, so pdf_light(w_l, w_c), f(w_c, w_l)
            // and adjoint_factor(w_c, w_l) reduce to these expressions (the same operations on the same values,
            // without looking the side and frame up again).
            const Vec3 c = v.frame.to_local(out.w);
            if (leaks(dot(out.w, v.ng), c.z)) return {};
            out.pdf = bsdf.pdf(l, c, TransportMode::Importance);
            if (!(out.pdf > 0.f)) return {};
            const Color f_cl = leaks(dot(w_l, v.ng), l.z) ? Color(0.f) : bsdf.f(c, l);
            const float g = std::fabs(dot(w_l, m_hit.ng));
            const float adjoint = g > 0.f ? std::fabs(dot(w_l, v.frame.n)) / g : 0.f;
            out.weight = f_cl * (std::fabs(dot(out.w, v.ng)) * adjoint / out.pdf);
            return out;
        }
        out.pdf = pdf_light(w_l, out.w);
        if (!(out.pdf > 0.f)) return {};
        out.weight = f(out.w, w_l) * (std::fabs(dot(out.w, v.ng)) * adjoint_factor(out.w, w_l) / out.pdf);
        return out;
    }

    /// Camera-side sampling: w_l drawn from w_c by the BSDF of w_c's side in its frame, as the path tracer draws it;
    /// weight f·|w_l·ns|/p (the shading cosine of the rendering equation).
    Sample sample_camera(const Vec3& w_c, Vec2 u, float u_lobe) const {
        Sample out;
        const ShadingPoint& sp = shading(w_c);
        const SurfaceVertex& v = vertex(w_c, sp);
        const BsdfSample bs = sp.bsdf().sample(v.frame.to_local(w_c), u, u_lobe);
        if (!bs.valid() || is_black(bs.f)) return {};
        out.w = v.frame.to_world(bs.wi);
        if (leaks(dot(out.w, v.ng), bs.wi.z)) return {};
        out.bsdf = bs;
        out.delta = bs.is_delta();
        out.pdf = bs.pdf;
        // A bent normal's bump shadowing scales f only (bsdf/bsdf.h): the sample's density stays, its f is f()'s.
        const Color f_wi = sp.bent && !bs.is_delta() ? f(w_c, out.w) : bs.f;
        out.weight = f_wi * (std::fabs(bs.wi.z) / bs.pdf);
        return out;
    }
    /// |w_l·ns| for the camera side's frame of w_c: the shading cosine a connection toward w_l carries at a camera
    /// vertex.
    float camera_cosine(const Vec3& w_c, const Vec3& w_l) const {
        const int s = shaded_side(w_c);
        if (m_flat_lambert[s]) return std::fabs(dot(w_l, m_hit.ng));  // the frame's normal is ±ng
        const ShadingPoint& sp = m_sp[s];
        const SurfaceVertex& v = vertex(w_c, sp);
        return std::fabs(dot(w_l, v.frame.n));
    }

    /// Veach's adjoint factor for the incoming direction: |w_l·n|/|w_l·ng|, n the normal of w_c's frame (the
    /// cosine the rendering equation takes at this vertex, over the geometric one the previous segment carried);
    /// 1 without shading normals.
    float adjoint_factor(const Vec3& w_c, const Vec3& w_l) const {
        const float g = std::fabs(dot(w_l, m_hit.ng));
        return g > 0.f ? camera_cosine(w_c, w_l) / g : 0.f;
    }

private:
    int side(const Vec3& w) const { return dot(w, m_hit.ng) < 0.f ? 1 : 0; }
    /// side(w), that side shaded.
    int shaded_side(const Vec3& w) const {
        const int s = side(w);
        if (__builtin_expect(!m_shaded[s], 0)) shade_side(s, w);
        return s;
    }
    /// ng turned to side s: the normal of both of that side's frames where it is flat (see classify_side).
    Vec3 turned_ng(int s) const { return s == 1 ? -m_hit.ng : m_hit.ng; }

    /// Notes whether side s (just shaded) is a lone Lambert lobe on a flat face with ε = 0 (mixture_share: ns = ng
    /// gives ns·ng = |ng|²). There f, the two densities, the camera cosine and the adjoint factor reduce to the
    /// cosines about ng turned to the side: the vertex's frame on that side is Frame(±ng) for every direction (ns =
    /// ng: both of its frames are ng's), its z is that dot product, leaks() only rejects a zero one, and Lambert's f
    /// and density test the same two signs — the same values as the general path, without the frame.
    void classify_side(int s) const {
        const Color* colour = m_sp[s].bsdf().lone_lambert();
        m_flat_lambert[s] = colour && flat(m_sp[s]) && !(dot(m_hit.ng, m_hit.ng) < 1.f - 1e-5f);
        if (m_flat_lambert[s]) m_lambert_colour[s] = *colour;
    }

    /// Whether the shading normal is the geometric one (a flat face, no bump): then ε = 0, both frames of a side
    /// are ng's, and no direction above ng leaks.
    bool flat(const ShadingPoint& sp) const {
        return !sp.bent && sp.ns.x == m_hit.ng.x && sp.ns.y == m_hit.ng.y && sp.ns.z == m_hit.ng.z;
    }
    /// sample_light for a lone Lambert lobe of colour R on a flat face: the general path's BSDF sample (the cosine
    /// about ng turned to w_l, in the frame vertex() builds there, so the same direction), whose weight
    /// f·|w_c·ng|·(|w_l·n|/|w_l·ng|)/p is exactly R: f = R/π, p = cos θ/π with cos θ = |w_c·ng|, and n = ng.
    Sample sample_flat_lambert(const Vec3& w_l, const Color& colour, Vec2 u) const {
        Sample out;
        const float cos_l = dot(w_l, m_hit.ng);
        if (cos_l == 0.f) return out;  // w_l grazing: Lambert samples nothing (its local z is 0)
        const Vec3 n = cos_l < 0.f ? -m_hit.ng : m_hit.ng;
        const Vec3 local = sample_cosine_hemisphere(u);
        if (local.z <= 1e-7f) return out;  // as LambertBsdf::sample: the disk's rim, a grazing direction
        out.w = Frame(n).to_world(local);
        if (!(dot(out.w, n) > 0.f)) return out;  // leaks() of the general path
        out.pdf = cosine_hemisphere_pdf(local.z);
        out.weight = colour;
        out.bsdf.wi = local;
        out.bsdf.f = colour * k_inv_pi;
        out.bsdf.pdf = out.pdf;
        out.bsdf.flags = k_bsdf_reflection | k_bsdf_diffuse;
        return out;
    }

    __attribute__((noinline)) void shade_side(int s, const Vec3& w) const {
        m_sp[s] = m_scene.shade(m_hit, w);
        if (m_subset) m_sp[s].own(m_subset->apply(m_sp[s].bsdf()));
        m_shaded[s] = true;
        classify_side(s);
    }
    /// SurfaceVertex::at(hit, sp.ns, w) for w's side (sp: that side's shading point). The vertex depends on w only
    /// through its side and whether w is above that side's shading normal (the frame is then built on ns, else on
    /// ng), so the at most four vertices are made once each and shared by every evaluation at this vertex.
    /// Which of its side's two frames w uses: 1 if w is above ns turned to its side (the frame is ns's), else 0.
    int frame_index(const Vec3& w, const ShadingPoint& sp) const {
        const float c = dot(w, sp.ns);
        return (side(w) == 1 ? -c : c) > 0.f ? 1 : 0;
    }
    const SurfaceVertex& vertex(const Vec3& w, const ShadingPoint& sp) const {
        const int s = side(w);
        const int k = frame_index(w, sp);
        if (!m_vertex_made[s][k]) {
            new (m_vertex[s][k]) SurfaceVertex(SurfaceVertex::at(m_hit, sp.ns, w));
            m_vertex_made[s][k] = true;
        }
        return *std::launder(reinterpret_cast<const SurfaceVertex*>(m_vertex[s][k]));
    }

    /// Whether the frame of direction w (on its own side) is the shading one: w above its shading hemisphere.
    bool frame_is_shading(const Vec3& w) const {
        const ShadingPoint& sp = shading(w);
        const Vec3 ns = dot(w, m_hit.ng) < 0.f ? -sp.ns : sp.ns;
        return dot(w, ns) > 0.f;
    }
    /// ε: the share of light-side samples drawn about ng where the shading normal is tilted (see above).
    static float mixture_share(const SurfaceVertex& v, const Bsdf& bsdf) {
        return bsdf.has_non_delta() && dot(v.ns, v.ng) < 1.f - 1e-5f ? 0.1f : 0.f;
    }
    /// The cosine share's density: about ng on w_l's side (both sides, half each, for a transmitting BSDF).
    static float geometric_cosine_pdf(const SurfaceVertex& v, const Bsdf& bsdf, const Vec3& w) {
        const float c = dot(w, v.ng);
        if (bsdf.flags() & k_bsdf_transmission) return 0.5f * std::fabs(c) * k_inv_pi;
        return c > 0.f ? c * k_inv_pi : 0.f;
    }

    const Scene& m_scene;
    const SurfaceHit& m_hit;
    const LobeSubset* m_subset = nullptr;
    mutable ShadingPoint m_sp[2];
    mutable bool m_shaded[2] = {false, false};
    mutable bool m_flat_lambert[2] = {false, false};  // classify_side
    mutable Color m_lambert_colour[2];
    // [side][frame on ns]: see vertex(). Raw storage: most vertices use one of the four, and zero-filling them all
    // would cost more than making that one.
    static_assert(std::is_trivially_destructible_v<SurfaceVertex>, "VertexBsdf keeps its vertices in raw storage");
    alignas(SurfaceVertex) mutable unsigned char m_vertex[2][2][sizeof(SurfaceVertex)];
    mutable bool m_vertex_made[2][2] = {{false, false}, {false, false}};
};

}  // namespace candela
