"""Piecewise-cubic load histories (cubic splines through tabulated load points).

A load l has knots t_0 < … < t_m (``knot_t[off[l]:off[l+1]]``) and on interval j the six
components (F_x, F_y, F_z, M_x, M_y, M_z) are

    f(t) = Σ_k c[k] (t − t_j)^(3−k),   k = 0…3,

with ``c = coef[off[l] + j]`` of shape (4, 6) — the layout of ``scipy.interpolate.PPoly`` (the
coefficients come from ``scipy.interpolate.CubicSpline``). Outside [t_0, t_m] the end values are
held, so a load spectrum stays at its last value after it ends.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, _nrt=False)
def spline_value(knot_t, coef, start, stop, t, out):
    """Write f(t) (6,) of the load whose knots are knot_t[start:stop] into ``out``."""
    last = stop - 1
    if t <= knot_t[start]:
        j, x = start, 0.0
    elif t >= knot_t[last]:
        j, x = last - 1, knot_t[last] - knot_t[last - 1]
    else:
        lo, hi = start, last
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if knot_t[mid] <= t:
                lo = mid
            else:
                hi = mid
        j, x = lo, t - knot_t[lo]
    for c in range(6):
        out[c] = ((coef[j, 0, c] * x + coef[j, 1, c]) * x + coef[j, 2, c]) * x + coef[j, 3, c]
