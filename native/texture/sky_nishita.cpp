#include "texture/sky_nishita.h"

#include <cmath>

#include "core/math.h"
#include "texture/cie.h"
#include "texture/sky.h"

namespace candela {

namespace {

constexpr int k_lambdas = 21;  // 380, 400, …, 780 nm
constexpr double k_earth = 6360e3, k_atmosphere = 6420e3, k_rayleigh_height = 8e3, k_mie_height = 1.2e3;
constexpr double k_mie = 2e-5, k_mie_g = 0.76;
constexpr int k_steps = 32, k_light_steps = 16;

// Extraterrestrial solar spectral irradiance, W/m²/nm (ASTM E-490 AM0, 20 nm means, rounded to 0.05).
constexpr float k_sun[k_lambdas] = {1.10f, 1.70f, 1.75f, 1.80f, 2.05f, 2.05f, 1.95f, 1.85f, 1.87f, 1.80f, 1.82f,
                                    1.75f, 1.67f, 1.60f, 1.52f, 1.50f, 1.41f, 1.35f, 1.28f, 1.23f, 1.18f};
// Ozone absorption at the density peak (25 km), per metre: the Chappuis band through Bruneton and Neyret's values
// at 440, 550 and 680 nm (2008, "Precomputed atmospheric scattering").
constexpr float k_ozone[k_lambdas] = {0.f,      0.02e-6f, 0.04e-6f, 0.085e-6f, 0.25e-6f, 0.45e-6f, 0.9e-6f,
                                      1.3e-6f,  1.7e-6f,  1.95e-6f, 2.1e-6f,   2.2e-6f,  1.9e-6f,  1.4e-6f,
                                      0.95e-6f, 0.65e-6f, 0.45e-6f, 0.3e-6f,   0.2e-6f,  0.12e-6f, 0.05e-6f};

/// Rayleigh scattering of sea-level air, ∝ λ⁻⁴ through 13.558·10⁻⁶ /m at 550 nm (Bruneton and Neyret 2008).
double rayleigh(int k) {
    const double lambda = 380.0 + 20.0 * k;
    return 13.558e-6 * std::pow(550.0 / lambda, 4.0);
}

/// Ozone's relative density: a tent from 10 to 40 km peaking at 25 km.
double ozone_density(double h) {
    if (h < 10000.0 || h >= 40000.0) return 0.0;
    return h < 25000.0 ? (h - 10000.0) / 15000.0 : (40000.0 - h) / 15000.0;
}

struct D3 {
    double x, y, z;
};
D3 add(const D3& a, const D3& b, double t) { return {a.x + b.x * t, a.y + b.y * t, a.z + b.z * t}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// Distance from p (inside the sphere of radius r) to its surface along d.
double exit_distance(const D3& p, const D3& d, double r) {
    const double b = dot(p, d), c = dot(p, p) - r * r;
    return -b + std::sqrt(std::fmax(b * b - c, 0.0));
}
bool hits_earth(const D3& p, const D3& d, double* t) {
    const double b = dot(p, d), c = dot(p, p) - k_earth * k_earth, disc = b * b - c;
    if (disc < 0.0) return false;
    *t = -b - std::sqrt(disc);
    return *t > 0.0;
}

/// Optical depths (Rayleigh, Mie, ozone: ∫ density ds) from p along d to the top of the atmosphere.
void optical_depth(const D3& p, const D3& d, double depth[3]) {
    const double length = exit_distance(p, d, k_atmosphere), ds = length / k_light_steps;
    depth[0] = depth[1] = depth[2] = 0.0;
    for (int i = 0; i < k_light_steps; ++i) {
        const double h = std::sqrt(dot(add(p, d, (i + 0.5) * ds), add(p, d, (i + 0.5) * ds))) - k_earth;
        depth[0] += std::exp(-h / k_rayleigh_height) * ds;
        depth[1] += std::exp(-h / k_mie_height) * ds;
        depth[2] += ozone_density(h) * ds;
    }
}

Vec3 spectrum_to_rec709(const double spectrum[k_lambdas]) {
    double xyz[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < k_lambdas; ++k)
        for (int c = 0; c < 3; ++c) xyz[c] += spectrum[k] * k_cie_cmf[k][c] * 20.0;  // ∫ … dλ, 20 nm bins
    return xyz_to_rec709(Vec3(float(xyz[0]), float(xyz[1]), float(xyz[2])));
}

}  // namespace

NishitaSky::NishitaSky(const NishitaParams& p) : m_params(p) {
    const float ce = std::cos(p.sun_elevation);
    m_sun = Vec3(std::sin(p.sun_rotation) * ce, std::cos(p.sun_rotation) * ce, std::sin(p.sun_elevation));
    m_table.resize(size_t(k_azimuths) * k_elevations);
    for (int j = 0; j < k_elevations; ++j) {
        const float v = float(j) / float(k_elevations - 1);
        const float elevation = 0.5f * k_pi * v * v;  // more rows near the horizon, where the sky changes fastest
        for (int i = 0; i < k_azimuths; ++i)
            m_table[size_t(j) * k_azimuths + i] = sky(k_pi * float(i) / float(k_azimuths - 1), elevation);
    }
    // The disc: sunlight transmitted along the rays to its lower and upper edges, over the disc's solid angle.
    const double solid_angle = 2.0 * k_pi * (1.0 - std::cos(0.5 * double(p.sun_size)));
    const D3 eye{0.0, 0.0, k_earth + double(p.altitude) + 1.0};
    for (int edge = 0; edge < 2; ++edge) {
        const double e = double(p.sun_elevation) + (edge ? 0.5 : -0.5) * double(p.sun_size);
        const D3 d{0.0, std::cos(e), std::sin(e)};
        double spectrum[k_lambdas] = {}, depth[3], t;
        if (!hits_earth(eye, d, &t)) {
            optical_depth(eye, d, depth);
            for (int k = 0; k < k_lambdas; ++k) {
                const double tau = rayleigh(k) * p.air * depth[0] + k_mie * 1.11 * p.dust * depth[1] +
                                   double(k_ozone[k]) * p.ozone * depth[2];
                spectrum[k] = k_sun[k] * std::exp(-tau) / solid_angle;
            }
        }
        (edge ? m_sun_top : m_sun_bottom) = vmax(spectrum_to_rec709(spectrum), Vec3(0.f));
    }
}

Vec3 NishitaSky::sky(float azimuth, float elevation) const {
    // Single scattering along the view ray from the eye to the top of the atmosphere (or the ground): at each of
    // k_steps points, sunlight attenuated on its way in and on the way to the eye, times the local scattering.
    const NishitaParams& p = m_params;
    const D3 eye{0.0, 0.0, k_earth + double(p.altitude) + 1.0};
    const D3 view{std::sin(double(azimuth)) * std::cos(double(elevation)),
                  std::cos(double(azimuth)) * std::cos(double(elevation)), std::sin(double(elevation))};
    const D3 sun{0.0, std::cos(double(p.sun_elevation)), std::sin(double(p.sun_elevation))};
    double length = exit_distance(eye, view, k_atmosphere), t_ground;
    if (hits_earth(eye, view, &t_ground)) length = t_ground;
    const double ds = length / k_steps;
    const double mu = dot(view, sun);
    const double phase_r = 3.0 / (16.0 * k_pi) * (1.0 + mu * mu);
    const double g2 = k_mie_g * k_mie_g;
    const double phase_m =
        3.0 / (8.0 * k_pi) * (1.0 - g2) * (1.0 + mu * mu) / ((2.0 + g2) * std::pow(1.0 + g2 - 2.0 * k_mie_g * mu, 1.5));
    double spectrum[k_lambdas] = {};
    double eye_depth[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < k_steps; ++i) {
        const D3 q = add(eye, view, (i + 0.5) * ds);
        const double h = std::sqrt(dot(q, q)) - k_earth;
        const double dr = std::exp(-h / k_rayleigh_height) * ds, dm = std::exp(-h / k_mie_height) * ds,
                     dz = ozone_density(h) * ds;
        // Depth from the eye to the middle of this segment.
        const double depth_r = eye_depth[0] + 0.5 * dr, depth_m = eye_depth[1] + 0.5 * dm,
                     depth_z = eye_depth[2] + 0.5 * dz;
        eye_depth[0] += dr;
        eye_depth[1] += dm;
        eye_depth[2] += dz;
        double t;
        if (hits_earth(q, sun, &t)) continue;  // in the Earth's shadow
        double light[3];
        optical_depth(q, sun, light);
        for (int k = 0; k < k_lambdas; ++k) {
            const double tau = rayleigh(k) * p.air * (depth_r + light[0]) +
                               k_mie * 1.11 * p.dust * (depth_m + light[1]) +
                               double(k_ozone[k]) * p.ozone * (depth_z + light[2]);
            spectrum[k] += std::exp(-tau) * (rayleigh(k) * p.air * dr * phase_r + k_mie * p.dust * dm * phase_m);
        }
    }
    for (int k = 0; k < k_lambdas; ++k) spectrum[k] *= k_sun[k];
    return vmax(spectrum_to_rec709(spectrum), Vec3(0.f));
}

Vec3 NishitaSky::radiance(const Vec3& d_in) const {
    const float len = length(d_in);
    if (!(len > 0.f)) return Vec3(0.f);
    const Vec3 d = d_in / len;
    const float elevation = std::asin(clamp(d.z, -1.f, 1.f));
    // The sun disc.
    const float half = sun_half_angle();
    if (half > 0.f) {
        const float angle = std::acos(clamp(dot(d, m_sun), -1.f, 1.f));
        if (angle < half && d.z >= 0.f) {
            const float r = angle / half;
            const float limb = 1.f - 0.6f * (1.f - std::sqrt(std::fmax(1.f - r * r, 0.f)));
            const float y = clamp((elevation - m_params.sun_elevation) / m_params.sun_size + 0.5f, 0.f, 1.f);
            return (m_sun_bottom * (1.f - y) + m_sun_top * y) * (limb * m_params.sun_intensity);
        }
    }
    // The sky, by azimuth from the sun (it is symmetric about the sun's vertical plane) and elevation.
    float azimuth = std::atan2(d.x, d.y) - m_params.sun_rotation;
    azimuth = std::fabs(azimuth - 2.f * k_pi * std::floor(azimuth / (2.f * k_pi) + 0.5f));
    float fade = 1.f;
    float e = elevation;
    if (d.z < 0.f) {
        if (d.z < -0.4f) return Vec3(0.f);
        const float f = 1.f + 2.5f * d.z;
        fade = f * f * f;
        e = 0.f;
    }
    const float u = clamp(azimuth / k_pi, 0.f, 1.f) * float(k_azimuths - 1);
    const float v = std::sqrt(clamp(e / (0.5f * k_pi), 0.f, 1.f)) * float(k_elevations - 1);
    const int i = std::min(int(u), k_azimuths - 2), j = std::min(int(v), k_elevations - 2);
    const float fu = u - float(i), fv = v - float(j);
    auto at = [&](int jj, int ii) { return m_table[size_t(jj) * k_azimuths + ii]; };
    const Vec3 c = (at(j, i) * (1.f - fu) + at(j, i + 1) * fu) * (1.f - fv) +
                   (at(j + 1, i) * (1.f - fu) + at(j + 1, i + 1) * fu) * fv;
    return c * fade;
}

}  // namespace candela
