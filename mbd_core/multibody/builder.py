"""Collect bodies, drivers, loads and contact pairs; ``finalize()`` validates and freezes them.

Frames: every body has a reference point (its centre of mass) and body axes that are its principal
axes of inertia. Rings, cages and the bearing use z as their axis; a roller's body z is its own axis.
Positions and forces are given in the world frame, m and N; angular velocities in the body frame.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

from ..kernels.forces import BALL_BALL, BALL_GROOVE, ELEMENT_POCKET, ROLLER_RACEWAY, ROLLER_RIB
from ..kernels.laws import NORMAL_HUNT_CROSSLEY, NORMAL_IMPACT
from foundation.validation import check_positive
from . import warmup
from .builder_arrays import (_f64, _i64, _quat_conj, _quat_mul, _rotate, _rotate_back, _skew, modal_arrays,
                             squeeze_film_arrays, unbalance_arrays)
from ..squeeze_film.force_table import FilmForceTable
from .builder_geometry import POCKET_KINDS, GeometryMixin, _Body, _vec
from .model import Model, ModelArrays, State
from .parts import ContactLaw, Driven, Fixed, Free, StripTraction, quat_from_axis_angle, quat_z_to

__all__ = ["ModelBuilder", "ContactLaw", "StripTraction", "Free", "Fixed", "Driven", "quat_from_axis_angle", "quat_z_to"]

PAIR_KIND_NAMES = {
    BALL_GROOVE: "ball_groove", BALL_BALL: "ball_ball", ROLLER_RACEWAY: "roller_raceway",
    ROLLER_RIB: "roller_rib", ELEMENT_POCKET: "element_pocket",
}


class ModelBuilder(GeometryMixin):
    """Edit freely, then :meth:`finalize` into a frozen :class:`Model` and its initial :class:`State`.

    ``gravity_m_s2``: world gravity. ``implicit_friction``: the friction on rigid bodies with a free
    component (free, or driven and free to move or tilt) enters their kick implicitly, as a damper
    frozen at the last force evaluation (the secant μ(u) F_n / u, along the slip the law's slope where
    that is larger; :mod:`mbd_core.kernels.explicit`); the friction law's slope then no longer limits
    the explicit step for those bodies. Off by default: the kick is then the plain explicit one.
    """

    def __init__(self, gravity_m_s2=(0.0, 0.0, 0.0), implicit_friction: bool = False):
        self.gravity_m_s2 = _vec("model", "gravity_m_s2", gravity_m_s2, 3)
        self.implicit_friction = bool(implicit_friction)
        self._bodies: list[_Body] = []
        self._pairs: list[dict] = []
        self._grooves: list[dict] = []
        self._surfaces: list[dict] = []
        self._pockets: list[dict] = []
        self._bushings: list[dict] = []
        self._drags: list[tuple[int, float, float]] = []
        self._dampers: list[dict] = []
        self._unbalances: list[dict] = []
        self._loads: list[tuple[int, np.ndarray, np.ndarray]] = []

    # -- bodies ---------------------------------------------------------------------------------
    def add_body(self, name: str, mass_kg: float, inertia_kg_m2, position_m=(0, 0, 0), orientation=(1, 0, 0, 0),
                 velocity_m_s=(0, 0, 0), omega_rad_s=(0, 0, 0), motion=Free()) -> int:
        """Add a rigid body; returns its index.

        ``inertia_kg_m2`` are the principal moments (body axes); ``orientation`` the unit quaternion
        (w, x, y, z) body → world; ``omega_rad_s`` the angular velocity in body axes. ``motion`` is
        :class:`Free`, :class:`Fixed` or :class:`Driven` (a driven body's spin overrides ω_z).
        """
        owner = f"body {name!r}"
        if any(b.name == name for b in self._bodies):
            raise ValueError(f"{owner}: a body of this name exists already")
        check_positive(owner, mass_kg=mass_kg)
        inertia = _vec(owner, "inertia_kg_m2", inertia_kg_m2, 3)
        if np.any(inertia <= 0):
            raise ValueError(f"{owner}: inertia_kg_m2 must be positive, got {inertia.tolist()}")
        q = _vec(owner, "orientation", orientation, 4)
        if np.linalg.norm(q) < 1e-12:
            raise ValueError(f"{owner}: orientation must be a non-zero quaternion")
        q = q / np.linalg.norm(q)
        v = np.concatenate([_vec(owner, "velocity_m_s", velocity_m_s, 3), _vec(owner, "omega_rad_s", omega_rad_s, 3)])
        if isinstance(motion, Free):
            free = np.ones(6, dtype=np.int64)
        elif isinstance(motion, Fixed):
            free = np.zeros(6, dtype=np.int64)
            v[:] = 0.0
        elif isinstance(motion, Driven):
            t, r = int(motion.translation_free), int(motion.tilt_free)
            free = np.array([t, t, t, r, r, 0], dtype=np.int64)
            v[:3] *= t
            v[3:5] *= r
            v[5] = motion.omega_rad_s
        else:
            raise TypeError(f"{owner}: motion must be Free(), Fixed() or Driven(...), got {motion!r}")
        self._bodies.append(_Body(name, float(mass_kg), inertia, np.concatenate([_vec(owner, "position_m", position_m, 3), q]), v, free))
        return len(self._bodies) - 1

    def add_modal_body(self, name: str, body, position_m=(0, 0, 0), orientation=(1, 0, 0, 0),
                       velocity_m_s=(0, 0, 0), omega_rad_s=(0, 0, 0), motion=Fixed(), eta=None, eta_dot=None,
                       implicit_modes: bool = False) -> int:
        """Add a modal (flexible) body from a :class:`cms_reduction.ReducedBody`; returns its index.

        ``position_m``/``orientation`` place the body's FE frame (ring axis = z); ``motion`` as for
        :meth:`add_body`. A :class:`Free` body needs free–free modes (a floating reduction: modes
        that do not move the centre of mass); its reference point is moved to its centre of mass on
        the axis, and geometry given later in its ring frame (grooves, surfaces, pockets) is shifted
        to match. ``eta``/``eta_dot`` (m,) are the initial modal coordinates (√kg) and rates;
        ``implicit_modes`` (Fixed or Driven frames) kicks the body with the augmented mass
        M + (h/2)C + (h/2)²K, which has the trapezoidal rule's stability, so that neither the stiffest
        mode nor its coupling with the frame's free components limits the step
        (:mod:`mbd_core.kernels.modal_step`).
        """
        from cms_reduction.invariants import Invariants

        owner = f"modal body {name!r}"
        try:
            inv = Invariants.from_arrays(body.extras)
        except KeyError as exc:
            raise ValueError(f"{owner}: the reduced body has no inertia invariants ({exc})") from None
        m = body.n_modes
        I2, I3, I4, I7, I8 = (np.array(x, float) for x in (inv.I2, inv.I3, inv.I4, inv.I7, inv.I8))
        shift = np.zeros(3)
        if isinstance(motion, Free):
            scale = math.sqrt(inv.mass_kg)
            if np.abs(I3).max(initial=0.0) > 1e-6 * scale:
                raise ValueError(f"{owner}: a free modal body needs free–free modes that leave the centre of mass "
                                 f"in place; |∫ρΦ dV| = {np.abs(I3).max():.3g} √kg·m (reduce it without grounded "
                                 "interfaces)")
            shift = I2 / inv.mass_kg
            radius = math.sqrt(np.trace(I7) / inv.mass_kg)
            if math.hypot(shift[0], shift[1]) > 1e-9 * radius:
                raise ValueError(f"{owner}: the centre of mass {shift.tolist()} m is off the ring axis; a free "
                                 "modal body needs it on its frame's z axis")
            shift[:2] = 0.0
            # invariants about the centre of mass: x̄ → x̄ − c (Steiner for I7; I4, I8 by their definitions)
            c, s2 = _skew(shift), _skew(I2)
            I7 = I7 - s2.T @ c - c.T @ s2 + inv.mass_kg * c.T @ c
            I4 = I4 - c @ I3
            I8 = I8 - np.einsum("ab,bck->ack", c.T, np.stack([_skew(I3[:, k]) for k in range(m)], axis=2))
            I2 = I2 - inv.mass_kg * shift
            I3 = np.zeros_like(I3)
        elif not isinstance(motion, (Fixed, Driven)):
            raise TypeError(f"{owner}: motion must be Free(), Fixed() or Driven(...), got {motion!r}")
        if implicit_modes and isinstance(motion, Free):
            raise ValueError(f"{owner}: implicit_modes needs a Fixed or Driven frame (a Free frame is integrated "
                             "in momentum form, explicitly)")
        q = _vec(owner, "orientation", orientation, 4)
        q = q / np.linalg.norm(q)
        pos = _vec(owner, "position_m", position_m, 3) + _rotate(q, shift)
        i = self.add_body(name, inv.mass_kg, np.maximum(np.diag(I7), 1e-30), pos, q, velocity_m_s, omega_rad_s,
                          motion)
        b = self._bodies[i]
        frame_free, b.free = b.free.copy(), np.zeros(6, dtype=np.int64)
        eta0 = np.zeros(m) if eta is None else _vec(owner, "eta", eta, m)
        eta_dot0 = np.zeros(m) if eta_dot is None else _vec(owner, "eta_dot", eta_dot, m)
        omega = 2.0 * np.pi * np.asarray(body.frequencies_Hz, float)
        b.frame_z_m = float(shift[2])
        b.modal = dict(reduced=body, frame_free=frame_free, implicit=int(bool(implicit_modes)), mass=inv.mass_kg,
                       I2=I2, I3=I3, I4=I4, I5=np.array(inv.I5), I6=np.array(inv.I6), I7=I7, I8=I8,
                       I9=np.array(inv.I9), omega2=omega**2,
                       damp=2.0 * np.asarray(body.damping_ratio, float) * omega, eta=eta0, eta_dot=eta_dot0,
                       shift=shift)
        return i

    def _body_index(self, body, owner: str) -> int:
        if isinstance(body, str):
            for i, b in enumerate(self._bodies):
                if b.name == body:
                    return i
            raise ValueError(f"{owner}: no body named {body!r}")
        if not (isinstance(body, (int, np.integer)) and 0 <= body < len(self._bodies)):
            raise ValueError(f"{owner}: no body with index {body!r}")
        return int(body)

    # -- loads ----------------------------------------------------------------------------------
    def add_force(self, body, force_N=(0, 0, 0), moment_Nm=(0, 0, 0)) -> None:
        """Constant world-frame force (at the body's reference point) and moment."""
        i = self._body_index(body, "force")
        self._bodies[i].force += np.concatenate([_vec("force", "force_N", force_N, 3), _vec("force", "moment_Nm", moment_Nm, 3)])

    def add_load_history(self, body, times_s, loads) -> None:
        """Time-varying world force and moment: a cubic spline through (t_k, [F, M]_k).

        ``times_s`` (k,) strictly increasing, k ≥ 2; ``loads`` (k, 6) N and N·m. Before the first
        and after the last time the end values are held.
        """
        i = self._body_index(body, "load history")
        t = np.asarray(times_s, float)
        f = np.asarray(loads, float)
        if t.ndim != 1 or t.size < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            raise ValueError("load history: times_s must be ≥ 2 finite, strictly increasing times")
        if f.shape != (t.size, 6) or not np.all(np.isfinite(f)):
            raise ValueError(f"load history: loads must be finite with shape ({t.size}, 6), got {f.shape}")
        self._loads.append((i, t, f))

    def add_drag(self, body, linear_N_s_m: float, quadratic_N_s2_m2: float = 0.0) -> None:
        """Drag of the surrounding fluid (at rest in the world frame) on a body's centre:
        F = −(c₁ + c₂|v|)·v, v the centre's velocity. For a ball of diameter d in a fluid of viscosity
        μ at small Reynolds numbers c₁ = 3π·μ·d (Stokes); c₂ = ½·ρ·C_D·A for a constant drag coefficient."""
        i = self._body_index(body, "drag")
        for name, value in (("linear_N_s_m", linear_N_s_m), ("quadratic_N_s2_m2", quadratic_N_s2_m2)):
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"drag: {name} must be a number ≥ 0, got {value!r}")
        self._drags.append((i, float(linear_N_s_m), float(quadratic_N_s2_m2)))

    def add_unbalance(self, body, point_m, unbalance_kg_m, angle_rad: float = 0.0, mode_shapes=None) -> None:
        """An unbalance of ``unbalance_kg_m`` (m_u e, kg·m) at ``point_m`` (the body's own frame; for a
        modal body its ring frame) pointing at ``angle_rad`` about the body's z axis from its x axis:
        the centrifugal force m_u (ω² e − (ω·e) ω) at that point, turning with the body
        (:mod:`mbd_core.kernels.unbalance`); on a modal body it also loads the modes there, through
        ``mode_shapes`` (3, m) m/√kg at the point, or by default the body's modes interpolated on its
        mesh (:func:`cms_reduction.sampling.sample_points`)."""
        owner = "unbalance"
        i = self._body_index(body, owner)
        p = _vec(owner, "point_m", point_m, 3)
        for name, value in (("unbalance_kg_m", unbalance_kg_m), ("angle_rad", angle_rad)):
            if not (isinstance(value, (int, float)) and math.isfinite(value)):
                raise ValueError(f"{owner}: {name} must be a finite number, got {value!r}")
        if unbalance_kg_m < 0.0:
            raise ValueError(f"{owner}: unbalance_kg_m must be ≥ 0, got {unbalance_kg_m}")
        b = self._bodies[i]
        disp = np.zeros((3, 0))
        if b.modal is not None:
            reduced = b.modal["reduced"]
            if mode_shapes is None:
                from cms_reduction.sampling import sample_points

                disp = sample_points(reduced, "unbalance", p[None, :], np.zeros(1)).displacement[0]
            else:
                disp = np.asarray(mode_shapes, dtype=float)
                if disp.shape != (3, reduced.n_modes) or not np.all(np.isfinite(disp)):
                    raise ValueError(f"{owner}: mode_shapes must be finite with shape (3, {reduced.n_modes}), "
                                     f"got {disp.shape}")
            p = p - b.modal["shift"]
        elif mode_shapes is not None:
            raise ValueError(f"{owner}: body {b.name!r} is rigid; mode_shapes apply to a modal body")
        u = float(unbalance_kg_m) * np.array([math.cos(angle_rad), math.sin(angle_rad), 0.0])
        self._unbalances.append(dict(body=i, point=p, u=u, disp=disp))

    def add_squeeze_film(self, journal, housing, table, bore_center_m=(0, 0, 0),
                         axis=(0, 0, 1), name: str | None = None, journal_center_m=None) -> int:
        """A squeeze-film damper between a journal (a bearing's outer race) and its housing; returns
        its index.

        ``table`` is the damper's :class:`mbd_core.squeeze_film.force_table.FilmForceTable`
        (:func:`~mbd_core.squeeze_film.force_table.tabulate` of a
        :class:`~mbd_core.squeeze_film.SqueezeFilmDamper`); ``bore_center_m`` the bore's centre and
        ``axis`` its axis, world, at the start; ``journal_center_m`` the journal's centre, world, at the
        start (None: its body's reference point). The journal gets the film force there. A journal beyond the table's eccentricity ends the run
        with an error naming the damper.
        """
        a, b = self._body_index(journal, "squeeze film"), self._body_index(housing, "squeeze film")
        if a == b:
            raise ValueError("squeeze film: journal and housing must differ")
        if not isinstance(table, FilmForceTable):
            raise TypeError("squeeze film: table must be a FilmForceTable (mbd_core.squeeze_film.force_table.tabulate)")
        n = _vec("squeeze film", "axis", axis, 3)
        if not np.linalg.norm(n) > 0.0:
            raise ValueError("squeeze film: axis must be a non-zero vector")
        n = n / np.linalg.norm(n)
        center = _vec("squeeze film", "bore_center_m", bore_center_m, 3)
        name = name or f"{self._bodies[a].name}–{self._bodies[b].name} film"
        if any(d["name"] == name for d in self._dampers):
            raise ValueError(f"squeeze film: the name {name!r} is used twice")
        journal_at = self._bodies[a].q[:3] if journal_center_m is None else _vec("squeeze film", "journal_center_m",
                                                                                  journal_center_m, 3)
        d = journal_at - center
        eps = float(np.linalg.norm(d - (d @ n) * n)) / table.clearance_m
        if eps > table.max_eccentricity_ratio:
            raise ValueError(f"squeeze film {name!r}: the journal starts at ε = {eps:.3g} of the clearance "
                             f"{table.clearance_m:g} m, beyond the table's {table.max_eccentricity_ratio:g}")
        self._dampers.append(dict(a=a, b=b, table=table, center=center, axis=n, name=name, journal=journal_at))
        return len(self._dampers) - 1

    # -- joints ---------------------------------------------------------------------------------
    def add_bushing(self, body_a, body_b, point_m, stiffness, damping=(0, 0, 0, 0, 0, 0)) -> None:
        """Penalty bushing between two bodies at a world point (their current relative pose is at rest).

        ``stiffness`` (6,) N/m ×3 then N·m/rad ×3 and ``damping`` (6,) N·s/m, N·m·s/rad, along
        body a's axes.
        """
        a, b = self._body_index(body_a, "bushing"), self._body_index(body_b, "bushing")
        if a == b:
            raise ValueError("bushing: body_a and body_b must differ")
        k = _vec("bushing", "stiffness", stiffness, 6)
        c = _vec("bushing", "damping", damping, 6)
        if np.any(k < 0) or np.any(c < 0):
            raise ValueError("bushing: stiffness and damping must be ≥ 0")
        self._bushings.append(dict(a=a, b=b, point=_vec("bushing", "point_m", point_m, 3), k=k, c=c))

    # -- contact pairs --------------------------------------------------------------------------
    def _add_pair(self, kind: int, element, other, geom: int, law: ContactLaw, radius: float, name: str | None,
                  radius_b: float = 0.0, length: float = 0.0, aux=(0.0, 0.0), drop=()) -> int:
        owner = f"{PAIR_KIND_NAMES[kind]} contact"
        a, b = self._body_index(element, owner), self._body_index(other, owner)
        if a == b:
            raise ValueError(f"{owner}: a body cannot touch itself ({self._bodies[a].name!r})")
        if not isinstance(law, ContactLaw):
            raise TypeError(f"{owner}: law must be a ContactLaw")
        check_positive(owner, element_radius_m=radius)
        name = name or f"{self._bodies[a].name}–{self._bodies[b].name}"
        self._pairs.append(dict(kind=kind, a=a, b=b, geom=geom, law=law, radius=float(radius), radius_b=float(radius_b),
                                length=float(length), aux=np.asarray(aux, float), drop=np.asarray(drop, float), name=name))
        return len(self._pairs) - 1

    def add_ball_groove(self, ball, ring, groove: int, ball_radius_m: float, law: ContactLaw, name=None) -> int:
        """Ball–groove point contact (the groove must belong to ``ring``)."""
        if not 0 <= groove < len(self._grooves):
            raise ValueError(f"ball–groove contact: no groove {groove}")
        if self._grooves[groove]["ring"] != self._body_index(ring, "ball–groove contact"):
            raise ValueError("ball–groove contact: the groove belongs to another body")
        if self._grooves[groove]["r"] <= ball_radius_m:
            raise ValueError(
                f"ball–groove contact: the groove radius {self._grooves[groove]['r']} m must exceed the ball "
                f"radius {ball_radius_m} m (conformity > 0.5)")
        return self._add_pair(BALL_GROOVE, ball, ring, groove, law, ball_radius_m, name)

    def add_ball_ball(self, ball_a, ball_b, radius_a_m: float, radius_b_m: float, law: ContactLaw, name=None) -> int:
        """Sphere–sphere contact (load ball against spacer ball)."""
        check_positive("ball–ball contact", radius_b_m=radius_b_m)
        return self._add_pair(BALL_BALL, ball_a, ball_b, -1, law, radius_a_m, name, radius_b=radius_b_m)

    def add_roller_raceway(self, roller, ring, surface: int, radius_m: float, length_m: float, law: ContactLaw,
                           n_slices: int = 20, drop_m=None, name=None) -> int:
        """Sliced line contact of a roller (body z = its axis) on a raceway surface of ``ring``.

        ``drop_m`` (n_slices,) is the profile drop of each slice (crown, logarithmic), m; None = flat.
        ``law.stiffness`` is the stiffness of one slice.
        """
        owner = "roller–raceway contact"
        if not 0 <= surface < len(self._surfaces):
            raise ValueError(f"{owner}: no surface {surface}")
        if not (isinstance(n_slices, (int, np.integer)) and n_slices >= 1):
            raise ValueError(f"{owner}: n_slices must be an integer ≥ 1, got {n_slices!r}")
        check_positive(owner, length_m=length_m)
        drop = np.zeros(n_slices) if drop_m is None else np.asarray(drop_m, float).reshape(-1)
        if drop.shape != (n_slices,) or not np.all(np.isfinite(drop)) or np.any(drop < 0) or np.any(drop >= radius_m):
            raise ValueError(f"{owner}: drop_m must be {n_slices} values in [0, radius)")
        self._check_owner(self._surfaces[surface]["grid"], self._surfaces[surface]["ring"], ring, owner, "surface")
        return self._add_pair(ROLLER_RACEWAY, roller, ring, surface, law, radius_m, name, length=length_m, drop=drop)

    def add_roller_rib(self, roller, ring, surface: int, radius_m: float, length_m: float, end_sign: int,
                       edge_radius_m: float, law: ContactLaw, name=None) -> int:
        """Roller end (at s = end_sign·L/2, rim rounded with edge_radius_m) against a rib surface."""
        owner = "roller–rib contact"
        if not 0 <= surface < len(self._surfaces):
            raise ValueError(f"{owner}: no surface {surface}")
        if end_sign not in (1, -1):
            raise ValueError(f"{owner}: end_sign must be +1 or -1, got {end_sign!r}")
        check_positive(owner, length_m=length_m, edge_radius_m=edge_radius_m)
        if edge_radius_m >= min(radius_m, length_m / 2):
            raise ValueError(f"{owner}: edge_radius_m must be smaller than the roller radius and half length")
        self._check_owner(self._surfaces[surface]["grid"], self._surfaces[surface]["ring"], ring, owner, "surface")
        return self._add_pair(ROLLER_RIB, roller, ring, surface, law, radius_m, name, length=length_m,
                              aux=(float(end_sign), edge_radius_m))

    def add_element_pocket(self, element, cage, pocket: int, radius_m: float, law: ContactLaw, length_m: float = 0.0,
                           name=None) -> int:
        """Rolling element in a cage pocket (a slot pocket needs the roller length)."""
        owner = "element–pocket contact"
        if not 0 <= pocket < len(self._pockets):
            raise ValueError(f"{owner}: no pocket {pocket}")
        if self._pockets[pocket]["kind"] == POCKET_KINDS["slot"]:
            check_positive(owner, length_m=length_m)
        self._check_owner(self._pockets[pocket]["walls"], self._pockets[pocket]["cage"], cage, owner, "pocket")
        return self._add_pair(ELEMENT_POCKET, element, cage, pocket, law, radius_m, name, length=length_m)

    def _check_owner(self, sampled, geom_body: int, body, owner: str, what: str) -> None:
        """A sampled surface or pocket deforms with its own body only (its modal forces go there)."""
        if sampled is not None and geom_body != self._body_index(body, owner):
            raise ValueError(f"{owner}: the sampled {what} belongs to body {self._bodies[geom_body].name!r}")

    # -- finalize -------------------------------------------------------------------------------
    def _check_strips(self, pairs) -> None:
        """Strip traction: ball–groove pairs (rigid or modal grooves) only (ValueError naming the pair)."""
        for p in pairs:
            if p["law"].strips is None:
                continue
            if p["kind"] != BALL_GROOVE:
                raise ValueError(f"model: contact {p['name']!r}: strip traction is for ball–groove contacts, not "
                                 f"{PAIR_KIND_NAMES[p['kind']]}")

    def finalize(self) -> tuple[Model, State]:
        """Validate and freeze: returns the model of flat arrays and the initial state."""
        warmup.wait()  # before the first kernel call of a model (module docstring of .warmup)
        if not self._bodies:
            raise ValueError("model: no bodies")
        bodies, pairs = self._bodies, self._pairs
        nb = len(bodies)
        mass = np.array([b.mass for b in bodies])
        force = np.array([b.force for b in bodies]).reshape(nb, 6)
        rigid = np.array([b.modal is None for b in bodies])
        force[rigid, :3] += mass[rigid, None] * self.gravity_m_s2  # modal bodies: from their invariants
        for name in {p["name"] for p in pairs}:
            if sum(p["name"] == name for p in pairs) > 1:
                raise ValueError(f"model: contact name {name!r} is used twice")
        laws = [p["law"] for p in pairs]
        slice_counts = [p["drop"].size if p["kind"] == ROLLER_RACEWAY else 0 for p in pairs]
        fric = [(l.friction.code, l.friction.params) if l.friction is not None else (0, np.zeros(4)) for l in laws]
        knot_t, knot_coef, load_off = [], [], [0]
        for _, t, f in self._loads:
            pp = CubicSpline(t, f, axis=0)
            coef = np.zeros((t.size, 4, 6))
            coef[:-1] = np.transpose(pp.c, (1, 0, 2))
            knot_t.append(t)
            knot_coef.append(coef)
            load_off.append(load_off[-1] + t.size)
        q0 = np.array([b.q for b in bodies])
        bq = []
        for bu in self._bushings:
            qa, qb = q0[bu["a"], 3:], q0[bu["b"], 3:]
            bq.append(_quat_mul(_quat_conj(qa), qb))
        p_a = [_rotate_back(q0[bu["a"]], bu["point"]) for bu in self._bushings]
        p_b = [_rotate_back(q0[bu["b"]], bu["point"]) for bu in self._bushings]
        grooves = self._grooves
        modal_arrays_ = modal_arrays(self._bodies, self._grooves, self._surfaces, self._pockets)
        for p in pairs:
            if bodies[p["b"]].modal is None or p["kind"] in (BALL_GROOVE, BALL_BALL):
                continue
            if p["kind"] == ELEMENT_POCKET and self._pockets[p["geom"]]["walls"] is None:
                raise ValueError(f"model: contact {p['name']!r}: pocket {p['geom']} on the modal cage "
                                 f"{bodies[p['b']].name!r} has no wall samples; give add_pocket(..., walls=k) "
                                 "(pocket k of the cage's stored 'pockets' sample) so that its walls deform with the "
                                 "cage")
            if p["kind"] in (ROLLER_RACEWAY, ROLLER_RIB) and self._surfaces[p["geom"]]["grid"] is None:
                raise ValueError(f"model: contact {p['name']!r}: surface {p['geom']} on the modal ring "
                                 f"{bodies[p['b']].name!r} is not sampled; give add_surface(..., raceway=...) (the "
                                 "(θ, s) grid of circles it deforms with)")
        self._check_strips(pairs)
        arrays = ModelArrays(
            body_mass=mass, body_inertia=np.array([b.inertia for b in bodies]),
            body_free=np.array([b.free for b in bodies], dtype=np.int64), body_force=force,
            body_fric_implicit=_i64([self.implicit_friction and b.modal is None and any(b.free) for b in bodies]),
            load_body=_i64([l[0] for l in self._loads]), load_off=_i64(load_off),
            knot_t=_f64(np.concatenate(knot_t) if knot_t else np.zeros(0)),
            knot_coef=_f64(np.concatenate(knot_coef) if knot_coef else np.zeros((0, 4, 6))),
            bush_a=_i64([b["a"] for b in self._bushings]), bush_b=_i64([b["b"] for b in self._bushings]),
            bush_p_a=_f64(p_a, (-1, 3)), bush_p_b=_f64(p_b, (-1, 3)), bush_q_ref=_f64(bq, (-1, 4)),
            bush_k=_f64([b["k"] for b in self._bushings], (-1, 6)), bush_c=_f64([b["c"] for b in self._bushings], (-1, 6)),
            drag_body=_i64([d[0] for d in self._drags]), drag_c=_f64([d[1:] for d in self._drags], (-1, 2)),
            **squeeze_film_arrays(self._dampers, q0),
            **unbalance_arrays(self._unbalances, modal_arrays_["modal_I6"].shape[1]),
            pair_type=_i64([p["kind"] for p in pairs]), pair_a=_i64([p["a"] for p in pairs]),
            pair_b=_i64([p["b"] for p in pairs]), pair_geom=_i64([p["geom"] for p in pairs]),
            pair_law=_i64([NORMAL_IMPACT if l.model == "impact" else NORMAL_HUNT_CROSSLEY for l in laws]),
            pair_k=_f64([l.stiffness for l in laws]), pair_n=_f64([l.exponent for l in laws]),
            pair_c=_f64([l.damping for l in laws]), pair_dmax=_f64([l.d_max_m for l in laws]),
            pair_fric=_i64([f[0] for f in fric]), pair_fric_p=_f64([f[1] for f in fric], (-1, 4)),
            pair_radius=_f64([p["radius"] for p in pairs]), pair_radius_b=_f64([p["radius_b"] for p in pairs]),
            pair_length=_f64([p["length"] for p in pairs]), pair_aux=_f64([p["aux"] for p in pairs], (-1, 2)),
            pair_slice_off=_i64(np.concatenate([[0], np.cumsum(slice_counts)])),
            slice_drop=_f64(np.concatenate([p["drop"] for p in pairs if p["kind"] == ROLLER_RACEWAY] or [np.zeros(0)])),
            pair_strips=_i64([0 if l.strips is None else l.strips.n_strips for l in laws]),
            pair_semi_major=_f64([0.0 if l.strips is None else l.strips.semi_major_m_per_N3 for l in laws]),
            pair_strip_curv=_f64([0.0 if l.strips is None else l.strips.curvature_per_m for l in laws]),
            pair_delta_max=_f64([l.max_penetration_m if l.max_penetration_m is not None else 0.02 * p["radius"]
                                for l, p in zip(laws, pairs)]),
            groove_rc=_f64([g["rc"] for g in grooves]), groove_zc=_f64([g["zc"] for g in grooves]),
            groove_r=_f64([g["r"] for g in grooves]),
            groove_h_off=_i64(np.concatenate([[0], np.cumsum([g["h"].size for g in grooves])])),
            groove_h=_f64(np.concatenate([g["h"] for g in grooves] or [np.zeros(0)])),
            groove_dr_off=_i64(np.concatenate([[0], np.cumsum([g["dr"].size for g in grooves])])),
            groove_dr=_f64(np.concatenate([g["dr"] for g in grooves] or [np.zeros(0)])),
            race_kind=_i64([s["kind"] for s in self._surfaces]), race_value=_f64([s["value"] for s in self._surfaces]),
            pocket_kind=_i64([p["kind"] for p in self._pockets]),
            pocket_angle=_f64([p["angle"] for p in self._pockets]),
            pocket_r=_f64([p["r"] for p in self._pockets]), pocket_z=_f64([p["z"] for p in self._pockets]),
            pocket_clearance=_f64([p["clearance"] for p in self._pockets]),
            gravity=self.gravity_m_s2.copy(), **modal_arrays_,
        )
        model = Model(arrays, tuple(b.name for b in bodies), tuple(p["name"] for p in pairs),
                      tuple(PAIR_KIND_NAMES[p["kind"]] for p in pairs), self.gravity_m_s2.copy(),
                      tuple(d["name"] for d in self._dampers))
        modal = [b.modal for b in bodies if b.modal is not None]
        state = State(0.0, q0.copy(), np.array([b.v for b in bodies]).reshape(nb, 6),
                      np.concatenate([d["eta"] for d in modal] or [np.zeros(0)]),
                      np.concatenate([d["eta_dot"] for d in modal] or [np.zeros(0)]))
        return model, state
