#include "texture/color_space.h"

#include <algorithm>

namespace candela {

namespace {

/// Hue (fraction of a turn) of rgb given its largest and smallest component.
float hue_of(const Color& c, float hi, float lo) {
    const float delta = hi - lo;
    if (!(delta > 0.f)) return 0.f;
    float h;
    if (c.x == hi)
        h = (c.y - c.z) / delta;
    else if (c.y == hi)
        h = 2.f + (c.z - c.x) / delta;
    else
        h = 4.f + (c.x - c.y) / delta;
    h /= 6.f;
    return h < 0.f ? h + 1.f : h;
}

/// The fully saturated colour of hue h (fraction of a turn), components in [0, 1].
Color pure_hue(float h) {
    h = h - std::floor(h);
    const float r = std::fabs(h * 6.f - 3.f) - 1.f;
    const float g = 2.f - std::fabs(h * 6.f - 2.f);
    const float b = 2.f - std::fabs(h * 6.f - 4.f);
    return {clamp(r, 0.f, 1.f), clamp(g, 0.f, 1.f), clamp(b, 0.f, 1.f)};
}

}  // namespace

Color rgb_to_hsv(const Color& c) {
    const float hi = max_component(c), lo = min_component(c);
    const float s = hi != 0.f ? (hi - lo) / hi : 0.f;
    return {s > 0.f ? hue_of(c, hi, lo) : 0.f, s, hi};
}

Color hsv_to_rgb(const Color& hsv) {
    if (hsv.y == 0.f) return Color(hsv.z);
    // v·(1 − s + s·pure) blends white and the pure hue at value v.
    return (Color(1.f - hsv.y) + pure_hue(hsv.x) * hsv.y) * hsv.z;
}

Color rgb_to_hsl(const Color& c) {
    const float hi = max_component(c), lo = min_component(c);
    const float l = 0.5f * (hi + lo);
    if (hi == lo) return {0.f, 0.f, l};
    const float d = hi - lo;
    const float s = l > 0.5f ? d / (2.f - hi - lo) : d / (hi + lo);
    return {hue_of(c, hi, lo), s, l};
}

Color hsl_to_rgb(const Color& hsl) {
    const float chroma = (1.f - std::fabs(2.f * hsl.z - 1.f)) * hsl.y;
    return (pure_hue(hsl.x) - Color(0.5f)) * chroma + Color(hsl.z);
}

}  // namespace candela
