// A vertex of a bidirectional subpath (Veach 1997, ch. 10; pbrt-v3 §16.3): where it is, how it scatters, the
// throughput of the subpath up to it, and its two area densities — p_fwd, with which its own subpath's sampling
// produced it, and p_rev, with which the other direction's sampling would produce it (filled in once the next vertex
// is sampled, and for the connection vertices by the MIS weight). Camera subpaths grow from the camera toward the
// lights, light subpaths from an emitter toward the camera; a surface vertex's BSDF is the path tracer's in both
// (integrators/common/vertex_bsdf.h), so for a camera vertex `w` is its w_c (toward the camera side) and for a light
// vertex its w_l.
//
// Distant vertices (an escaped camera ray's world, a sun or world light vertex) store densities in solid angle, as
// pbrt does: a distant light's "position" is a direction.
#pragma once

#include <new>
#include <type_traits>
#include <utility>

#include "integrators/common/vertex_bsdf.h"
#include "lights/light_emission.h"
#include "scene/scene.h"

namespace candela {

enum class VertexKind : uint8_t { Camera, Light, Surface };

/// A surface vertex's BSDF, constructed in place (it refers to the vertex's `hit`), with std::optional's interface.
/// The storage is raw: declaring a vertex (BDPT makes one for every fresh light or lens point of a strategy) must not
/// initialise the BSDF's ~1.6 KB, which GCC does for an optional's payload.
class VertexBsdfSlot {
public:
    VertexBsdfSlot() {}
    template <class... Args>
    VertexBsdf& emplace(Args&&... args) {
        m_made = true;
        return *new (m_storage) VertexBsdf(std::forward<Args>(args)...);
    }
    void reset() { m_made = false; }
    explicit operator bool() const { return m_made; }
    const VertexBsdf* operator->() const { return get(); }
    const VertexBsdf& operator*() const { return *get(); }

private:
    static_assert(std::is_trivially_destructible_v<VertexBsdf>, "VertexBsdfSlot never destroys its BSDF");
    const VertexBsdf* get() const { return std::launder(reinterpret_cast<const VertexBsdf*>(m_storage)); }
    bool m_made = false;
    alignas(VertexBsdf) unsigned char m_storage[sizeof(VertexBsdf)];
};

struct PathVertex {
    VertexKind kind = VertexKind::Surface;
    Vec3 p{0.f};
    Vec3 ng{0.f};     // unit geometric normal (winding side); zero for points and the camera
    Vec3 w{0.f};      // unit direction toward the previous vertex of its own subpath
    Color beta{0.f};  // the subpath's throughput arriving at this vertex
    float pdf_fwd = 0.f, pdf_rev = 0.f;
    bool delta = false;     // left by a delta lobe (connections through it are impossible)
    bool infinite = false;  // a distant light or the world seen by an escaped ray: `w` is the direction toward it,
                            // not toward the previous vertex
    // Light vertices: the emitter (EmitterSet index) and the radiance it sends along `d_out` (set when known).
    int32_t emitter = -1;
    Color Le{0.f};
    bool delta_light = false;  // an emitter no ray can hit (point, spot, soft sun): no strategy s = 0 reaches it
    // Surface vertices
    SurfaceHit hit;
    VertexBsdfSlot bsdf;  // constructed in place (it refers to `hit`): never copy a surface vertex

    /// Back to a blank vertex (the BSDF refers to `hit`: vertices are reused in place, never copied).
    void clear() {
        bsdf.reset();
        kind = VertexKind::Surface;
        p = ng = w = Vec3(0.f);
        beta = Le = Color(0.f);
        pdf_fwd = pdf_rev = 0.f;
        delta = infinite = delta_light = false;
        emitter = -1;
        hit = SurfaceHit();
    }

    bool on_surface() const { return kind == VertexKind::Surface || (kind == VertexKind::Light && !is_zero(ng)); }
    static bool is_zero(const Vec3& v) { return v.x == 0.f && v.y == 0.f && v.z == 0.f; }
};

/// p_ω (solid angle at `from`, toward `to`) as an area density at `to`: p_ω·|cos θ_to|/d² (a distant `to`: p_ω).
inline float solid_angle_to_area(const PathVertex& from, const PathVertex& to, float pdf_omega) {
    if (to.infinite) return pdf_omega;
    const Vec3 d = to.p - from.p;
    const float d2 = length_squared(d);
    if (!(d2 > 0.f)) return 0.f;
    float density = pdf_omega / d2;
    if (to.on_surface()) density *= std::fabs(dot(to.ng, d)) / std::sqrt(d2);
    return density;
}

}  // namespace candela
