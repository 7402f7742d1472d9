#include "lights/triangle_light.h"

namespace candela {

LightSample TriangleLight::sample_li_near(const LightSampleContext& ctx, Vec2 u, float plane_dist) const {
    // One preparation gives Ω (the range test, the pdf) and the unit vertex directions the sampler needs.
    const SphericalTriangle st = SphericalTriangle::make(ctx.p, p0, p1, p2);
    if (!in_spherical_range(st.omega)) return sample_li(ctx, u);
    LightSample s;
    const SphericalSample ss = st.sample(u);
    if (!(ss.pdf > 0.f)) return s;
    const float denom = dot(ss.w, normal);
    const float t = plane_dist / denom;
    if (!(t > 0.f) || !std::isfinite(t)) return s;
    s.wi = ss.w;
    s.dist = t;
    s.pdf = ss.pdf;
    if (source) {
        const Vec3 p = ctx.p + ss.w * t;
        const Vec2 b = barycentrics(p);
        s.Li = Le(p, b.x, b.y, -ss.w);
    } else {
        s.Li = radiance;
    }
    return s;
}

}  // namespace candela
