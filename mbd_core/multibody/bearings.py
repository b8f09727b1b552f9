"""Whole bearing rows as multibody elements, with Hertz-derived contact laws by default.

:func:`add_ball_row` and :func:`add_roller_row` take the row descriptions of the quasi-static
solver (:class:`~mbd_core.quasistatic.BallRow`, :class:`~mbd_core.quasistatic.RollerRow`), so a
dynamic model and a quasi-static load distribution describe the same bearing. Both rings must be
bodies at the origin with identity orientation (ring axis = z); elements are placed at the
unloaded geometric positions with the clearance split equally between the two raceways.

Ball rows: with u the unit vector from the ball centre to the moving ring's contact point at the
nominal angle α0, u = (∓cos α0 (inner/outer moving raceway), −s sin α0) in (radial, axial) with s
the row's axial sign, the moving groove's curvature centre lies at x − (f_m D − D/2) u and the
fixed one at x + (f_f D − D/2) u (Harris & Kotzalas, *Essential Concepts*, ch. 2). The clearance
is taken through the geometry, as in the quasi-static solver (ISO/TS 16281): a diametral
clearance P_d moves the two curvature centres apart radially by P_d/4 each (the rings concentric),
the groove radii stay f·D and the ball touches both grooves when the centres are A apart, so a
loaded contact angle differs from α0 with play.
Each contact gets its own Hertz constant (exact elliptic integrals, :func:`ball_on_groove`).

Roller rows: the moving raceway is the inner cylinder (radial row, load sign +1) or the plane below
the rollers (thrust row, load sign +1); each roller–raceway contact has c = c_L 2^(10/9)/n_s per
slice, c_L the ISO/TS 16281 constant of the roller between both raceways (two equal contacts in
series give c_L back).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact.hertz import ball_on_groove
from foundation.materials import effective_modulus_Pa
from ..kernels.ball_groove import groove_point
from ..quasistatic.row_common import ball_mass_kg
from ..quasistatic.rows import BallRow, RollerRow
from ..quasistatic.rows_four_point import FourPointRow
from .builder import ContactLaw, ModelBuilder, quat_z_to
from .parts import StripTraction
from .model import Model, State

__all__ = ["RowBodies", "add_ball_row", "add_roller_row", "set_rolling_velocities", "start_at_equilibrium", "place_balls", "ball_mass_kg", "roller_mass_kg",
           "orbit_rad_s", "row_speed_rad_s"]

LINE_EXPONENT = 10.0 / 9.0


@dataclass(frozen=True)
class RowBodies:
    """Indices of what a row added: element bodies, their contact pairs per raceway (a four-point row's
    two per ball, +α then −α), the cage, and (ball rows) per contact diagonal the moving and the
    fixed ring's groove."""

    elements: tuple[int, ...]
    moving_pairs: tuple[int, ...]
    fixed_pairs: tuple[int, ...]
    cage: int | None = None
    pocket_pairs: tuple[int, ...] = ()
    other_pairs: tuple[int, ...] = ()
    grooves: tuple[int, ...] = ()


def roller_mass_kg(diameter_m: float, length_m: float, density_kg_m3: float) -> float:
    return density_kg_m3 * math.pi * diameter_m**2 / 4.0 * length_m


def orbit_rad_s(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Orbit speed about the z axis of points at ``q`` moving at ``v`` (last axis x, y, z), rad/s."""
    return (q[..., 0] * v[..., 1] - q[..., 1] * v[..., 0]) / (q[..., 0] ** 2 + q[..., 1] ** 2)


def row_speed_rad_s(rows: RowBodies, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Per recorded sample ((k, n_b, 7) poses ``q``, (k, n_b, 6) velocities ``v``), the speed of a
    row's cage about its own axis (the bearing's), or without a cage its elements' mean orbit
    speed, rad/s."""
    if rows.cage is not None:
        return v[:, rows.cage, 5]
    idx = list(rows.elements)
    return orbit_rad_s(q[:, idx, :3], v[:, idx, :3]).mean(axis=1)


def _law(stiffness: float, exponent: float, damping: float, d_max_m: float, friction,
         max_penetration_m=None, strips=None) -> ContactLaw:
    return ContactLaw(stiffness, exponent, damping, d_max_m, "impact", friction, max_penetration_m, strips)


def _cage_body(builder, name, mass_kg, radius_m, motion, height_m=0.0):
    from .builder import Free

    inertia = (0.5 * mass_kg * radius_m**2, 0.5 * mass_kg * radius_m**2, mass_kg * radius_m**2)
    return builder.add_body(name, mass_kg, inertia, position_m=(0.0, 0.0, height_m), motion=motion or Free())


def _deformed_radius_m(groove_radius_m: float, ball_radius_m: float) -> float:
    """Radius of the deformed surface of a ball in a groove across the contact's major axis,
    2·r_g·r_b/(r_g + r_b) (equal elastic constants: the mean of the two curvatures; Harris &
    Kotzalas, *Rolling Bearing Analysis*, ball–raceway sliding)."""
    return 2.0 * groove_radius_m * ball_radius_m / (groove_radius_m + ball_radius_m)


def _diagonal(builder: ModelBuilder, row, axial_sign: int, moving_ring, fixed_ring, damping_N_s_m: float,
              d_max_m: float, friction, moving_sample, fixed_sample, moving_groove_m, fixed_groove_m,
              traction_strips: int = 0, fixed_frame_z_m: float = 0.0):
    """The moving and the fixed groove of one contact diagonal of a ball row (its curvature centres,
    module docstring) and the Hertz laws of a ball on them: (g_m, g_f, law_m, law_f). With
    ``traction_strips`` the laws integrate the friction over the Hertz ellipse of each contact."""
    D, R = row.ball_diameter_m, row.pitch_diameter_m / 2
    a0 = row.contact_angle_rad
    s_rad = -1.0 if row.moving_raceway == "inner" else 1.0
    u = np.array([s_rad * math.cos(a0), -axial_sign * math.sin(a0)])
    play = np.array([0.25 * row.diametral_clearance_m * s_rad, 0.0])  # each centre moves P_d/4 radially
    c_m = np.array([R, row.axial_position_m]) - (row.conformity_moving * D - D / 2) * u + play
    c_f = np.array([R, row.axial_position_m]) + (row.conformity_fixed * D - D / 2) * u - play
    fixed_raceway = "outer" if row.moving_raceway == "inner" else "inner"
    hertz_m = ball_on_groove(D, row.conformity_moving, row.pitch_diameter_m, a0, row.moving_raceway,
                             row.ball_material, row.race_material)
    hertz_f = ball_on_groove(D, row.conformity_fixed, row.pitch_diameter_m, a0, fixed_raceway,
                             row.ball_material, row.race_material)
    if row.stiffness_N_per_m1p5 is not None:
        k_m = k_f = row.stiffness_N_per_m1p5 * 2.0**1.5  # two equal contacts in series give K back
    else:
        k_m, k_f = hertz_m.stiffness_N_per_m1p5, hertz_f.stiffness_N_per_m1p5
    g_m = builder.add_groove(moving_ring, c_m[0], c_m[1], row.conformity_moving * D,
                             *(moving_groove_m or (None, None)), raceway=moving_sample)
    g_f = builder.add_groove(fixed_ring, c_f[0], c_f[1] - fixed_frame_z_m, row.conformity_fixed * D,
                             *(fixed_groove_m or (None, None)), raceway=fixed_sample)
    strips = [None, None]
    if traction_strips:
        strips = [StripTraction(int(traction_strips), float(h.semi_axes_m(1.0)[0]), _deformed_radius_m(f * D, D / 2))
                  for h, f in ((hertz_m, row.conformity_moving), (hertz_f, row.conformity_fixed))]
    law_m, law_f = (_law(k, 1.5, damping_N_s_m, d_max_m, friction, strips=st) for k, st in zip((k_m, k_f), strips))
    return g_m, g_f, law_m, law_f


def add_ball_row(builder: ModelBuilder, row: BallRow | FourPointRow, moving_ring, fixed_ring, *, friction=None,
                 damping_N_s_m: float = 0.0, d_max_m: float = 1e-6, cage_mass_kg: float | None = None,
                 pocket_clearance_m: float = 0.5e-3, cage_stiffness_N_per_m: float = 1e8,
                 pocket_friction=None, moving_sample=None, fixed_sample=None, moving_groove_m=None,
                 fixed_groove_m=None, cage_motion=None, traction_strips: int = 0,
                 fixed_frame_z_m: float = 0.0) -> RowBodies:
    """Add the balls of ``row`` with their ball–groove contacts (and a cage if ``cage_mass_kg``).

    A :class:`~mbd_core.quasistatic.BallRow` gives each ball two contacts, one per ring; a
    :class:`~mbd_core.quasistatic.FourPointRow` four: each ring's gothic arch is two grooves, one
    per diagonal (+α, −α), the curvature centres of a diagonal placed as for an angular-contact
    row of that axial sign (:mod:`mbd_core.quasistatic.rows_four_point`); the contact pairs are
    then interleaved per ball (+α, −α), as the quasi-static solver's entries. An arch is modelled as
    its whole torus: a contact angle beyond the groove shoulder is not cut off here.

    ``damping_N_s_m`` is the IMPACT damping of every ball contact, reached at ``d_max_m``;
    ``friction`` the law at the raceways, ``pocket_friction`` the one in the cage pockets (None:
    frictionless; pocket friction brakes the balls and makes them slip). ``moving_sample`` /
    ``fixed_sample``: the sampled raceway of a modal ring's groove (see
    :meth:`ModelBuilder.add_groove`); ``moving_groove_m`` / ``fixed_groove_m``: (undulation h(θ),
    radial offset Δr(θ)) tables of that ring's groove, m (None: none); ``cage_motion``: the cage's
    :class:`Free` (default), :class:`Fixed` (balls held at their azimuths, as in the quasi-static
    model) or :class:`Driven` motion. ``traction_strips`` > 0: the raceway friction acts strip by strip
    over each contact's Hertz ellipse (:class:`~mbd_core.multibody.parts.StripTraction`, rigid rings),
    so the balls' spin gives spin moments; 0: at the contact centre.

    The rings' frames are taken to coincide with the world's at the start, except that the fixed
    ring's (and the cage's) origin may sit ``fixed_frame_z_m`` up the axis (a ring whose reference
    point is its own centre, as one of two rows on a shaft): the row's ``axial_position_m`` is then
    the height in the moving ring's frame, and the fixed groove and the pockets are placed below it
    in theirs.
    """
    D, R = row.ball_diameter_m, row.pitch_diameter_m / 2
    four_point = isinstance(row, FourPointRow)
    signs = row.DIAGONAL_SIGNS if four_point else (row.axial_sign,)
    if traction_strips and friction is None:
        raise ValueError(f"ball row {row.name!r}: traction_strips integrate the raceway friction: give friction")
    diagonals = [_diagonal(builder, row, s, moving_ring, fixed_ring, damping_N_s_m, d_max_m, friction, moving_sample,
                           fixed_sample, moving_groove_m, fixed_groove_m, traction_strips, fixed_frame_z_m) for s in signs]
    mass = ball_mass_kg(D, row.ball_material.density_kg_m3)
    inertia = 0.1 * mass * D * D
    cage = None
    if cage_mass_kg is not None:
        cage = _cage_body(builder, f"{row.name} cage", cage_mass_kg, R, cage_motion, fixed_frame_z_m)
    balls, mov, fix, pockets = [], [], [], []
    for j, psi in enumerate(row.azimuths_rad()):
        b = builder.add_body(f"{row.name} ball {j}", mass, (inertia,) * 3,
                             position_m=(R * math.cos(psi), R * math.sin(psi), row.axial_position_m))
        balls.append(b)
        for s, (g_m, g_f, law_m, law_f) in zip(signs, diagonals):
            tag = (" +α" if s > 0 else " −α") if four_point else ""
            mov.append(builder.add_ball_groove(b, moving_ring, g_m, D / 2, law_m,
                                               name=f"{row.name} ball {j}–moving{tag}"))
            fix.append(builder.add_ball_groove(b, fixed_ring, g_f, D / 2, law_f, name=f"{row.name} ball {j}–fixed{tag}"))
        if cage is not None:
            p = builder.add_pocket(cage, "cylinder", psi, R, row.axial_position_m - fixed_frame_z_m, pocket_clearance_m)
            pockets.append(builder.add_element_pocket(
                b, cage, p, D / 2, _law(cage_stiffness_N_per_m, 1.0, damping_N_s_m, d_max_m, pocket_friction),
                name=f"{row.name} ball {j}–pocket"))
    return RowBodies(tuple(balls), tuple(mov), tuple(fix), cage, tuple(pockets),
                     grooves=tuple((g_m, g_f) for g_m, g_f, _, _ in diagonals))


def add_roller_row(builder: ModelBuilder, row: RollerRow, moving_ring, fixed_ring, *, friction=None,
                   damping_N_s_m: float = 0.0, d_max_m: float = 1e-6, rib_clearance_m: float | None = None,
                   edge_radius_m: float | None = None, cage_mass_kg: float | None = None,
                   pocket_clearance_m: float = 0.5e-3, cage_stiffness_N_per_m: float = 1e8,
                   pocket_friction=None, roller_law: tuple[float, float] | None = None, moving_raceway=None,
                   fixed_raceway=None, rib_raceways=(None, None), cage=None, pocket_walls: bool = False,
                   ribs_on: str = "moving") -> RowBodies:
    """Add the rollers of ``row`` with their sliced raceway contacts.

    ``rib_clearance_m``: ribs at both roller ends with this axial play (None: no ribs), on the
    moving ring (``ribs_on="moving"``) or on the cage (``"cage"``: the ends of window pockets, which
    hold a roller along its axis and turn with it); ``cage_mass_kg``: a cage with slot pockets. ``damping_N_s_m`` is the IMPACT damping
    of one slice (ribs and pockets use it too); ``friction`` acts at raceways and ribs,
    ``pocket_friction`` in the pockets (None: frictionless). ``roller_law``: (K, n) of one
    roller–raceway contact, N/m^n, in place of the ISO/TS 16281 line law (each slice gets K/n_s).

    Modal rings and cages: ``moving_raceway`` / ``fixed_raceway`` / ``rib_raceways`` (end +, end −)
    are the sampled (θ, s) grids of those surfaces (``raceway`` of :meth:`ModelBuilder.add_surface`);
    ``cage``: an existing cage body (e.g. modal) in place of a rigid one of ``cage_mass_kg``, its
    pocket k at roller k; ``pocket_walls``: the pockets deform with the cage's stored ``"pockets"``
    sample (:meth:`ModelBuilder.add_pocket`).
    """
    if row.orientation == "crossed":
        raise ValueError(f"add_roller_row: row {row.name!r}: crossed roller rows are modelled by the quasi-static "
                         "solver only (no V-groove raceway surfaces in the multibody model)")
    D, L, R, ns = row.roller_diameter_m, row.roller_length_m, row.pitch_diameter_m / 2, row.n_slices
    g2 = row.gap_m / 2
    x = -0.5 * L + (np.arange(ns) + 0.5) * L / ns
    drop = row.drop_m(x)
    if roller_law is None:
        law = _law(row.contact_stiffness() * 2.0**LINE_EXPONENT / ns, LINE_EXPONENT, damping_N_s_m, d_max_m, friction)
    else:
        # a user law may be much softer than Hertz (the divergence bound, 2 % of the roller radius by
        # default, would then stop a sound run): bound the approach at 10 % of the diameter instead
        law = _law(roller_law[0] / ns, roller_law[1], damping_N_s_m, d_max_m, friction, 0.1 * D)
    z0 = row.axial_position_m
    if row.orientation == "radial":
        inner, outer = R - D / 2 - g2, R + D / 2 + g2
        moving_is_inner = row.load_sign > 0
        s_m = builder.add_surface(moving_ring, "inner_cylinder" if moving_is_inner else "outer_cylinder",
                                  inner if moving_is_inner else outer, raceway=moving_raceway)
        s_f = builder.add_surface(fixed_ring, "outer_cylinder" if moving_is_inner else "inner_cylinder",
                                  outer if moving_is_inner else inner, raceway=fixed_raceway)
    else:
        below, above = z0 - D / 2 - g2, z0 + D / 2 + g2
        s_m = builder.add_surface(moving_ring, "plane_up" if row.load_sign > 0 else "plane_down",
                                  below if row.load_sign > 0 else above, raceway=moving_raceway)
        s_f = builder.add_surface(fixed_ring, "plane_down" if row.load_sign > 0 else "plane_up",
                                  above if row.load_sign > 0 else below, raceway=fixed_raceway)
    if cage is None and cage_mass_kg is not None:
        cage = _cage_body(builder, f"{row.name} cage", cage_mass_kg, R, None)
    if ribs_on not in ("moving", "cage") or (ribs_on == "cage" and cage is None):
        raise ValueError(f"add_roller_row: ribs_on must be 'moving' or 'cage' (with a cage), got {ribs_on!r}")
    rib_body = moving_ring if ribs_on == "moving" else cage
    ribs = ()
    e_r = edge_radius_m if edge_radius_m is not None else 0.1 * D
    if rib_clearance_m is not None:
        h = L / 2 + rib_clearance_m / 2
        # the rib's material lies beyond the roller end: above/below it (radial row), outside the
        # outer end and inside the inner end (thrust rows; "outer_cylinder" has its material at r > value)
        kinds = (("plane_down", z0 + h), ("plane_up", z0 - h)) if row.orientation == "radial" else (
            ("outer_cylinder", R + h), ("inner_cylinder", R - h))
        ribs = tuple((builder.add_surface(rib_body, kind, value, raceway=grid), end)
                     for (kind, value), grid, end in zip(kinds, rib_raceways, (1, -1)))
    density = row.roller_material.density_kg_m3
    mass = roller_mass_kg(D, L, density)
    i_axis = mass * D * D / 8
    i_trans = mass * (3 * (D / 2) ** 2 + L * L) / 12
    rib_friction = friction if ribs_on == "moving" else pocket_friction
    rollers, mov, fix, pockets, other = [], [], [], [], []
    for j, psi in enumerate(row.azimuths_rad()):
        e = np.array([math.cos(psi), math.sin(psi), 0.0])
        axis = (0.0, 0.0, 1.0) if row.orientation == "radial" else e
        b = builder.add_body(f"{row.name} roller {j}", mass, (i_trans, i_trans, i_axis),
                             position_m=(R * e[0], R * e[1], z0), orientation=quat_z_to(axis))
        rollers.append(b)
        mov.append(builder.add_roller_raceway(b, moving_ring, s_m, D / 2, L, law, ns, drop,
                                              name=f"{row.name} roller {j}–moving"))
        fix.append(builder.add_roller_raceway(b, fixed_ring, s_f, D / 2, L, law, ns, drop,
                                              name=f"{row.name} roller {j}–fixed"))
        for surface, end in ribs:
            other.append(builder.add_roller_rib(
                b, rib_body, surface, D / 2, L, end, e_r, _rib_law(e_r, row, damping_N_s_m, d_max_m, rib_friction),
                name=f"{row.name} roller {j}–rib {'+' if end > 0 else '-'}"))
        if cage is not None:
            p = builder.add_pocket(cage, "slot", psi, R, z0, pocket_clearance_m, walls=j if pocket_walls else None)
            pockets.append(builder.add_element_pocket(
                b, cage, p, D / 2, _law(cage_stiffness_N_per_m, 1.0, damping_N_s_m, d_max_m, pocket_friction), length_m=L,
                name=f"{row.name} roller {j}–pocket"))
    return RowBodies(tuple(rollers), tuple(mov), tuple(fix), cage, tuple(pockets), tuple(other))


def _rib_law(edge_radius_m, row: RollerRow, damping, d_max_m, friction) -> ContactLaw:
    """Sphere of the edge radius on a flat rib (Hertz, circular contact): K = (4/3) E* √r, E* = E'/2
    (Johnson, *Contact Mechanics*, eq. 4.23)."""
    e_eff = effective_modulus_Pa(row.roller_material, row.race_material)
    return _law(2.0 / 3.0 * e_eff * math.sqrt(edge_radius_m), 1.5, damping, d_max_m, friction)


#: singular values of the rolling-velocity system (columns scaled to one size) below this share of
#: the largest are taken as zero: the near-null direction is a ball's spin about the line through its
#: two contacts, whose singular value is about the angle between the contact normals. With the
#: contacts 0.1° off collinear it is fixed otherwise by that misalignment alone, and came out at
#: 380 rad/s (100× the rolling speed) on the 1 m slewing ring with a modal top, biasing the orbit
#: by 1.8 % for the whole run (the point contacts carry no spin torque to stop it).
SPIN_RCOND = 1e-2


def set_rolling_velocities(model: Model, state: State, elements, ring, other_ring=None) -> None:
    """Give rolling elements (and nothing else) the no-slip velocities between two rings.

    The rings turn about the world z axis at the speeds they have in ``state``. Each element's
    orbit speed (its centre moving about z) and angular velocity are those that make the slip zero
    at its raceway contact points with both rings (ribs and pockets do not count), in the
    least-squares sense: for elements touching ``ring`` and ``other_ring`` along the line through
    their centres this is the classical rolling kinematics (Harris & Kotzalas, *Essential
    Concepts*, ch. 8). A ball gets the minimum-norm spin; a roller turns about its own axis a only,
    ω = ω_c ẑ + ω_s a (its axis follows the orbit), which fixes the spin about the contact normal
    of a thrust roller. The contact points are the element's surface points along its contact
    normals at ``state``.
    """
    a = model.arrays
    omega_ring = [0.0, 0.0]
    for k, body in enumerate((ring, other_ring)):
        if body is not None:
            omega_ring[k] = _spin_z(state, body)
    z = np.array([0.0, 0.0, 1.0])
    for e in elements:
        pairs = [c for c in range(model.n_pairs) if a.pair_a[c] == e and a.pair_b[c] in (ring, other_ring)
                 and model.pair_kinds[c] in ("ball_groove", "roller_raceway")]
        roller = all(model.pair_kinds[c] == "roller_raceway" for c in pairs)
        axis = _rotate(state.q[e, 3:], z)
        x = state.q[e, :3]
        pts, vel = [], []
        for c in pairs:
            b = a.pair_b[c]
            n = _pair_normal(model, state, c)
            p = x + a.pair_radius[c] * n
            wz = omega_ring[0] if b == ring else omega_ring[1]
            pts.append(p - x)
            vel.append(np.cross([0.0, 0.0, wz], p - state.q[b, :3]))
        if len(pts) < 2:
            raise ValueError(f"set_rolling_velocities: element {model.body_names[e]!r} does not touch both rings")
        # unknowns: orbit speed ω_c (centre velocity ω_c ẑ × x) and ω (world) of a ball, or ω_c and
        # the spin ω_s of a roller (ω = ω_c ẑ + ω_s a)
        rows, rhs = [], []
        for r, vp in zip(pts, vel):
            for i in range(3):
                # v_i = ω_c (ẑ × x)_i + (ω × r)_i,  (ω × r)·e_i = ω·(r × e_i)
                e_i = np.eye(3)[i]
                if roller:
                    rows.append([np.cross(z, x)[i] + np.cross(z, r)[i], np.cross(axis, r)[i]])
                else:
                    rows.append(np.concatenate([[np.cross(z, x)[i]], np.cross(r, e_i)]))
                rhs.append(vp[i])
        # the spin about the line through both contacts does not move them: when the two normals
        # are collinear to within SPIN_RCOND (a ball between a rigid and a deformed modal groove, or
        # round-off) that spin is left at zero instead of being fixed by their tiny misalignment
        A = np.array(rows)
        # columns of one size, so that the cut-off compares directions, not units; a ball's three
        # ω columns share one factor, which keeps its minimum-norm spin that of ω itself
        scale = np.linalg.norm(A, axis=0)
        if not roller:
            scale[1:] = scale[1:].max()
        scale[scale == 0.0] = 1.0
        sol = np.linalg.lstsq(A / scale, np.array(rhs), rcond=SPIN_RCOND)[0] / scale
        omega_c = sol[0]
        omega_w = omega_c * z + sol[1] * axis if roller else sol[1:]
        state.v[e, :3] = omega_c * np.cross(z, x)
        state.v[e, 3:] = _rotate_back(state.q[e, 3:], omega_w)


def start_at_equilibrium(model: Model, state: State, balls: RowBodies, inner: int, outer: int, quasi) -> None:
    """Put a ball row in ``state`` at a quasi-static high-speed equilibrium ``quasi`` (the result of
    :func:`mbd_core.quasistatic.solve_high_speed_row`): the inner ring's displacement, then the balls
    and cage as :func:`place_balls`, so a run starts without a start-up shock."""
    state.q[inner, :3] = quasi.displacement[:3]
    place_balls(model, state, balls, inner, outer, quasi)


def place_balls(model: Model, state: State, balls: RowBodies, inner: int, outer: int, quasi,
                shift_z_m: float = 0.0) -> None:
    """Each ball of a row at its centre in ``quasi`` (:func:`mbd_core.quasistatic.solve_high_speed_row`,
    given in the outer ring's frame; ``shift_z_m`` moves them and the cage up the axis with an outer
    ring that is not where the solution has it), the no-slip rolling velocities
    (:func:`set_rolling_velocities`) and the cage at the balls' mean orbit speed."""
    for j, ball in enumerate(balls.elements):
        r, z = quasi.ball_centre_rz_m[j]
        state.q[ball, :3] = (r * math.cos(quasi.azimuth_rad[j]), r * math.sin(quasi.azimuth_rad[j]), z + shift_z_m)
    set_rolling_velocities(model, state, balls.elements, inner, other_ring=outer)
    if balls.cage is not None:
        elements = list(balls.elements)
        state.q[balls.cage, 2] += shift_z_m
        state.v[balls.cage, 5] = float(np.mean(orbit_rad_s(state.q[elements, :3], state.v[elements, :3])))


def _spin_z(state: State, body: int) -> float:
    return float(_rotate(state.q[body, 3:], state.v[body, 3:])[2])


def _pair_normal(model: Model, state: State, c: int) -> np.ndarray:
    """Unit vector from an element's centre towards its contact point of pair c (world): for a
    groove, from the curvature centre through the ball centre; for a raceway, into the raceway."""
    a = model.arrays
    e, b = a.pair_a[c], a.pair_b[c]
    x = state.q[e, :3] - state.q[b, :3]
    xl = _rotate_back(state.q[b, 3:], x)
    kind = model.pair_kinds[c]
    if kind == "ball_groove":
        g = a.pair_geom[c]
        _, _, nx, ny, nz = groove_point(xl[0], xl[1], xl[2], a.groove_rc[g], a.groove_zc[g], 0.0,
                                        a.groove_h[a.groove_h_off[g]:a.groove_h_off[g + 1]],
                                        a.groove_dr[a.groove_dr_off[g]:a.groove_dr_off[g + 1]])
        return _rotate(state.q[b, 3:], np.array([nx, ny, nz]))
    g = a.pair_geom[c]
    kind_s = a.race_kind[g]
    if kind_s <= 1:
        er = np.array([xl[0], xl[1], 0.0]) / math.hypot(xl[0], xl[1])
        n = -er if kind_s == 0 else er
    else:
        n = np.array([0.0, 0.0, -1.0 if kind_s == 2 else 1.0])
    return _rotate(state.q[b, 3:], n)


def _rotate(q, x):
    w, v = q[0], np.asarray(q[1:])
    t = 2.0 * np.cross(v, x)
    return x + w * t + np.cross(v, t)


def _rotate_back(q, x):
    return _rotate(np.array([q[0], -q[1], -q[2], -q[3]]), x)
