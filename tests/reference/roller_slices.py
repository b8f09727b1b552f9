"""numpy twin of mbd_core.kernels.roller_slices (vectorised over slices)."""

import numpy as np


def roller_slices(center, axis, length, radius, drop, raceway, value):
    n_s = len(drop)
    s = -length / 2 + (np.arange(n_s) + 0.5) * length / n_s
    p = center[None, :] + s[:, None] * axis[None, :]
    if raceway in (0, 1):
        er = np.column_stack((p[:, 0], p[:, 1], np.zeros(n_s))) / np.hypot(p[:, 0], p[:, 1])[:, None]
        d = -er if raceway == 0 else er
    else:
        d = np.tile([0.0, 0.0, -1.0 if raceway == 2 else 1.0], (n_s, 1))
    d = d - (d @ axis)[:, None] * axis[None, :]
    q = p + (radius - np.asarray(drop))[:, None] * d / np.linalg.norm(d, axis=1)[:, None]
    if raceway in (0, 1):
        rq = np.hypot(q[:, 0], q[:, 1])
        e = np.column_stack((q[:, 0] / rq, q[:, 1] / rq, np.zeros(n_s)))
        return (value - rq, q, e) if raceway == 0 else (rq - value, q, -e)
    if raceway == 2:
        return value - q[:, 2], q, np.tile([0.0, 0.0, 1.0], (n_s, 1))
    return q[:, 2] - value, q, np.tile([0.0, 0.0, -1.0], (n_s, 1))
