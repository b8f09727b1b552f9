"""Plain-numpy twins of mbd_core.kernels (laws and ball–groove geometry), written independently
from the formulas in the kernels' docstrings."""

import numpy as np


def step(x, x0, h0, x1, h1):
    d = np.clip((np.asarray(x, float) - x0) / (x1 - x0), 0.0, 1.0)
    return h0 + (h1 - h0) * d**2 * (3 - 2 * d)


def normal_force(law, delta, delta_dot, k, n, c, d_max):
    delta = np.asarray(delta, float)
    pos = np.maximum(delta, 0.0)
    elastic = k * pos**n
    if law == 0:
        f = elastic + step(delta, 0.0, 0.0, d_max, c) * delta_dot
    else:
        f = elastic * (1 + c * np.asarray(delta_dot, float))
    return np.where(delta > 0, np.maximum(f, 0.0), 0.0)


def friction_coefficient(law, u, p):
    u = np.asarray(u, float)
    if law == 0:
        mu_s, mu_d, v_s, v_d = p
        return np.where(u < v_s, step(u, 0, 0, v_s, mu_s), np.where(u < v_d, step(u, v_s, mu_s, v_d, mu_d), mu_d))
    if law == 1:
        return p[0] * u
    if law == 2:
        return step(u, 0, 0, p[1], p[0])
    if law == 3:
        falling = np.maximum(p[0] - p[1] * u, 0.0)
        return np.where(u < p[2], step(u, 0, 0, p[2], max(p[0] - p[1] * p[2], 0.0)), falling) if p[2] > 0 else falling
    if law == 5:
        return p[0] * (1.0 - np.exp(-u / p[1]))
    return np.maximum((p[0] + p[1] * u) * np.exp(-p[2] * u) + p[3], 0.0)


def friction_force(law, p, fn, v):
    v = np.asarray(v, float)
    u = np.linalg.norm(v)
    if u == 0 or fn <= 0:
        return np.zeros(3)
    return -friction_coefficient(law, u, p) * fn * v / u


def ball_groove(x, r_c, z_c, clearance_radius, h_table, dr_table):
    x = np.atleast_2d(x)
    th = np.mod(np.arctan2(x[:, 1], x[:, 0]), 2 * np.pi)
    th = np.where(th >= 2 * np.pi, th - 2 * np.pi, th)

    def lookup(t):
        t = np.asarray(t)
        if len(t) == 1:
            return np.full_like(th, t[0])
        grid = np.arange(len(t) + 1) * 2 * np.pi / len(t)
        return np.interp(th, grid, np.append(t, t[0]))

    r = r_c + lookup(dr_table)
    rho = np.hypot(x[:, 0], x[:, 1])  # cos θ = x/ρ, sin θ = y/ρ
    safe = np.where(rho > 0, rho, 1.0)
    cs, sn = np.where(rho > 0, x[:, 0] / safe, 1.0), np.where(rho > 0, x[:, 1] / safe, 0.0)
    c = np.column_stack((r * cs, r * sn, z_c + lookup(h_table)))
    d = x - c
    dist = np.linalg.norm(d, axis=1)
    n = np.divide(d, dist[:, None], out=np.zeros_like(d), where=dist[:, None] > 0)
    return th, dist - clearance_radius, n
