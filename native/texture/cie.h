// Colour-matching data shared by the spectral nodes (the Nishita sky, Blackbody).
#pragma once

#include "core/vec.h"

namespace candela {

/// Wavelengths of the tables: 380, 400, …, 780 nm.
inline constexpr int k_cie_samples = 21;
inline constexpr float k_cie_first_nm = 380.f, k_cie_step_nm = 20.f;

// CIE 1931 2° standard observer, x̄ ȳ z̄ at 380…780 nm in 20 nm steps (CIE 015:2004, table T.4).
inline constexpr float k_cie_cmf[k_cie_samples][3] = {
    {0.001368f, 0.000039f, 0.006450f}, {0.014310f, 0.000396f, 0.067850f}, {0.134380f, 0.004000f, 0.645600f},
    {0.348280f, 0.023000f, 1.747060f}, {0.290800f, 0.060000f, 1.669200f}, {0.095640f, 0.139020f, 0.812950f},
    {0.004900f, 0.323000f, 0.272000f}, {0.063270f, 0.710000f, 0.078250f}, {0.290400f, 0.954000f, 0.020300f},
    {0.594500f, 0.995000f, 0.003900f}, {0.916300f, 0.870000f, 0.001650f}, {1.062200f, 0.631000f, 0.000800f},
    {0.854450f, 0.381000f, 0.000190f}, {0.447900f, 0.175000f, 0.000020f}, {0.164900f, 0.061000f, 0.f},
    {0.046770f, 0.017000f, 0.f}, {0.011359f, 0.004102f, 0.f}, {0.002899f, 0.001047f, 0.f},
    {0.000690f, 0.000249f, 0.f}, {0.000166f, 0.000060f, 0.f}, {0.000042f, 0.000015f, 0.f}};

/// The Blackbody node: the colour of a black body at `kelvin` (Planck's law integrated against the CIE 1931
/// observer, in linear Rec.709), normalised to luminance 1 as Cycles' node is; negative channels (outside the
/// Rec.709 gamut) are clamped to 0.
Vec3 blackbody_rec709(float kelvin);

}  // namespace candela
