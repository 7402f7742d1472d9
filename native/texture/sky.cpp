#include "texture/sky.h"

#include <cmath>

#include "core/math.h"

namespace candela {

size_t sky_state_size(SkyModel model) {
    switch (model) {
    case SkyModel::Preetham: return 20;
    case SkyModel::Nishita: return 9;
    }
    return 0;
}

Vec3 xyz_to_rec709(const Vec3& c) {
    return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
            -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
            0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

namespace {

float perez(const float* k, float theta, float gamma) {
    const float cg = std::cos(gamma);
    return (1.f + k[0] * std::exp(k[1] / std::cos(theta))) * (1.f + k[2] * std::exp(k[3] * gamma) + k[4] * cg * cg);
}

Vec3 preetham(const float* s, const Vec3& d) {
    const float len = length(d);
    if (!(len > 0.f)) return Vec3(0.f);
    // Spherical angles as the Sky Texture takes them: θ from +Z, φ = atan2(x, y).
    float theta = std::acos(clamp(d.z / len, -1.f, 1.f));
    const float phi = std::atan2(d.x, d.y);
    const float cos_gamma = std::sin(theta) * std::sin(s[0]) * std::cos(s[1] - phi) + std::cos(theta) * std::cos(s[0]);
    const float gamma = std::acos(clamp(cos_gamma, -1.f, 1.f));
    theta = std::fmin(theta, 0.5f * k_pi - 0.001f);
    const float Y = s[2] * perez(s + 5, theta, gamma);
    const float x = s[3] * perez(s + 10, theta, gamma);
    const float y = s[4] * perez(s + 15, theta, gamma);
    if (!(y != 0.f)) return Vec3(0.f);
    return xyz_to_rec709(Vec3(x / y * Y, Y, (1.f - x - y) / y * Y));
}

}  // namespace

Vec3 sky_radiance(SkyModel model, const float* state, const Vec3& d) {
    switch (model) {
    case SkyModel::Preetham: return preetham(state, d);
    case SkyModel::Nishita: break;  // tabulated: ShaderLibrary evaluates it
    }
    return Vec3(0.f);
}

}  // namespace candela

#include "texture/cie.h"

namespace candela {

Vec3 blackbody_rec709(float kelvin) {
    // Planck's spectral radiance up to a constant: λ⁻⁵ / (exp(hc/(λ k T)) − 1), hc/k = 1.4388e-2 m·K. Only the
    // chromaticity matters: the result is normalised to luminance 1.
    const double t = std::fmax(double(kelvin), 800.0);
    double xyz[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < k_cie_samples; ++k) {
        const double lambda = (double(k_cie_first_nm) + double(k_cie_step_nm) * k) * 1e-9;
        const double planck = 1.0 / (std::pow(lambda * 1e6, 5.0) * (std::exp(1.4388e-2 / (lambda * t)) - 1.0));
        for (int c = 0; c < 3; ++c) xyz[c] += planck * double(k_cie_cmf[k][c]);
    }
    Vec3 rgb = vmax(xyz_to_rec709(Vec3(float(xyz[0]), float(xyz[1]), float(xyz[2]))), Vec3(0.f));
    const float lum = luminance(rgb);
    return lum > 0.f ? rgb / lum : Vec3(0.f);
}

Vec3 wavelength_rec709(float nm) {
    const float x = (nm - 380.f) * (1.f / 5.f);
    if (!(x >= 0.f) || !(x < float(k_cie_5nm_samples - 1))) return Vec3(0.f);
    const int i = int(x);
    const float t = x - float(i);
    const float* a = k_cie_cmf_5nm[i];
    const float* b = k_cie_cmf_5nm[i + 1];
    const Vec3 xyz(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t);
    return vmax(xyz_to_rec709(xyz) * (1.f / 2.52f), Vec3(0.f));
}

}  // namespace candela
