#include "texture/image_texture.h"

#include <cmath>

#include "core/math.h"
#include "texture/color_space.h"

namespace candela {

const std::vector<std::string>& tex_interpolation_names() {
    static const std::vector<std::string> names = {"CLOSEST", "LINEAR", "CUBIC"};
    return names;
}
const std::vector<std::string>& tex_extension_names() {
    static const std::vector<std::string> names = {"REPEAT", "EXTEND", "CLIP"};
    return names;
}
const std::vector<std::string>& tex_color_space_names() {
    static const std::vector<std::string> names = {"LINEAR", "SRGB"};
    return names;
}
const std::vector<std::string>& tex_storage_names() {
    static const std::vector<std::string> names = {"FLOAT", "BYTE"};
    return names;
}

namespace {

/// floor(x) as an integer and x − floor(x); non-finite or huge coordinates are pinned (they carry no
/// position information a float could resolve anyway).
int split(float x, float* frac) {
    if (!std::isfinite(x)) x = 0.f;
    x = clamp(x, -1.6e7f, 1.6e7f);
    const float f = std::floor(x);
    *frac = x - f;
    return static_cast<int>(f);
}

int wrap_periodic(int i, int n) {
    i %= n;
    return i < 0 ? i + n : i;
}

Rgba scaled(const Rgba& t, float w) { return {t.rgb * w, t.a * w}; }
void accumulate(Rgba& sum, const Rgba& t, float w) {
    sum.rgb += t.rgb * w;
    sum.a += t.a * w;
}

/// Texel (x, y) under the extension rule: returns false (transparent black) for Clip outside the image.
bool resolve(const ImageTexture& img, TexExtension ext, int* x, int* y) {
    const int w = int(img.width), h = int(img.height);
    switch (ext) {
    case TexExtension::Repeat:
        *x = wrap_periodic(*x, w);
        *y = wrap_periodic(*y, h);
        return true;
    case TexExtension::Extend:
        *x = std::min(std::max(*x, 0), w - 1);
        *y = std::min(std::max(*y, 0), h - 1);
        return true;
    case TexExtension::Clip: return *x >= 0 && *x < w && *y >= 0 && *y < h;
    }
    return false;
}

Rgba fetch(const ImageTexture& img, TexExtension ext, int x, int y) {
    if (!resolve(img, ext, &x, &y)) return {};
    return img.texel(uint32_t(x), uint32_t(y));
}

/// Uniform cubic B-spline weights for the four texels around a sample at fraction t.
void bspline_weights(float t, float w[4]) {
    const float t2 = t * t, t3 = t2 * t;
    w[0] = (1.f - 3.f * t + 3.f * t2 - t3) / 6.f;
    w[1] = (4.f - 6.f * t2 + 3.f * t3) / 6.f;
    w[2] = (1.f + 3.f * t + 3.f * t2 - 3.f * t3) / 6.f;
    w[3] = t3 / 6.f;
}

}  // namespace

Rgba ImageTexture::lookup(float u, float v, TexInterpolation interpolation, TexExtension extension) const {
    if (width == 0 || height == 0) return {};
    Rgba out;
    float fx, fy;
    switch (interpolation) {
    case TexInterpolation::Closest: {
        const int x = split(u * float(width), &fx), y = split(v * float(height), &fy);
        out = fetch(*this, extension, x, y);
        break;
    }
    case TexInterpolation::Linear: {
        const int x = split(u * float(width) - 0.5f, &fx), y = split(v * float(height) - 0.5f, &fy);
        out = scaled(fetch(*this, extension, x, y), (1.f - fx) * (1.f - fy));
        accumulate(out, fetch(*this, extension, x + 1, y), fx * (1.f - fy));
        accumulate(out, fetch(*this, extension, x, y + 1), (1.f - fx) * fy);
        accumulate(out, fetch(*this, extension, x + 1, y + 1), fx * fy);
        break;
    }
    case TexInterpolation::Cubic: {
        const int x = split(u * float(width) - 0.5f, &fx), y = split(v * float(height) - 0.5f, &fy);
        float wx[4], wy[4];
        bspline_weights(fx, wx);
        bspline_weights(fy, wy);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) accumulate(out, fetch(*this, extension, x - 1 + i, y - 1 + j), wx[i] * wy[j]);
        break;
    }
    }
    if (color_space == TexColorSpace::Srgb) out.rgb = srgb_to_linear(out.rgb);
    return out;
}

}  // namespace candela
