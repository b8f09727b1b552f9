"""Frozen model, restartable state and preallocated work of a multibody bearing model.

The model is a set of flat arrays (structure of arrays) grouped in one namedtuple so
that the compiled kernels take it as a single argument; per-entity arrays are named
``entity_property``. Shapes (n_b bodies, n_c contact pairs, n_g grooves, n_r raceway/rib surfaces,
n_p cage pockets, n_u bushings, n_l load histories):

Bodies
    body_mass (n_b,) kg; body_inertia (n_b, 3) kg·m², principal, body frame;
    body_free (n_b, 6) int64, 1 where the component of v is integrated (v_x, v_y, v_z world,
    ω_x, ω_y, ω_z body), 0 where it is held at its prescribed value;
    body_force (n_b, 6) N and N·m: constant world force and moment (gravity included);
    body_fric_implicit (n_b,) int64, 1 for a body whose friction is integrated implicitly (a rigid
    body with a free component, in a model built with ``implicit_friction``; :mod:`mbd_core.kernels.explicit`).
Load histories (cubic splines, :mod:`mbd_core.kernels.splines`)
    load_body (n_l,), load_off (n_l + 1,), knot_t (n_k,) s, knot_coef (n_k, 4, 6).
Bushings (:func:`mbd_core.kernels.forces._bushings`)
    bush_a, bush_b (n_u,); bush_p_a, bush_p_b (n_u, 3) m in each body's frame; bush_q_ref (n_u, 4)
    relative orientation q_a⁻¹ q_b at rest; bush_k (n_u, 6) N/m, N·m/rad; bush_c (n_u, 6).
Drag of the surrounding fluid (:func:`mbd_core.kernels.forces._drag`)
    drag_body (n_d,) int64; drag_c (n_d, 2): c₁ N·s/m and c₂ N·s²/m² of F = −(c₁ + c₂|v|) v.
Unbalances (:mod:`mbd_core.kernels.unbalance`; n_u of them)
    unb_body (n_u,) int64; unb_point (n_u, 3) m, body frame; unb_kg_m (n_u, 3) kg·m, body frame;
    unb_disp (n_u, 3, M) m/√kg, the mode shapes at the point (zero on a rigid body).
Squeeze-film dampers (:mod:`mbd_core.kernels.squeeze_film`; n_f of them)
    sfd_a (journal), sfd_b (housing) (n_f,) int64; sfd_p_a, sfd_p_b (n_f, 3) m the journal and bore
    centres in their bodies' frames; sfd_axis (n_f, 3) the bore axis, housing frame; sfd_clearance
    (n_f,) m; sfd_eps_max (n_f,) the tables' end; sfd_table_off (n_f + 1,) int64 into sfd_table
    (Σ n_ε n_ψ, 2) N·s/m; sfd_table_size (n_f, 2) int64 (n_ε, n_ψ).
Contact pairs (body a: the rolling element; b: the ring, cage or other ball)
    pair_type, pair_a, pair_b, pair_geom (index into the geometry of its type) (n_c,) int64;
    pair_law (n_c,) int64, pair_k (n_c,) N/m^n (per slice for rollers), pair_n, pair_c N·s/m,
    pair_dmax m; pair_fric (n_c,) int64, pair_fric_p (n_c, 4); pair_radius, pair_radius_b,
    pair_length (n_c,) m; pair_aux (n_c, 2) (roller end: end sign, edge radius m);
    pair_slice_off (n_c + 1,) into slice_drop (n_s,) m; pair_delta_max (n_c,) m (divergence bound);
    pair_strips (n_c,) int64 strips of the traction over a ball contact's ellipse (0: at its centre) and
    pair_semi_major (n_c,) m/N^(1/3), a = pair_semi_major·F_n^(1/3), and pair_strip_curv (n_c,) 1/m, κ of
    the curved contact surface z = κ·y² (:mod:`mbd_core.kernels.strip_traction`).
Grooves (ball–groove)
    groove_rc, groove_zc, groove_r (n_g,) m; groove_h_off, groove_dr_off (n_g + 1,) into the
    undulation h(θ) and radial offset Δr(θ) tables groove_h, groove_dr, m.
Raceways and ribs of rollers: race_kind (n_r,) int64, race_value (n_r,) m.
Cage pockets: pocket_kind (n_p,) int64, pocket_angle rad, pocket_r m, pocket_z m,
    pocket_clearance m.
Gravity: gravity (3,) m/s², world (already in body_force for rigid bodies; modal bodies get their
    weight from their invariants, :mod:`mbd_core.kernels.modal_step`).
Modal bodies (n_mb of them, n_η modal coordinates in all, M the largest number of modes of one body;
    :mod:`mbd_core.kernels.modal_step`)
    body_modal (n_b,) int64, the modal index of a body or −1; modal_body (n_mb,) its body index;
    modal_off (n_mb + 1,) into η; modal_frame_free (n_mb, 6) int64 as body_free for the reference
    frame (the rigid arrays hold such a body with body_free = 0); modal_implicit (n_mb,) int64, 1 to
    integrate −Kη − Dη̇ by the trapezoidal rule; modal_unit (n_mb,) int64, 1 when I6 is the identity;
    modal_omega2 (n_η,) 1/s², modal_damp (n_η,) 2ζω 1/s; invariants zero-padded to M modes:
    modal_mass (n_mb,) kg, modal_I2 (n_mb, 3), modal_I3/modal_I4 (n_mb, 3, M), modal_I5 (n_mb, 3, M, M),
    modal_I6 (n_mb, M, M), modal_I7 (n_mb, 3, 3), modal_I8 (n_mb, 3, 3, M), modal_I9 (n_mb, 3, 3, M, M)
    (units of :class:`cms_reduction.invariants.Invariants`).
Flexible grooves: groove_modal (n_g,) int64 modal index of the groove's ring or −1; groove_periodic
    (n_g,) int64; groove_samp_off (n_g + 1,) into the raceway samples samp_theta (n_s,) rad,
    samp_point (n_s, 3) m (ring frame), samp_disp and samp_rot (n_s, 3, M) m/√kg and rad/√kg
    (:class:`cms_reduction.sampling.RacewaySample`).
Flexible roller raceways and ribs (:mod:`mbd_core.kernels.roller_slices`, a (θ, s) grid of n_c circles
    of n_θ samples each): race_modal (n_r,) int64 modal index of the surface's ring or −1 (a rigid
    surface, or one on a modal ring that is not sampled); race_periodic (n_r,) int64; race_samp_off
    (n_r + 1,) into samp_*, circle after circle (circle j of surface r starts at race_samp_off[r] + j n_θ,
    every circle with the angles of the first); race_circle_off (n_r + 1,) into race_circle_s (n_sc,) m,
    the ascending coordinate s of each circle across the surface (z on a cylinder, r on a plane, ring frame).
Flexible cage pockets: pocket_modal (n_p,) int64 modal index of the pocket's cage or −1; pocket_samp
    (n_p,) int64 row in samp_* of the pocket's leading wall sample (the trailing wall's is the next row;
    −1 for a rigid pocket).
Every one of these tables is empty, and every index −1, in a model without sampled surfaces or pockets.
Bound of the sampled surfaces' motion: modal_disp_max, modal_rot_max (n_η,) the largest |D_s,k| m/√kg
    and |Ω_s,k| rad/√kg of each modal coordinate k over the samples s of its body (zero for a body
    without samples).
"""

from __future__ import annotations

import hashlib
from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from ..kernels.strip_traction import strip_table

MODEL_FIELDS = (
    "body_mass body_inertia body_free body_force body_fric_implicit "
    "load_body load_off knot_t knot_coef "
    "bush_a bush_b bush_p_a bush_p_b bush_q_ref bush_k bush_c drag_body drag_c unb_body unb_point unb_kg_m unb_disp "
    "sfd_a sfd_b sfd_p_a sfd_p_b sfd_axis sfd_clearance sfd_eps_max sfd_table_off sfd_table_size sfd_table "
    "pair_type pair_a pair_b pair_geom pair_law pair_k pair_n pair_c pair_dmax pair_fric pair_fric_p "
    "pair_radius pair_radius_b pair_length pair_aux pair_slice_off slice_drop pair_delta_max pair_strips pair_semi_major pair_strip_curv "
    "groove_rc groove_zc groove_r groove_h_off groove_h groove_dr_off groove_dr "
    "race_kind race_value "
    "pocket_kind pocket_angle pocket_r pocket_z pocket_clearance "
    "gravity body_modal modal_body modal_off modal_frame_free modal_implicit modal_unit modal_omega2 modal_damp "
    "modal_mass modal_I2 modal_I3 modal_I4 modal_I5 modal_I6 modal_I7 modal_I8 modal_I9 "
    "groove_modal groove_periodic groove_samp_off samp_theta samp_point samp_disp samp_rot "
    "race_modal race_periodic race_samp_off race_circle_off race_circle_s pocket_modal pocket_samp "
    "modal_disp_max modal_rot_max"
)
ModelArrays = namedtuple("ModelArrays", MODEL_FIELDS)

#: Scratch arrays of one force evaluation. body_f/body_t (n_b, 3) world force N / moment N·m;
#: contact_* (n_c,) outputs: fn N (sum over slices/points), delta m (largest), slip m/s (at the
#: most loaded point), ft N (sum of friction magnitudes), angle rad (atan2(n_axial, n_radial) of
#: the normal in the ring's frame), theta rad (ball angle on its groove); contact_point (n_c, 3) the
#: contact point, world m, and contact_normal (n_c, 3) the unit normal of the force on the element
#: (body a), world: for a pair of several points (roller slices, pocket walls) those of its most loaded
#: point (like slip and angle), for a pair without load those of its deepest point; energy (2,) J: contact
#: and bushing potential; type_count (5,) the number of pairs of each kind; modal_f (n_η,) the
#: contacts' modal forces, √kg·m/s²; the modal_* rest is scratch of the modal step (M the largest
#: number of modes of a body): modal_u, modal_u0, modal_rhs, modal_h, modal_b (6 + M,), modal_sel
#: (6 + M,) int64, modal_vec (4, 3), modal_eta (M,), modal_s (3,); per modal body, the terms at the η
#: they were formed for (kept while η stays, :mod:`mbd_core.kernels.modal_step`): modal_eta_at (n_mb, M),
#: modal_level (n_mb,) int64 (0 none, 2 η-terms, 3 and M, 4 and its factor), modal_S (n_mb, 3),
#: modal_J (n_mb, 3, 3), modal_G (n_mb, 3, 3, M), modal_I4e (n_mb, 3, M) (:func:`mbd_core.kernels.modal.eta_terms`),
#: modal_M (n_mb, 6 + M, 6 + M) M(η), modal_L (n_mb, 6 + M, 6 + M) the Cholesky factor of its block of
#: integrated components, modal_nfac (n_mb,) int64 that block's size, modal_fac_h (n_mb,) s the half step of
#: the implicit modes' matrix M + (h/2) C + (h/2)² K it factors (0: M); modal_c (n_η,) 1/s the damping 2ζω
#: of implicit modes at the step and modal_dinv (n_η,) 1/(1 + (h/2) c + (h/2)² ω²), modal_imp_h (n_mb,) s the
#: half step they were formed for (:mod:`mbd_core.kernels.modal_step`).
#: Sampled surfaces of modal bodies (:mod:`mbd_core.kernels.forces`): flex_row (FLEX_ROWS,) int64 the
#: cached sample rows, flex_field (FLEX_ROWS, 18) their D η, Ω η, D η̇, Ω η̇ and gathered force and
#: moment on the ring (ring frame); flex_corner (4, 2) int64 row and cache slot, flex_weight (4,) the
#: interpolation weights of one contact point; groove_rows (4, 3) D_i0 η, D_i1 η, Ω_i0 η, Ω_i1 η of the two
#: samples around a ball on a modal ring's groove. Implicit friction (:mod:`mbd_core.kernels.explicit`):
#: fric_c (n_b, 6, 6) each body's friction damping matrix, world (v, ω) (blocks N·s/m, N·s, N·m·s);
#: fric_v (n_b, 6) the velocity (v world, ω body) at which the forces were evaluated; fric_pts (n_f, 12)
#: the contact points with friction on such a body (a, b, secant coefficient N·s/m, normal, world
#: point m, pair, F_n N, slip speed m/s; n_f = 0 in a model without them), fric_n (1,) int64 how
#: many; fric_a (6, 6), fric_r (6,), fric_g (6,), fric_rot (3, 3), fric_idx (6,) int64 scratch.
#: Open contacts on sampled surfaces (:func:`mbd_core.kernels.forces.compute_forces`): flex_skip (2,)
#: int64, [0] 1 when the caller allows a step to skip the surface deformation of a contact whose
#: rigid-geometry gap exceeds the surface's motion bound, [1] 1 while the current evaluation does
#: (set by the explicit step loop on steps that are not recorded); flex_bound (n_mb, 4) per modal
#: body: the bound Σ|η_k| max|D_k| m and Σ|η_k| max|Ω_k| rad of this evaluation (inf when not
#: skipping), and the running counts of surface contacts checked and skipped. strip_each (max strips, 5) the
#: strips of one ball contact (:func:`mbd_core.kernels.strip_traction.strip_traction_forces`); strip_table
#: (max strips, 2) the load centroid (units of a) and load share of each strip of the largest strip count
#: (:func:`mbd_core.kernels.strip_traction.strip_table`).
WorkArrays = namedtuple(
    "WorkArrays",
    "body_f body_t contact_fn contact_delta contact_slip contact_ft contact_angle contact_theta contact_point "
    "contact_normal energy "
    "load pi center axis point slice_delta slice_point slice_normal type_count "
    "modal_f modal_u modal_u0 modal_rhs modal_h modal_b modal_sel modal_vec modal_eta modal_s modal_eta_at "
    "modal_level modal_S modal_J modal_G modal_I4e modal_M modal_L modal_nfac modal_fac_h modal_dinv modal_c "
    "modal_imp_h "
    "flex_row flex_field flex_corner flex_weight groove_rows fric_c fric_v fric_pts fric_n fric_a fric_r fric_g "
    "fric_rot fric_idx flex_skip flex_bound strip_each strip_table",
)
FLEX_ROWS = 32

#: Buffers for k samples: t (k,), q (k, n_b, 7), v (k, n_b, 6), eta and eta_dot (k, n_η), contact
#: outputs (k, n_c), contact point and normal (k, n_c, 3) float32 (µm resolution on a 7 m ring; they
#: serve to rebuild force vectors, not to integrate).
RecordBuffers = namedtuple("RecordBuffers", "t q v eta eta_dot fn delta slip ft angle theta point normal")
RECORDED_CONTACT_FIELDS = ("fn", "delta", "slip", "ft", "angle", "theta", "point", "normal")
#: the recorded contact fields with a vector per contact
VECTOR_CONTACT_FIELDS = ("point", "normal")


@dataclass(frozen=True)
class Model:
    """A finalized multibody model: flat arrays plus the names that make results readable.

    Build it with :class:`mbd_core.multibody.ModelBuilder`; it does not change afterwards.

    Attributes
    ----------
    arrays : ModelArrays
        Everything the kernels need (see the module docstring).
    body_names, pair_names : tuple of str
    pair_kinds : tuple of str
        "ball_groove", "ball_ball", "roller_raceway", "roller_rib" or "element_pocket".
    gravity_m_s2 : (3,) float
    damper_names : tuple of str
        The squeeze-film dampers, in the order of the ``sfd_*`` arrays.
    """

    arrays: ModelArrays
    body_names: tuple[str, ...]
    pair_names: tuple[str, ...]
    pair_kinds: tuple[str, ...]
    gravity_m_s2: np.ndarray = field(default_factory=lambda: np.zeros(3))
    damper_names: tuple[str, ...] = ()

    @property
    def n_bodies(self) -> int:
        return len(self.body_names)

    @property
    def n_pairs(self) -> int:
        return len(self.pair_names)

    @property
    def n_modal(self) -> int:
        """Number of modal coordinates of all modal bodies."""
        return int(self.arrays.modal_off[-1])

    def modal_slice(self, name: str) -> slice:
        """The modal coordinates of the modal body called ``name`` within η."""
        i = self.body(name)
        j = int(self.arrays.body_modal[i])
        if j < 0:
            raise KeyError(f"body {name!r} is rigid: it has no modal coordinates")
        return slice(int(self.arrays.modal_off[j]), int(self.arrays.modal_off[j + 1]))

    def body(self, name: str) -> int:
        """Index of the body called ``name``."""
        try:
            return self.body_names.index(name)
        except ValueError:
            raise KeyError(f"no body named {name!r}") from None

    def pairs_of(self, kind: str) -> np.ndarray:
        """Indices of the contact pairs of one kind."""
        return np.array([i for i, k in enumerate(self.pair_kinds) if k == kind], dtype=np.int64)

    def free_mask(self) -> np.ndarray:
        """(n_b, 6) bool: integrated velocity components (a modal body's: its frame's, ``modal_frame_free``)."""
        a = self.arrays
        free = a.body_free.astype(bool)
        free[a.modal_body] = a.modal_frame_free.astype(bool)
        return free


@dataclass
class State:
    """Restartable state: time t (s), q (n_b, 7) positions m and quaternions, v (n_b, 6) m/s, rad/s,
    modal coordinates eta (n_η,) √kg and rates eta_dot (n_η,) √kg/s of the modal bodies."""

    t: float
    q: np.ndarray
    v: np.ndarray
    eta: np.ndarray = field(default_factory=lambda: np.zeros(0))
    eta_dot: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def copy(self) -> "State":
        return State(float(self.t), self.q.copy(), self.v.copy(), self.eta.copy(), self.eta_dot.copy())


def make_work(model: Model) -> WorkArrays:
    """Preallocate the scratch arrays of one force evaluation."""
    a = model.arrays
    nb, nc = model.n_bodies, model.n_pairs
    ns = int(np.max(np.diff(a.pair_slice_off))) if nc else 0
    ns = max(ns, 1)
    n6 = 6 + a.modal_I6.shape[1]
    nm = a.modal_body.size
    return WorkArrays(
        body_f=np.zeros((nb, 3)), body_t=np.zeros((nb, 3)),
        contact_fn=np.zeros(nc), contact_delta=np.zeros(nc), contact_slip=np.zeros(nc),
        contact_ft=np.zeros(nc), contact_angle=np.zeros(nc), contact_theta=np.zeros(nc),
        contact_point=np.zeros((nc, 3)), contact_normal=np.zeros((nc, 3)),
        energy=np.zeros(2), load=np.zeros(6), pi=np.zeros(3), center=np.zeros(3), axis=np.zeros(3),
        point=np.zeros(3), slice_delta=np.zeros(ns), slice_point=np.zeros((ns, 3)),
        slice_normal=np.zeros((ns, 3)),
        type_count=np.bincount(a.pair_type, minlength=5).astype(np.int64),
        modal_f=np.zeros(model.n_modal),
        modal_u=np.zeros(n6), modal_u0=np.zeros(n6), modal_rhs=np.zeros(n6), modal_h=np.zeros(n6),
        modal_b=np.zeros(n6), modal_sel=np.zeros(n6, dtype=np.int64), modal_vec=np.zeros((4, 3)),
        modal_eta=np.zeros(n6 - 6), modal_s=np.zeros(3), modal_eta_at=np.zeros((nm, n6 - 6)),
        modal_level=np.zeros(nm, dtype=np.int64), modal_S=np.zeros((nm, 3)), modal_J=np.zeros((nm, 3, 3)),
        modal_G=np.zeros((nm, 3, 3, n6 - 6)), modal_I4e=np.zeros((nm, 3, n6 - 6)), modal_M=np.zeros((nm, n6, n6)),
        modal_L=np.zeros((nm, n6, n6)), modal_nfac=np.zeros(nm, dtype=np.int64),
        modal_fac_h=np.zeros(nm), modal_dinv=np.zeros(model.n_modal), modal_c=np.zeros(model.n_modal),
        modal_imp_h=np.zeros(nm),
        flex_row=np.zeros(FLEX_ROWS, dtype=np.int64), flex_field=np.zeros((FLEX_ROWS, 18)),
        flex_corner=np.zeros((4, 2), dtype=np.int64), flex_weight=np.zeros(4), groove_rows=np.zeros((4, 3)),
        fric_c=np.zeros((nb, 6, 6)), fric_v=np.zeros((nb, 6)),
        # at most: every slice, two points per other pair (roller ends, pocket walls), every strip
        fric_pts=np.zeros((a.slice_drop.size + 2 * nc + int(a.pair_strips.sum()) if a.body_fric_implicit.any() else 0,
                           12)),
        fric_n=np.zeros(1, dtype=np.int64), fric_a=np.zeros((6, 6)), fric_r=np.zeros(6), fric_g=np.zeros(6),
        fric_rot=np.zeros((3, 3)), fric_idx=np.zeros(6, dtype=np.int64),
        flex_skip=np.zeros(2, dtype=np.int64), flex_bound=np.zeros((a.modal_body.size, 4)),
        strip_each=np.zeros((max(int(a.pair_strips.max(initial=0)), 1), 5)),
        strip_table=_strip_table(max(int(a.pair_strips.max(initial=0)), 1)),
    )


def _strip_table(n_strips: int) -> np.ndarray:
    out = np.zeros((n_strips, 2))
    strip_table(n_strips, out)
    return out


def make_record_buffers(model: Model, n_samples: int) -> RecordBuffers:
    """Buffers for ``n_samples`` recorded samples."""
    nb, nc = model.n_bodies, model.n_pairs
    k = max(int(n_samples), 1)
    return RecordBuffers(
        t=np.zeros(k), q=np.zeros((k, nb, 7)), v=np.zeros((k, nb, 6)),
        eta=np.zeros((k, model.n_modal)), eta_dot=np.zeros((k, model.n_modal)),
        **{name: (np.zeros((k, nc, 3), np.float32) if name in VECTOR_CONTACT_FIELDS else np.zeros((k, nc)))
           for name in RECORDED_CONTACT_FIELDS},
    )


def model_fingerprint(model: Model) -> dict:
    """SHA-256 (hex, 16 digits) of every model array (dtype, shape and bytes) and of the name lists.

    Two models with equal fingerprints integrate identically; comparing two fingerprints with
    :func:`fingerprint_differences` names the arrays that differ.
    """
    out = {}
    for name, value in zip(model.arrays._fields, model.arrays):
        a = np.ascontiguousarray(value)
        h = hashlib.sha256(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
        out[name] = h.hexdigest()[:16]
    for name in ("body_names", "pair_names", "pair_kinds"):
        out[name] = hashlib.sha256("\x00".join(getattr(model, name)).encode()).hexdigest()[:16]
    return out


def fingerprint_differences(recorded: dict, present: dict) -> list[str]:
    """Names of the entries in which two :func:`model_fingerprint` results differ (sorted)."""
    return sorted(k for k in set(recorded) | set(present) if recorded.get(k) != present.get(k))
