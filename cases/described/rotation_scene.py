"""The scene of a described bearing's ``rotation`` study (:mod:`.rotation`): its rings, rows and
separators as a multibody model, and the state it starts from.

Ball rows (every type; a four-point row's arches are two grooves per ring) carry a cage, spacer
balls or a full complement (``[rows.separator]``). Rings are rigid, or modal where the file gives
``[rings.X]`` tables.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mbd_core.contact import ball_on_groove
from mbd_core.contact.hertz import sphere_on_sphere
from mbd_core.multibody import Driven, Fixed, ModelBuilder
from mbd_core.multibody.bearings import (_rotate_back, add_ball_row, ball_mass_kg, orbit_rad_s,
                                         set_rolling_velocities)
from mbd_core.multibody.builder import ContactLaw
from mbd_core.multibody.statics import static_equilibrium
from mbd_core.quasistatic import BallRow, RollerRow

from ..config import CaseError

__all__ = ["RotationScene", "check_rotation", "modal_rings", "build_scene", "start_state",
           "modal_mass_kg", "CAGE_GUIDE_STIFFNESS_N_PER_M", "POCKET_STIFFNESS_N_PER_M"]

#: radial stiffness of a cage's land guidance on the fixed ring, N/m; its damping ratio
CAGE_GUIDE_STIFFNESS_N_PER_M = 1e7
CAGE_GUIDE_DAMPING_RATIO = 0.3
#: stiffness of a ball in its cage pocket (linear), N/m
POCKET_STIFFNESS_N_PER_M = 1e8
#: penetration over which the contact damping ramps in, m (well below a Hertz approach)
D_MAX_M = 1e-6


@dataclasses.dataclass
class RotationScene:
    """The model, its start state and what a run reads back, per row: the ``RowBodies`` and the
    spacers; ``modal``: the modal rings by side (:func:`modal_rings`)."""

    model: object
    state: object
    moving: int
    fixed: int
    rows: tuple
    row_bodies: tuple
    spacers: tuple
    spacer_pairs: tuple
    neighbour_pairs: tuple
    modal: dict = dataclasses.field(default_factory=dict)


def check_rotation(desc, rings: str, rotation) -> None:
    """Refuse, naming the key, what the rotation study does not model (before anything is built)."""
    modal_moving = rings == "file" and any(m.side == "moving" for m in desc.rings.values())
    if rotation.moving_ring_mass_kg is None and not modal_moving:
        raise CaseError("rotation.moving_ring_mass_kg: missing key (the mass of the moving ring and of what turns "
                        "with it, kg; the rotation study needs it)")
    if rotation.moving_ring_mass_kg is not None and modal_moving:
        raise CaseError("rotation.moving_ring_mass_kg: the moving ring is modal ([rings.X] of the file): its mass is "
                        "its finite-element model's; leave the key out (or set bearing.rings = \"rigid\")")
    if len(desc.load_cases) != 1:
        raise CaseError(f"bearing.file: the rotation study applies one constant load; the file gives "
                        f"{len(desc.load_cases)} load cases (a spectrum or a time history)")
    for row in desc.bearing.rows:
        where = f"the row {row.name!r}"
        if row.name not in desc.separators:
            raise CaseError(f"bearing.file: {where} has no [rows.separator] table: the rotation study needs "
                            "kind = 'cage', 'spacer_balls' or 'full_complement'")
        if isinstance(row, RollerRow):
            raise CaseError(f"bearing.file: {where}: the rotation study runs ball rows; roller rows are modelled "
                            "quasi-statically only (a turning roller row needs its ribs and the axial location of "
                            "its rings, which the description file does not give)")


def modal_rings(desc, rings: str) -> dict:
    """side ("moving", "fixed") → (RingModel, ReducedBody) of the rings the file makes modal
    (reduced here or loaded from the cache); none with ``rings = "rigid"``."""
    if rings == "rigid" or not desc.rings:
        return {}
    from foundation.progress import phase

    from ..bearing_ring_reduction import reduce_ring

    with phase(f"modal rings of {desc.name}"):
        return {m.side: (m, reduce_ring(m, desc.bearing)) for m in desc.rings.values()}


def modal_mass_kg(body) -> float:
    from cms_reduction.invariants import Invariants

    return float(Invariants.from_arrays(body.extras).mass_kg)


def _guide_cage(b, fixed, cage: int, row, mass_kg: float) -> None:
    """A ball cage's land guidance on the fixed ring: a radial spring pair at its centre
    (``CAGE_GUIDE_STIFFNESS_N_PER_M``, ``CAGE_GUIDE_DAMPING_RATIO`` of critical); its pockets hold it
    along the axis and in tilt; it turns freely."""
    k = CAGE_GUIDE_STIFFNESS_N_PER_M
    c = CAGE_GUIDE_DAMPING_RATIO * 2.0 * math.sqrt(k * mass_kg)
    b.add_bushing(fixed, cage, (0.0, 0.0, row.axial_position_m), (k, k, 0, 0, 0, 0), (c, c, 0, 0, 0, 0))


def _contact_constants(row: BallRow) -> tuple[float, float]:
    """Hertz constants K (N/m^1.5) of a ball on the moving and on the fixed groove."""
    fixed = "outer" if row.moving_raceway == "inner" else "inner"
    k_m = ball_on_groove(row.ball_diameter_m, row.conformity_moving, row.pitch_diameter_m, row.contact_angle_rad,
                         row.moving_raceway, row.ball_material, row.race_material).stiffness_N_per_m1p5
    k_f = ball_on_groove(row.ball_diameter_m, row.conformity_fixed, row.pitch_diameter_m, row.contact_angle_rad,
                         fixed, row.ball_material, row.race_material).stiffness_N_per_m1p5
    return k_m, k_f


def _damping_N_s_m(row: BallRow, largest_load_N: float, ratio: float) -> float:
    """``ratio`` × 2√(k m): k = 1.5 K δ^½ the linearised stiffness of the stiffer contact at the
    row's largest quasi-static load (at least 1 % of the ball's weight-free scale: 1 N)."""
    K = max(_contact_constants(row))
    delta = (max(largest_load_N, 1.0) / K) ** (2.0 / 3.0)
    m = ball_mass_kg(row.ball_diameter_m, row.ball_material.density_kg_m3)
    return ratio * 2.0 * math.sqrt(1.5 * K * math.sqrt(delta) * m)


def _add_spacers(b, row: BallRow, rb, moving, fixed, diameter_m: float, damping: float, friction):
    """A spacer ball half-way between each pair of neighbouring balls, on the balls' pitch circle,
    with contacts to both grooves and to its two neighbours."""
    D, d = row.ball_diameter_m, diameter_m
    fixed_raceway = "outer" if row.moving_raceway == "inner" else "inner"
    laws = []
    for conformity, raceway in ((row.conformity_moving, row.moving_raceway), (row.conformity_fixed, fixed_raceway)):
        k = ball_on_groove(d, conformity * D / d, row.pitch_diameter_m, row.contact_angle_rad, raceway,
                           row.ball_material, row.race_material).stiffness_N_per_m1p5
        laws.append(ContactLaw(k, 1.5, damping, D_MAX_M, friction=friction))
    law_ball = ContactLaw(sphere_on_sphere(D, d).stiffness_N_per_m1p5, 1.5, damping, D_MAX_M, friction=friction)
    m = ball_mass_kg(d, row.ball_material.density_kg_m3)
    R, n = row.pitch_diameter_m / 2, row.n_balls
    spacers, pairs = [], []
    for j in range(n):
        psi = row.first_azimuth_rad + 2.0 * math.pi * (j + 0.5) / n
        s = b.add_body(f"{row.name} spacer {j}", m, (0.1 * m * d * d,) * 3,
                       position_m=(R * math.cos(psi), R * math.sin(psi), row.axial_position_m))
        for k, diagonal in enumerate(rb.grooves):  # both arches of a four-point groove
            for ring, side, groove, law in zip((moving, fixed), ("moving", "fixed"), diagonal, laws):
                b.add_ball_groove(s, ring, groove, d / 2, law, name=f"{row.name} spacer {j}–{side} {k}")
        for k in (j, (j + 1) % n):
            pairs.append(b.add_ball_ball(rb.elements[k], s, D / 2, d / 2, law_ball,
                                         name=f"{row.name} ball {k}–spacer {j}"))
        spacers.append(s)
    return tuple(spacers), tuple(pairs)


def _add_neighbours(b, row: BallRow, rb, damping: float, friction) -> tuple:
    """Full complement: ball j touches ball j + 1."""
    D, n = row.ball_diameter_m, row.n_balls
    law = ContactLaw(sphere_on_sphere(D, D).stiffness_N_per_m1p5, 1.5, damping, D_MAX_M, friction=friction)
    return tuple(b.add_ball_ball(rb.elements[j], rb.elements[(j + 1) % n], D / 2, D / 2, law,
                                 name=f"{row.name} ball {j}–ball {(j + 1) % n}") for j in range(n))


def _ring(b, name: str, motion, omega: float, modal: tuple | None, mass_kg: float, radius_m: float):
    """A ring body: the modal one of ``modal`` (RingModel, ReducedBody), else rigid, a thin ring of
    ``mass_kg`` on ``radius_m``; returns (index, mass kg)."""
    if modal is not None:
        return b.add_modal_body(name, modal[1], motion=motion, omega_rad_s=(0.0, 0.0, omega)), modal_mass_kg(modal[1])
    m, R = mass_kg, radius_m
    return b.add_body(name, m, (0.5 * m * R * R, 0.5 * m * R * R, m * R * R), motion=motion,
                      omega_rad_s=(0.0, 0.0, omega)), m


def build_scene(desc, rotation, reference, modal: dict | None = None) -> RotationScene:
    """The multibody model of the described bearing at rest (``reference``: its quasi-static
    load distribution, for the damping scale; ``modal``: :func:`modal_rings`)."""
    rows = desc.bearing.rows
    modal = modal or {}
    omega = rotation.speed_rpm * 2.0 * math.pi / 60.0
    g = rotation.gravity_m_s2
    b = ModelBuilder(gravity_m_s2=(0.0, 0.0, -g), implicit_friction=rotation.implicit_friction)
    R = max(r.pitch_diameter_m for r in rows) / 2
    m_given = rotation.moving_ring_mass_kg
    moving, m = _ring(b, "moving ring", Driven(omega, translation_free=True, tilt_free=True), omega,
                      modal.get("moving"), m_given or 0.0, R)
    fixed, _ = _ring(b, "fixed ring", Fixed(), 0.0, modal.get("fixed"), m, R)
    samples = {side: ring[0].raceways for side, ring in modal.items()}
    friction = rotation.friction_law()
    added, spacers, spacer_pairs, neighbours = [], [], [], []
    for row, loads in zip(rows, reference.rows):
        sep = desc.separators[row.name]
        largest = float(np.max(loads.load_N))
        cage = {}
        if sep.kind == "cage":
            cage = dict(cage_mass_kg=sep.mass_kg, pocket_clearance_m=sep.pocket_clearance(row.ball_diameter_m),
                        cage_stiffness_N_per_m=POCKET_STIFFNESS_N_PER_M, pocket_friction=friction)
        c = _damping_N_s_m(row, largest, rotation.damping_ratio)
        rb = add_ball_row(b, row, moving, fixed, friction=friction, damping_N_s_m=c, d_max_m=D_MAX_M,
                          moving_sample=samples.get("moving", {}).get(row.name),
                          fixed_sample=samples.get("fixed", {}).get(row.name), **cage)
        if rb.cage is not None:
            _guide_cage(b, fixed, rb.cage, row, sep.mass_kg)
        if sep.kind == "spacer_balls":
            s, p = _add_spacers(b, row, rb, moving, fixed, sep.spacer_diameter_m, c, friction)
            spacers.append(s)
            spacer_pairs.append(p)
        else:
            spacers.append(())
            spacer_pairs.append(())
        neighbours.append(_add_neighbours(b, row, rb, c, friction) if sep.kind == "full_complement" else ())
        added.append(rb)
    load = desc.default_load
    # the file's load includes the moving ring's weight: gravity on its mass is taken off again
    b.add_force(moving, (load.Fx_N, load.Fy_N, load.Fz_N + m * g), (load.Mx_Nm, load.My_Nm, 0.0))
    model, state = b.finalize()
    return RotationScene(model, state, moving, fixed, tuple(rows), tuple(added), tuple(spacers), tuple(spacer_pairs),
                         tuple(neighbours), modal)


def start_state(sc: RotationScene):
    """The static equilibrium with the balls and spacers held at their azimuths, then rolling velocities."""
    held = [e for rb in sc.row_bodies for e in rb.elements] + [s for row in sc.spacers for s in row]
    spin = sc.state.v[sc.moving, 3:].copy()
    state = static_equilibrium(sc.model, sc.state, fixed_azimuth=held).state
    state.v[sc.moving, 3:] = spin
    for rb, spacers, row in zip(sc.row_bodies, sc.spacers, sc.rows):
        set_rolling_velocities(sc.model, state, rb.elements, sc.moving, sc.fixed)
        idx = list(rb.elements)
        w_c = float(np.mean(orbit_rad_s(state.q[idx, :3], state.v[idx, :3])))
        if rb.cage is not None:
            state.v[rb.cage, 3:] = _rotate_back(state.q[rb.cage, 3:], np.array([0.0, 0.0, w_c]))
        a = sc.model.arrays
        for s in spacers:
            x = state.q[s, :3]
            v = w_c * np.cross([0.0, 0.0, 1.0], x)
            c = int(np.flatnonzero((a.pair_a == s) & (a.pair_b == sc.fixed))[0])
            g = a.pair_geom[c]
            centre = np.array([a.groove_rc[g] * x[0], a.groove_rc[g] * x[1], 0.0]) / math.hypot(x[0], x[1])
            centre[2] = a.groove_zc[g]
            n = (x - centre) / np.linalg.norm(x - centre)  # towards the fixed groove's surface
            state.v[s, :3] = v
            state.v[s, 3:] = _rotate_back(state.q[s, 3:], np.cross(v, n) / a.pair_radius[c])  # rolls on it
    return state


