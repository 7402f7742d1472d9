// The light-path settings of Blender's Light Paths panel with Cycles 3.4's semantics (docs/light_paths.md): the
// bounce budget per scattering type, Clamp Direct and Indirect, Filter Glossy and the Caustics switches, plus what a
// camera path carries for them and for the Light Path node. One copy of each rule, for every integrator whose paths
// start at the camera (a light-rooted path has no camera-side depth or ray type: those integrators do not publish
// these settings, and the session says so for the scene features they cannot honour).
//
// Bounce budget (Cycles' path_state_next, with its kernel's limits of the UI value + 1). A path counts its
// scatterings: every non-transparent one adds to the total and to one type — a reflection to diffuse or glossy (a
// mirror counts as glossy), any transmission (glass, translucency) to transmission — and a Transparent BSDF's
// pass-through only to transparent. When a count exceeds its limit, the next surface the ray reaches contributes
// its emission and lets the ray on through its Transparent closures, and the path ends at the first surface
// without them ("terminate after transparent"); once the transparent count exceeds its limit the next surface gives
// its emission only. So Max Bounces 0 is direct light, and Diffuse 0 keeps direct light on diffuse surfaces.
//
// Clamps (Cycles' kernel_accum_clamp): a contribution — throughput × radiance × MIS weight — whose |R| + |G| + |B|
// exceeds 3·c is scaled down to that sum; c is Clamp Direct for light that reaches the camera by at most one
// scattering (emission seen directly, and at the first surface both next-event estimation and emission found by its
// continuation) and Clamp Indirect for everything else; 0 turns a clamp off. Biased: it removes energy.
//
// Filter Glossy (Cycles' surface_shader_prepare_closures): with f > 0, a vertex reached by a path whose smallest
// scattering density so far (over its non-delta, non-transparent scatterings) is p < f gets every microfacet lobe's
// α raised to at least ½·√(1 − p/f): sharp reflections seen after a diffuse bounce are blurred, which removes
// caustic fireflies. Biased.
//
// Caustics (Cycles' svm closure rules): at a vertex reached by a ray from a diffuse scattering, Reflective off drops
// glossy reflection lobes and Refractive off drops refraction (bsdf/bsdf_filters.h splits glass as Cycles does), so
// no path carries light along diffuse → specular → … → light. Biased.
#pragma once

#include <cmath>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "bsdf/bsdf_filters.h"
#include "core/param_spec.h"
#include "texture/shader_program.h"

namespace candela {

/// The Light Paths settings (besides max_bounces, which every path integrator publishes itself).
struct LightPathSettings {
    int max_bounces = 12;
    int diffuse_bounces = 1024, glossy_bounces = 1024, transmission_bounces = 1024, transparent_bounces = 8;
    float clamp_direct = 0.f, clamp_indirect = 0.f;
    float filter_glossy = 0.f;
    bool caustics_reflective = true, caustics_refractive = true;

    /// The published settings, identical for every integrator that honours them (append them to its own specs).
    static std::vector<ParamSpec> specs() {
        return {
            int_param("diffuse_bounces", "Diffuse", 1024, 0, 1024,
                      "Maximum diffuse reflections along a path, as Cycles counts them (Cycles' default is 4; "
                      "1024: only Max Bounces limits them)",
                      "Max Bounces", 16),
            int_param("glossy_bounces", "Glossy", 1024, 0, 1024,
                      "Maximum glossy and mirror reflections along a path (Cycles' default is 4; 1024: only Max "
                      "Bounces limits them)",
                      "Max Bounces", 16),
            int_param("transmission_bounces", "Transmission", 1024, 0, 1024,
                      "Maximum transmissions (glass, refraction, translucency) along a path (Cycles' default is 12; "
                      "1024: only Max Bounces limits them)",
                      "Max Bounces", 16),
            int_param("transparent_bounces", "Transparent", 8, 0, 1024,
                      "Maximum Transparent BSDF surfaces a path or shadow ray passes through; they do not count as "
                      "bounces (Cycles' default, 8)",
                      "Max Bounces", 64),
            float_param("clamp_direct", "Direct Light", 0.0, 0.0, 1e9,
                        "Clamp light reaching the camera by at most one scattering: a contribution whose R + G + B "
                        "exceeds 3× this is scaled down to it; 0 = off (Cycles' default). Biased",
                        "Clamping", 100.0),
            float_param("clamp_indirect", "Indirect Light", 0.0, 0.0, 1e9,
                        "The same for light after more scatterings; 0 = off (Cycles' default is 10). Biased: it "
                        "removes fireflies by removing energy",
                        "Clamping", 100.0),
            float_param("filter_glossy", "Filter Glossy", 0.0, 0.0, 10.0,
                        "Blur glossy reflections seen after unlikely (diffuse, rough) bounces to reduce caustic "
                        "noise; 0 = off (Cycles' default is 1). Biased",
                        "Caustics", 10.0),
            bool_param("caustics_reflective", "Reflective Caustics", true,
                       "Light reflected by glossy surfaces onto diffuse ones (off: glossy reflection is dropped at "
                       "surfaces reached by diffuse rays, as in Cycles)",
                       "Caustics"),
            bool_param("caustics_refractive", "Refractive Caustics", true,
                       "Light refracted by glass onto diffuse surfaces (off: refraction is dropped at surfaces reached "
                       "by diffuse rays, as in Cycles)",
                       "Caustics"),
        };
    }

    /// Reads the settings (max_bounces from the integrator's own spec of it) through the integrator's reader.
    static LightPathSettings read(const ParamReader& r) {
        LightPathSettings s;
        s.max_bounces = r.get_int("max_bounces");
        s.diffuse_bounces = r.get_int("diffuse_bounces");
        s.glossy_bounces = r.get_int("glossy_bounces");
        s.transmission_bounces = r.get_int("transmission_bounces");
        s.transparent_bounces = r.get_int("transparent_bounces");
        s.clamp_direct = r.get_float("clamp_direct");
        s.clamp_indirect = r.get_float("clamp_indirect");
        s.filter_glossy = r.get_float("filter_glossy");
        s.caustics_reflective = r.get_bool("caustics_reflective");
        s.caustics_refractive = r.get_bool("caustics_refractive");
        return s;
    }
};

/// Scatterings so far along a camera path (the ray being traced was produced by the last of them).
struct PathDepth {
    int bounce = 0, diffuse = 0, glossy = 0, transmission = 0, transparent = 0;
};

/// What a camera path carries for these rules and for the Light Path node.
struct LightPathState {
    PathDepth depth;
    uint32_t ray_flags = LightPathInfo::k_camera;  // the Light Path node's ray types of the ray being traced
    float min_ray_pdf = std::numeric_limits<float>::infinity();  // Filter Glossy's smallest scattering density
    bool transparent_background = true;  // the ray is the camera ray, through transparent surfaces only

    /// The Light Path node's inputs where the ray, after `ray_length` of its last segment, reaches a surface.
    LightPathInfo info(float ray_length) const {
        LightPathInfo i;
        i.flags = ray_flags;
        i.ray_length = ray_length;
        i.depth = depth.bounce;
        i.diffuse_depth = depth.diffuse;
        i.glossy_depth = depth.glossy;
        i.transmission_depth = depth.transmission;
        i.transparent_depth = depth.transparent;
        return i;
    }
    /// The inputs of a shadow ray (or light sampling's emission evaluation) leaving a vertex this state arrived at:
    /// Cycles counts such rays one bounce further.
    LightPathInfo shadow_info() const {
        LightPathInfo i = info(0.f);
        i.flags = LightPathInfo::k_shadow;
        i.depth += 1;
        return i;
    }
};

/// Whether a vertex reached with depth d may scatter (next-event estimation, a bounce); false: it gives its emission
/// and, if may_pass_transparent, lets the ray through its Transparent closures.
inline bool may_scatter(const LightPathSettings& s, const PathDepth& d) {
    return d.bounce <= s.max_bounces && d.diffuse <= s.diffuse_bounces && d.glossy <= s.glossy_bounces &&
           d.transmission <= s.transmission_bounces && d.transparent <= s.transparent_bounces;
}
inline bool may_pass_transparent(const LightPathSettings& s, const PathDepth& d) {
    return d.transparent <= s.transparent_bounces;
}

/// The state of the ray a scattering sampled as `bs` (a BSDF sample, local frame) continues with. `see_through`:
/// the scattering keeps the background transparent behind it (Film > Transparent Glass: a smooth enough refraction).
inline void after_scatter(LightPathState& st, const BsdfSample& bs, bool see_through = false) {
    if (bs.is_transparent()) {  // the same ray, carried on: only the transparent count changes
        ++st.depth.transparent;
        return;
    }
    ++st.depth.bounce;
    uint32_t flags;
    if (bs.is_transmission()) {
        ++st.depth.transmission;
        flags = LightPathInfo::k_transmission;
    } else {
        if (bs.flags & k_bsdf_diffuse)
            ++st.depth.diffuse;
        else
            ++st.depth.glossy;
        flags = LightPathInfo::k_reflection;
    }
    if (bs.flags & k_bsdf_diffuse)
        flags |= LightPathInfo::k_diffuse;
    else if (bs.flags & k_bsdf_glossy)
        flags |= LightPathInfo::k_glossy;
    else
        flags |= LightPathInfo::k_glossy | LightPathInfo::k_singular;
    st.ray_flags = flags;
    if (!bs.is_delta()) st.min_ray_pdf = std::fmin(st.min_ray_pdf, bs.pdf);
    st.transparent_background = st.transparent_background && see_through;
}

/// Clamps a contribution by Cycles' rule; `scatterings` is how many scatterings the light took to reach the camera
/// beyond the first surface (0: direct — next-event estimation at the first surface, emission found by the camera
/// ray or by the first surface's continuation).
inline __attribute__((always_inline)) void clamp_contribution(Color& c, const LightPathSettings& s, int scatterings) {
    const float limit = scatterings > 0 ? s.clamp_indirect : s.clamp_direct;
    if (!(limit > 0.f)) return;
    const float sum = std::fabs(c.x) + std::fabs(c.y) + std::fabs(c.z);
    if (sum > 3.f * limit) c *= 3.f * limit / sum;
}

/// Room for one BSDF that is only constructed when needed (a Bsdf is ~500 bytes: default-constructing one at every
/// vertex would zero it for nothing). Bsdf is trivially destructible, so nothing needs destroying.
class BsdfSlot {
public:
    Bsdf& emplace(const Bsdf& b) { return *new (m_storage) Bsdf(b); }

private:
    alignas(Bsdf) unsigned char m_storage[sizeof(Bsdf)];
};

/// Whether vertex_scattering_bsdf can change a BSDF under these settings (bump shadowing aside).
inline bool modifies_bsdfs(const LightPathSettings& s) {
    return s.filter_glossy > 0.f || !s.caustics_reflective || !s.caustics_refractive;
}

/// The BSDF a vertex scatters with under Filter Glossy and the Caustics switches (and bump shadowing, if `bump` is
/// active): `bsdf` itself when nothing applies, else a modified copy in `slot`. cos_o: the outgoing direction's
/// cosine with the shading normal.
inline const Bsdf& vertex_scattering_bsdf(const Bsdf& bsdf, const LightPathSettings& s, const LightPathState& st,
                                          float cos_o, const BumpShadowing& bump, BsdfSlot& slot) {
    const Bsdf* b = &bsdf;
    Bsdf* own = nullptr;  // b, once it is the slot's
    const bool from_diffuse = (st.ray_flags & LightPathInfo::k_diffuse) != 0;
    if (from_diffuse && caustics_filter_changes(*b, s.caustics_reflective, s.caustics_refractive))
        b = own = &slot.emplace(caustics_filter(*b, cos_o, s.caustics_reflective, s.caustics_refractive));
    if (s.filter_glossy > 0.f && st.min_ray_pdf < s.filter_glossy && has_microfacet_lobe(*b)) {
        const float blur_pdf = st.min_ray_pdf / s.filter_glossy;
        b = own = &slot.emplace(blur_bsdf(*b, 0.5f * std::sqrt(1.f - blur_pdf)));
    }
    if (bump.active) {
        if (!own) b = own = &slot.emplace(*b);
        own->set_bump_shadowing(bump);
    }
    return *b;
}

/// The settings a light-rooted integrator (its paths start at the lights) cannot honour, named for its log when
/// they differ from their defaults; empty if none do.
inline std::string unhonoured_light_path_settings(const LightPathSettings& s) {
    const LightPathSettings d;
    std::string out;
    auto note = [&](bool differs, const char* what) {
        if (differs) out += (out.empty() ? "" : ", ") + std::string(what);
    };
    note(s.diffuse_bounces != d.diffuse_bounces || s.glossy_bounces != d.glossy_bounces ||
             s.transmission_bounces != d.transmission_bounces,
         "per-type bounce limits");
    note(s.clamp_direct != d.clamp_direct || s.clamp_indirect != d.clamp_indirect, "clamping");
    note(s.filter_glossy != d.filter_glossy, "Filter Glossy");
    note(s.caustics_reflective != d.caustics_reflective || s.caustics_refractive != d.caustics_refractive,
         "the Caustics switches");
    return out;
}

}  // namespace candela
