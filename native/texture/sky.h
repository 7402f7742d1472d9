// The Sky Texture's analytic sky models (docs/textures.md, "Sky Texture"), evaluated from a state the add-on
// precomputes per node (addon/candela/export/sky.py).
//
// PREETHAM (Preetham, Shirley, Smits 1999, "A Practical Analytic Model for Daylight"): luminance Y and chromaticity
// x, y of the sky in direction (θ, φ) are each the zenith value times the Perez distribution
//     F(θ, γ) = (1 + A·e^{B/cos θ})·(1 + C·e^{D·γ} + E·cos² γ)
// normalised by its value at the zenith, γ the angle to the sun; A…E and the zenith values are the paper's linear
// and polynomial fits in the turbidity. Below the horizon θ is held at π/2 − 0.001. xyY → XYZ → linear Rec.709.
// State: [θ_sun, φ_sun, Y_z', x_z', y_z', A…E for Y, x, y] (20 floats; the zenith values already divided by
// F(0, θ_sun)).
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace candela {

enum class SkyModel : uint32_t { Preetham, Nishita };

/// Floats of precomputed state per model.
size_t sky_state_size(SkyModel model);

/// Radiance of the Preetham sky toward direction d (from the scene to the sky; need not be unit). NISHITA's state
/// is its node's parameters (NishitaParams order: sun elevation, rotation, altitude, air, dust, ozone, disc, size,
/// intensity), tabulated at load (texture/sky_nishita.h).
Vec3 sky_radiance(SkyModel model, const float* state, const Vec3& d);

/// CIE XYZ → linear Rec.709 (D65), the matrix Blender's colour management uses for XYZ.
Vec3 xyz_to_rec709(const Vec3& xyz);

}  // namespace candela
