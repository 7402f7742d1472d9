"""The analytic sub-case of the door gap (bench/door_gap.py, docs/door_gap.md): sky light through a slit onto a floor.

A closed room, x, y ∈ [−R, R], z ∈ [0, H], black (reflectance 0) but for its floor (reflectance ρ). Its ceiling is
two slabs of thickness T (T = 0: two quads) leaving a slit x ∈ [−W/2, W/2] that runs wall to wall; above is a
uniform sky of radiance 1. A floor point (x, y) sees the sky in the directions that cross both ends of the slit, the
rectangle [−W/2, W/2] × [−R, R] at heights H and H + T (the channel between them is convex, so crossing both ends
means crossing it untouched). Written as slopes (sx, sy) = (dx/dz, dy/dz), each end's condition bounds sx and sy
separately, so the sky is seen in a rectangle of slope space, which is the solid angle of a rectangle parallel to
the floor at height 1. Its irradiance is π·F with F the view factor of a parallel rectangle, a sum of four signed
corner terms (Howell's catalogue of configuration factors, C-11):
    F([0, a] × [0, b]) = 1/(2π) · (a/√(1+a²)·atan(b/√(1+a²)) + b/√(1+b²)·atan(a/√(1+b²))).
Light leaving the floor meets black surfaces or leaves through the slit, so the floor's radiance is ρ·F exactly
(a single bounce), and a box-filtered pixel is its average over the pixel's footprint.
"""

import numpy as np

# The slit scene's dimensions (bench/door_gap_render.py builds it from these).
ROOM_HALF = 1.5        # R
HEIGHT = 1.0           # H, the slit's lower end
SLIT_WIDTH = 0.1       # W
SLAB = 0.05            # T of the slab variants
FLOOR_RHO = 0.8
WINDOW_HALF = 1.0      # the orthographic camera sees x, y ∈ [−1, 1]


def corner(a, b):
    """Signed view factor of the rectangle [0, a] × [0, b] at height 1 from the origin (odd in a and in b)."""
    ra, rb = np.sqrt(1.0 + a * a), np.sqrt(1.0 + b * b)
    return (a / ra * np.arctan(b / ra) + b / rb * np.arctan(a / rb)) / (2.0 * np.pi)


def view_factor(x, y, width=SLIT_WIDTH, height=HEIGHT, slab=SLAB, half=ROOM_HALF):
    """F of the sky through the slit from floor point(s) (x, y)."""
    h0, h1 = height, height + slab
    sx0 = np.maximum((-width / 2 - x) / h0, (-width / 2 - x) / h1)
    sx1 = np.minimum((width / 2 - x) / h0, (width / 2 - x) / h1)
    sy0 = np.maximum((-half - y) / h0, (-half - y) / h1)
    sy1 = np.minimum((half - y) / h0, (half - y) / h1)
    f = corner(sx1, sy1) - corner(sx0, sy1) - corner(sx1, sy0) + corner(sx0, sy0)
    return np.where((sx1 > sx0) & (sy1 > sy0), f, 0.0)


def image(nx, ny, slab=SLAB, width=SLIT_WIDTH, sub=16):
    """The expected box-filtered image (ny × nx, row 0 at +y) over the window, `sub`² midpoints per pixel (a smooth
    integrand between the kinks at the slit's shadow edges: the midpoint rule's error is below 10⁻⁵ relative)."""
    u = (np.arange(nx * sub) + 0.5) / (nx * sub)
    v = (np.arange(ny * sub) + 0.5) / (ny * sub)
    x = -WINDOW_HALF + 2 * WINDOW_HALF * u
    y = WINDOW_HALF - 2 * WINDOW_HALF * v
    f = FLOOR_RHO * view_factor(x[None, :], y[:, None], width=width, slab=slab)
    return f.reshape(ny, sub, nx, sub).mean(axis=(1, 3))


def mean(slab=SLAB, width=SLIT_WIDTH, n=4096):
    """The image mean (a function of the window only, not of the pixel grid)."""
    return float(image(n // 16, n // 16, slab=slab, width=width, sub=16).mean())


def offset_effect(distance, slab=0.0, n=1024):
    """The relative change of the image mean when the camera is `distance` further up (bench/door_gap_render.py's
    `_far<D>`): Candela's rays leave the floor from an origin lifted by 256 ulps of the floor's camera-world height
    (scene/ray_offset.h), as if the slit were that much lower."""
    lift = 256.0 * float(np.spacing(np.float32(distance + HEIGHT - 0.1)))
    u = (np.arange(n) + 0.5) / n
    x = -WINDOW_HALF + 2 * WINDOW_HALF * u

    def m(h):
        return float(view_factor(x[None, :], x[:, None], height=h, slab=slab).mean())
    return m(HEIGHT - lift) / m(HEIGHT) - 1.0


if __name__ == "__main__":
    for t in (0.0, SLAB):
        print(f"slab {t}: image mean {mean(slab=t):.7f} (coarser grid {mean(slab=t, n=2048):.7f})")
