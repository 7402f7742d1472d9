"""The Sky Texture's precomputed model states (native/texture/sky.h describes their layout and the models)."""

import math


def _perez(k, theta, gamma):
    return (1.0 + k[0] * math.exp(k[1] / math.cos(theta))) * (1.0 + k[2] * math.exp(k[3] * gamma)
                                                              + k[4] * math.cos(gamma) ** 2)


def sun_angles(direction):
    """(θ, φ) of the node's sun direction: θ from +Z, φ = atan2(x, y), as the Sky Texture measures them."""
    x, y, z = direction
    n = math.sqrt(x * x + y * y + z * z) or 1.0
    return math.acos(max(-1.0, min(1.0, z / n))), math.atan2(x / n, y / n)


def preetham_state(direction, turbidity):
    """Preetham, Shirley and Smits (1999), appendix: the zenith luminance (scaled by 0.06, Cycles' unit) and
    chromaticity fits and the Perez coefficients of Y, x and y as functions of the turbidity T; the zenith values
    are divided by F(0, θ_sun) so that F(θ, γ)·value is the sky in direction (θ, γ)."""
    theta, phi = sun_angles(direction)
    t = turbidity
    chi = (4.0 / 9.0 - t / 120.0) * (math.pi - 2.0 * theta)
    zenith_y = ((4.0453 * t - 4.9710) * math.tan(chi) - 0.2155 * t + 2.4192) * 0.06
    th, th2, th3 = theta, theta * theta, theta ** 3
    zenith_x = (t * t * (0.00166 * th3 - 0.00375 * th2 + 0.00209 * th)
                + t * (-0.02903 * th3 + 0.06377 * th2 - 0.03202 * th + 0.00394)
                + (0.11693 * th3 - 0.21196 * th2 + 0.06052 * th + 0.25886))
    zenith_yc = (t * t * (0.00275 * th3 - 0.00610 * th2 + 0.00317 * th)
                 + t * (-0.04214 * th3 + 0.08970 * th2 - 0.04153 * th + 0.00516)
                 + (0.15346 * th3 - 0.26756 * th2 + 0.06670 * th + 0.26688))
    k_y = [0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771, -0.0670 * t + 0.3703]
    k_x = [-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989, -0.0033 * t + 0.0452]
    k_yc = [-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537,
            -0.0109 * t + 0.0529]
    return [theta, phi,
            zenith_y / _perez(k_y, 0.0, theta), zenith_x / _perez(k_x, 0.0, theta), zenith_yc / _perez(k_yc, 0.0, theta),
            *k_y, *k_x, *k_yc]
