"""A modal body spinning at constant speed Ω about its z axis, written in its spinning frame.

For a body whose frame turns at ω = Ω ẑ about a fixed point (a rotor on its bearings) the modal
equations of the floating frame (:mod:`cms_reduction.invariants`, h_η with v = 0, ω̇ = 0) are

    I6 η̈ + (Ω G + C) η̇ + (K + Ω² (S − P) + Ω c_s A) η = Ω² c₀ + Q

with, for mass-normalised shapes φ_k (J. Géradin & D. Rixen, *Mechanical Vibrations*, 3rd ed.,
Wiley 2015, §6.2 for the rotating-frame equations of a spinning elastic body; G. Genta, *Dynamics
of Rotating Systems*, Springer 2005, ch. 4 for the same with stationary damping):

=====  =====================================  ==============================================
G      G_kl = 2 ẑ·∫ρ φ_l × φ_k dV = 2 I5[z,l,k]   Coriolis (gyroscopic) matrix, skew
P      P_kl = ∫ρ (φ_k × ẑ)·(φ_l × ẑ) dV = I9[z,z,k,l]  centrifugal (spin) softening, symmetric
A      A_kl = ẑ·∫ρ φ_l × φ_k dV = I5[z,l,k]       stationary damping seen from the spinning frame
S      S = Φᵀ K_σ Φ                               stress stiffening of the centrifugal prestress
c₀     c₀_k = ∫ρ φ_k·(x̄_x, x̄_y, 0) dV            centrifugal load (a static deflection)
=====  =====================================  ==============================================

K_σ is the geometric stiffness of the prestress at 1 rad/s (:mod:`fem_rings.prestress`). The
softening P alone is the linearisation of a rotation's centrifugal energy to first order in the
displacement; the stress stiffening carries the second-order part, and together they leave a rigid
rotation (and a rigid disc's tilt) unchanged, as they must (omitting S costs a thick disc's whirl
frequencies 1–2 % at 1 000 rad/s and more above).

K = diag(ω_k²) and C = diag(2 ζ_k ω_k) are the modal stiffness and the damping that turns with the
body (material damping). A stationary viscous damping proportional to mass, c_s in 1/s (air drag,
a damper distributed like the mass), acts on the velocity in the fixed frame, u̇ + Ω ẑ × u seen
from the spinning one: it adds c_s I6 to the damping and Ω c_s A to the stiffness.

A rotor on isotropic supports (the same all round) has constant coefficients in the spinning frame,
so its modes there are its whirl modes; :mod:`.campbell` converts their frequencies to the fixed frame.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cms_reduction.invariants import Invariants, compute_invariants
from fem_rings.model import FEModel
from fem_rings.spinning import centrifugal_geometric_stiffness, circumferential_derivative

__all__ = ["SpinningBody", "spinning_body", "spinning_body_of_model", "spinning_matrices"]

_Z = 2


@dataclass(frozen=True, eq=False)
class SpinningBody:
    """The modal matrices of a body spinning about its z axis (module docstring).

    Attributes
    ----------
    mass : (m, m) float64
        I6, modal mass (the identity for mass-normalised shapes).
    stiffness_rad2_s2 : (m, m) float64
        K = diag(ω_k²), N/m per unit modal mass, plus the bearing springs (:func:`.seats.on_bearings`).
    damping_rad_s : (m, m) float64
        C = diag(2 ζ_k ω_k): damping that turns with the body.
    coriolis : (m, m) float64
        G, skew; the Coriolis term is Ω G η̇.
    softening : (m, m) float64
        P, symmetric positive semi-definite; the spin softening is −Ω² P η.
    stiffening : (m, m) float64
        S = Φᵀ K_σ Φ, the stress stiffening at 1 rad/s (zero when not given).
    cross : (m, m) float64
        A = G/2, skew: ẑ·∫ρ u × u̇ dV = η̇ᵀ A η is the vibration's angular momentum about z.
    rotation : (m, m) float64
        Q = A − Φᵀ D Φ, the mass-weighted rotation generator 𝓛 on the modes (skew), which gives
        a mode's nodal diameters (:mod:`fem_rings.spinning`, :func:`.campbell.angular_order`).
    support_damping, support_cross : (m, m) float64
        Stationary damping of the supports (:func:`.seats.on_bearings`): c in the damping and
        Ω times ``support_cross`` in the stiffness; zero by default.
    """

    mass: np.ndarray
    stiffness_rad2_s2: np.ndarray
    damping_rad_s: np.ndarray
    coriolis: np.ndarray
    softening: np.ndarray
    cross: np.ndarray
    stiffening: np.ndarray
    rotation: np.ndarray
    support_damping: np.ndarray | None = None
    support_cross: np.ndarray | None = None

    def __post_init__(self) -> None:
        for name in ("support_damping", "support_cross"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros_like(self.mass))

    @property
    def n_modes(self) -> int:
        return self.mass.shape[0]


def spinning_body(inv: Invariants, frequencies_Hz, stress_stiffening, circumferential,
                  damping_ratio=0.0) -> SpinningBody:
    """The spinning-frame matrices of a modal body.

    Parameters
    ----------
    inv : Invariants
        Of the mode shapes Φ (:func:`cms_reduction.invariants.compute_invariants`).
    frequencies_Hz : (m,)
    stress_stiffening : (m, m)
        Φᵀ K_σ Φ at 1 rad/s (:func:`fem_rings.spinning.centrifugal_geometric_stiffness`).
    circumferential : (m, m)
        Φᵀ D Φ (:func:`fem_rings.spinning.circumferential_derivative`).
    damping_ratio : float or (m,)
        Damping that turns with the body.
    """
    w = 2.0 * np.pi * np.asarray(frequencies_Hz, dtype=float)
    if w.shape != (inv.n_modes,):
        raise ValueError(f"frequencies_Hz: expected {inv.n_modes} values (one per mode), got shape {w.shape}")
    zeta = np.broadcast_to(np.asarray(damping_ratio, dtype=float), w.shape)
    A = np.array(inv.I5[_Z].T)
    S, Dm = (np.asarray(x, dtype=float) for x in (stress_stiffening, circumferential))
    for name, x in (("stress_stiffening", S), ("circumferential", Dm)):
        if x.shape != A.shape:
            raise ValueError(f"{name}: expected shape {A.shape}, got {x.shape}")
    Q = A - Dm
    return SpinningBody(mass=np.array(inv.I6), stiffness_rad2_s2=np.diag(w * w), damping_rad_s=np.diag(2.0 * zeta * w),
                        coriolis=2.0 * A, softening=np.array(inv.I9[_Z, _Z]), cross=A, stiffening=0.5 * (S + S.T),
                        rotation=0.5 * (Q - Q.T))


def spinning_body_of_model(model: FEModel, shapes, frequencies_Hz, held, density_kg_m3=None,
                           damping_ratio=0.0) -> SpinningBody:
    """:func:`spinning_body` of mode shapes of an FE model held at DOFs ``held`` (the supports,
    which the centrifugal prestress is computed with); ``density_kg_m3`` per element when the
    model's mass was assembled with several."""
    phi = np.asarray(shapes, dtype=float)
    inv = compute_invariants(model.M, model.nodes_m, phi)
    K_sigma, _ = centrifugal_geometric_stiffness(model, held)
    D = circumferential_derivative(model, density_kg_m3)
    return spinning_body(inv, frequencies_Hz, phi.T @ (K_sigma @ phi), phi.T @ (D @ phi), damping_ratio)


def spinning_matrices(body: SpinningBody, speed_rad_s: float,
                      stationary_damping_per_s: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M, C, K) of the spinning-frame equations at speed Ω (module docstring), modal units."""
    W, cs = float(speed_rad_s), float(stationary_damping_per_s)
    if cs < 0.0:
        raise ValueError(f"stationary_damping_per_s must be ≥ 0, got {cs}")
    C = body.damping_rad_s + W * body.coriolis + cs * body.mass + body.support_damping
    K = (body.stiffness_rad2_s2 + W * W * (body.stiffening - body.softening) + W * cs * body.cross
         + W * body.support_cross)
    return body.mass, C, K
