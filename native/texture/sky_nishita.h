// The Sky Texture's Nishita model (Nishita et al. 1993, "Display of the Earth taking into account atmospheric
// scattering"; docs/textures.md, "Sky Texture"): single scattering of sunlight by air (Rayleigh) and aerosols
// (Mie, Cornette–Shanks phase with g = 0.76) in a spherical atmosphere 60 km thick over a 6360 km Earth, with
// ozone absorption, integrated over 21 wavelengths from 380 to 780 nm and converted to Rec.709 through the CIE 1931
// observer. The sky is tabulated once per node over (azimuth from the sun, √(elevation/90°)); below the horizon it
// is the horizon's colour faded by (1 + 2.5·z)³ to black at z = −0.4, as Cycles does. The sun disc (angular
// diameter `size`) is the sunlight transmitted along its direction over the disc's solid angle, with limb
// darkening 1 − 0.6·(1 − √(1 − r²)), times `intensity`.
//
// The spectral data are published physical tables rounded (sky_nishita.cpp), not Cycles' own: the result is a
// Nishita sky, not Cycles' to the percent (the parity scene measures the difference).
#pragma once

#include <vector>

#include "core/vec.h"

namespace candela {

struct NishitaParams {
    float sun_elevation = 0.2618f, sun_rotation = 0.f;  // radians
    float altitude = 0.f;                               // metres
    float air = 1.f, dust = 1.f, ozone = 1.f;           // density multipliers
    bool sun_disc = true;
    float sun_size = 0.009512f, sun_intensity = 1.f;  // angular diameter (radians)
};

class NishitaSky {
public:
    explicit NishitaSky(const NishitaParams& p);
    /// Radiance toward direction d (need not be unit).
    Vec3 radiance(const Vec3& d) const;
    /// The unit direction toward the sun and the disc's angular radius (0 without a disc).
    Vec3 sun_direction() const { return m_sun; }
    float sun_half_angle() const { return m_params.sun_disc ? 0.5f * m_params.sun_size : 0.f; }

    static constexpr int k_azimuths = 128, k_elevations = 64;

private:
    Vec3 sky(float azimuth_from_sun, float elevation) const;
    NishitaParams m_params;
    Vec3 m_sun;
    std::vector<Vec3> m_table;               // k_elevations rows of k_azimuths, Rec.709
    Vec3 m_sun_bottom{0.f}, m_sun_top{0.f};  // disc radiance at its lower and upper edge
};

}  // namespace candela
