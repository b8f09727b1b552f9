"""Plots of bearing-level results of :mod:`mbd_core.bearing` (mbd_core has no matplotlib)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mbd_core.bearing.limiting_load import LimitingLoadCurve

from .results import plt

__all__ = ["limiting_load_curve_xy", "plot_limiting_load_curve"]


def limiting_load_curve_xy(curve: LimitingLoadCurve) -> tuple[np.ndarray, np.ndarray]:
    """(M in kN·m, F_a in kN) of the carried points in ray order, closed where the curve goes all round."""
    M, F = curve.moment_Nm[curve.carried] / 1e3, curve.axial_N[curve.carried] / 1e3
    if curve.carried.all() and M.size:
        M, F = np.append(M, M[0]), np.append(F, F[0])
    return M, F


def plot_limiting_load_curve(curve: LimitingLoadCurve, path, bearing_name: str = "",
                             operating_points=(), reference: LimitingLoadCurve | None = None,
                             labels: tuple[str, str] = ("limiting load", "")) -> Path:
    """PNG of the limiting load curve: axial force F_a (kN) against tilting moment M (kN·m), the
    criterion in the title; rays with no point (not carried) are left out and counted in the title.
    ``operating_points``: (M N·m, F_a N) pairs marked on the plot (the load cases); ``reference``:
    a second curve drawn dashed (e.g. rigid rings), ``labels`` the two curves' legend entries."""
    pyplot = plt()
    M, F = limiting_load_curve_xy(curve)
    fig, ax = pyplot.subplots(figsize=(7.0, 5.5), constrained_layout=True)
    ax.plot(M, F, "o-", color="C0", ms=3, lw=1.5, label=labels[0])
    if reference is not None:
        Mr, Fr = limiting_load_curve_xy(reference)
        ax.plot(Mr, Fr, "--", color="C7", lw=1.2, label=labels[1])
    if len(operating_points) or reference is not None:
        ax.legend(loc="best")
    if len(operating_points):
        pts = np.asarray(operating_points, dtype=float) / 1e3
        ax.plot(pts[:, 0], pts[:, 1], "x", color="C3", ms=8, mew=2,
                label="load case" if len(pts) == 1 else "load cases")
        ax.legend(loc="best")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.axvline(0.0, color="k", lw=0.6)
    ax.set_xlabel("tilting moment M (kN·m)")
    ax.set_ylabel("axial force F_a (kN)")
    missing = int((~curve.carried).sum())
    extra = f", radial force {curve.radial_N / 1e3:.4g} kN" if curve.radial_N else ""
    note = f"; {missing} rays not carried" if missing else ""
    ax.set_title(f"Static limiting load curve {bearing_name}".rstrip() + f"\n{curve.criterion}{extra}{note}")
    ax.grid(True, alpha=0.3)
    out = Path(path)
    fig.savefig(out, dpi=120)
    pyplot.close(fig)
    return out
