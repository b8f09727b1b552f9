"""Flat arrays of a finalized model: the modal bodies' invariants and samples, and small numpy helpers
(dtype casts, quaternions) of the builder."""

from __future__ import annotations

import numpy as np

def modal_arrays(bodies, grooves, surfaces, pockets) -> dict:
    """The modal-body arrays of :class:`ModelArrays` and those of the grooves, surfaces and pockets that
    deform with them (zero-padded to M modes); the samples go to samp_* in that order."""
    modal = [b.modal for b in bodies if b.modal is not None]
    n_mb = len(modal)
    M = max([d["I6"].shape[0] for d in modal] or [0])
    counts = [d["I6"].shape[0] for d in modal]

    def pad(key, shape):
        out = np.zeros((n_mb, *shape))
        for j, d in enumerate(modal):
            a = d[key]
            out[(j, *tuple(slice(0, n) for n in a.shape))] = a
        return out

    body_modal = np.full(len(bodies), -1, dtype=np.int64)
    j = 0
    for i, b in enumerate(bodies):
        if b.modal is not None:
            body_modal[i] = j
            j += 1
    samples = [g["sample"] for g in grooves]
    grids = [s["grid"] for s in surfaces]
    walls = [p["walls"] for p in pockets]
    n_s = [0 if smp is None else smp["theta"].size for smp in samples]
    n_grid = [0 if grid is None else grid["theta"].size for grid in grids]
    start = sum(n_s) + np.concatenate([[0], np.cumsum(n_grid)])
    pocket_samp = start[-1] + np.cumsum([0] + [0 if x is None else 2 for x in walls])[:-1]
    s_theta, s_point, s_disp, s_rot = [np.zeros(0)], [np.zeros((0, 3))], [np.zeros((0, 3, M))], [np.zeros((0, 3, M))]
    for smp in samples + grids + walls:
        if smp is None:
            continue
        s_theta.append(smp["theta"])
        s_point.append(smp["points"])
        for key, lst in (("disp", s_disp), ("rot", s_rot)):
            a = np.zeros((smp["theta"].size, 3, M))
            a[:, :, :smp[key].shape[2]] = smp[key]
            lst.append(a)
    disp_max, rot_max = _mode_amplitudes(body_modal, counts, [(g["ring"], x) for g, x in zip(grooves, samples)]
                                         + [(sf["ring"], x) for sf, x in zip(surfaces, grids)]
                                         + [(p["cage"], x) for p, x in zip(pockets, walls)])
    I6 = pad("I6", (M, M))
    unit = [int(np.allclose(d["I6"], np.eye(d["I6"].shape[0]), rtol=0.0, atol=1e-12)) for d in modal]
    return dict(
        body_modal=body_modal, modal_body=_i64([i for i, b in enumerate(bodies) if b.modal is not None]),
        modal_off=_i64(np.concatenate([[0], np.cumsum(counts)])),
        modal_frame_free=_i64([d["frame_free"] for d in modal]).reshape(-1, 6),
        modal_implicit=_i64([d["implicit"] for d in modal]), modal_unit=_i64(unit),
        modal_omega2=_f64(np.concatenate([d["omega2"] for d in modal] or [np.zeros(0)])),
        modal_damp=_f64(np.concatenate([d["damp"] for d in modal] or [np.zeros(0)])),
        modal_mass=_f64([d["mass"] for d in modal]), modal_I2=pad("I2", (3,)), modal_I3=pad("I3", (3, M)),
        modal_I4=pad("I4", (3, M)), modal_I5=pad("I5", (3, M, M)), modal_I6=I6, modal_I7=pad("I7", (3, 3)),
        modal_I8=pad("I8", (3, 3, M)), modal_I9=pad("I9", (3, 3, M, M)),
        groove_modal=_i64([-1 if smp is None else body_modal[g["ring"]] for g, smp in zip(grooves, samples)]),
        groove_periodic=_i64([0 if smp is None else smp["periodic"] for smp in samples]),
        groove_samp_off=_i64(np.concatenate([[0], np.cumsum(n_s)])),
        samp_theta=_f64(np.concatenate(s_theta)), samp_point=_f64(np.concatenate(s_point)),
        samp_disp=_f64(np.concatenate(s_disp)), samp_rot=_f64(np.concatenate(s_rot)),
        race_modal=_i64([-1 if grid is None else body_modal[s["ring"]] for s, grid in zip(surfaces, grids)]),
        race_periodic=_i64([0 if grid is None else grid["periodic"] for grid in grids]),
        race_samp_off=_i64(start),
        race_circle_off=_i64(np.concatenate([[0], np.cumsum([0 if x is None else x["circle_s"].size
                                                             for x in grids])])),
        race_circle_s=_f64(np.concatenate([x["circle_s"] for x in grids if x is not None] or [np.zeros(0)])),
        pocket_modal=_i64([-1 if x is None else body_modal[p["cage"]] for p, x in zip(pockets, walls)]),
        pocket_samp=_i64([-1 if x is None else r for x, r in zip(walls, pocket_samp)]),
        modal_disp_max=disp_max, modal_rot_max=rot_max,
    )


def _mode_amplitudes(body_modal, counts, sampled) -> tuple[np.ndarray, np.ndarray]:
    """Per modal coordinate k of each modal body: the largest |D_s,k| (m/√kg) and |Ω_s,k| (rad/√kg)
    over the samples s of all its sampled surfaces (``sampled``: (body index, sample or None) pairs).
    Σ_k |η_k| times them bounds how far any sampled point of the body moves and turns
    (:func:`mbd_core.kernels.forces.compute_forces`, the bound of the surface contacts)."""
    off = np.concatenate([[0], np.cumsum(counts)]).astype(int)
    disp_max, rot_max = np.zeros(off[-1]), np.zeros(off[-1])
    for body, smp in sampled:
        if smp is None:
            continue
        j = body_modal[body]
        for key, out in (("disp", disp_max), ("rot", rot_max)):
            amp = np.linalg.norm(np.asarray(smp[key]), axis=1).max(axis=0, initial=0.0)  # (modes,)
            seg = out[off[j]:off[j] + amp.size]
            np.maximum(seg, amp, out=seg)
    return disp_max, rot_max


def unbalance_arrays(unbalances, n_modes_max: int) -> dict:
    """The unb_* arrays of :class:`ModelArrays` (mode shapes zero-padded to ``n_modes_max``)."""
    disp = np.zeros((len(unbalances), 3, n_modes_max))
    for j, u in enumerate(unbalances):
        disp[j, :, :u["disp"].shape[1]] = u["disp"]
    return dict(unb_body=_i64([u["body"] for u in unbalances]), unb_point=_f64([u["point"] for u in unbalances], (-1, 3)),
                unb_kg_m=_f64([u["u"] for u in unbalances], (-1, 3)), unb_disp=_f64(disp))


def squeeze_film_arrays(dampers, q0) -> dict:
    """The ``sfd_*`` arrays of :class:`ModelArrays` from the builder's dampers (the journal's centre, the
    bore centre and axis, given in world at the start, go to the journal's and the housing's frames)."""
    tables = [d["table"] for d in dampers]
    rows = [t.scaled_N_s_m.reshape(-1, 2) for t in tables]
    return dict(
        sfd_a=_i64([d["a"] for d in dampers]), sfd_b=_i64([d["b"] for d in dampers]),
        sfd_p_a=_f64([_rotate_back(q0[d["a"]], d["journal"]) for d in dampers], (-1, 3)),
        sfd_p_b=_f64([_rotate_back(q0[d["b"]], d["center"]) for d in dampers], (-1, 3)),
        sfd_axis=_f64([_rotate(_quat_conj(q0[d["b"], 3:]), d["axis"]) for d in dampers], (-1, 3)),
        sfd_clearance=_f64([t.clearance_m for t in tables]),
        sfd_eps_max=_f64([t.max_eccentricity_ratio for t in tables]),
        sfd_table_off=_i64(np.concatenate([[0], np.cumsum([r.shape[0] for r in rows])])),
        sfd_table_size=_i64([[t.n_eps, t.n_psi] for t in tables]).reshape(-1, 2),
        sfd_table=_f64(np.concatenate(rows) if rows else np.zeros((0, 2)), (-1, 2)),
    )


def _i64(x) -> np.ndarray:
    return np.asarray(x, dtype=np.int64)


def _f64(x, shape=None) -> np.ndarray:
    """float64 array; ``shape`` (e.g. (-1, 3)) keeps empty tables two-dimensional for the kernels."""
    a = np.asarray(x, dtype=np.float64)
    return a.reshape(shape) if shape else a


def _skew(a) -> np.ndarray:
    """ã with ã b = a × b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _rotate(q, x) -> np.ndarray:
    """R(q) x for a unit quaternion (w, x, y, z)."""
    return _quat_mul(_quat_mul(q, np.concatenate([[0.0], x])), _quat_conj(q))[1:]


def _quat_conj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


def _quat_mul(p, q):
    pw, pv, qw, qv = p[0], p[1:], q[0], q[1:]
    return np.concatenate([[pw * qw - pv @ qv], pw * qv + qw * pv + np.cross(pv, qv)])


def _rotate_back(q7, point):
    """Coordinates of a world point in the frame of a body at pose q7 = (r, quaternion)."""
    qc = _quat_conj(q7[3:])
    d = np.concatenate([[0.0], np.asarray(point) - q7[:3]])
    return _quat_mul(_quat_mul(qc, d), q7[3:])[1:]
