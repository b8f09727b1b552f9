"""The examples run as scripts and are checked here (each example computes at module level).

The two heavy ones run at their ``--quick`` size (FLEXBEARING_EXAMPLE_QUICK=1: a mesh twice as
coarse, the same loads, supports, modes and run); the checks below hold at any mesh (load sums,
equilibrium, load carried after the ramp), and benchmarks/bench_examples.py makes them at the
full size.
"""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _run(name, monkeypatch, tmp_path):
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_OUT", str(tmp_path / name))
    # the heavy examples at their quick size (coarser race mesh, same loads, supports and history);
    # their full size is run and checked by benchmarks/bench_examples.py
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_QUICK", "1")
    monkeypatch.setenv("FLEXBEARING_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_QUICK", "1")
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_slewing_race_static(monkeypatch, tmp_path):
    ex = _run("slewing_race_static", monkeypatch, tmp_path)
    # each ball's Hertz patch carries Q = W/(Z sin α) along the local groove normals (unit vectors,
    # weights summing to one), W = 68.9 t × 9.81 m/s²
    Q = 68.9e3 * 9.81 / (16 * math.sin(math.radians(60.0)))
    assert np.linalg.norm(ex.forces_N, axis=1).sum() == pytest.approx(16 * Q, rel=1e-12)
    # static equilibrium: the bolt reactions balance the ball loads
    assert ex.reaction_N == pytest.approx(-ex.applied_N, abs=1e-9 * np.abs(ex.applied_N).max())
    assert (tmp_path / "slewing_race_static" / "race.vtu").stat().st_size > 0
    assert (tmp_path / "slewing_race_static" / "von_mises.png").stat().st_size > 0


def test_ball_bearing_dynamics(monkeypatch, tmp_path):
    ex = _run("ball_bearing_dynamics", monkeypatch, tmp_path)
    # friction drives the cage up to the no-slip speed ω_i (1 − γ)/2 (Harris & Kotzalas, Essential
    # Concepts, eq. 8.24) within 1 % once spun up; the cage then swings about it (±1.8 %, period
    # about 30 ms, lightly damped), so the mean is taken from 10 ms on (over two swings)
    after = ex.run["t"] > 0.01
    assert np.mean(ex.cage_speed_rad_s[after]) == pytest.approx(ex.theory.cage_speed_rad_s, rel=0.01)
    assert ex.run["status"] == "complete"
    assert (tmp_path / "ball_bearing_dynamics" / "cage_speed.png").stat().st_size > 0


def test_flexible_race_dynamics(monkeypatch, tmp_path):
    ex = _run("flexible_race_dynamics", monkeypatch, tmp_path)
    # after the moment has ramped up (0.12 s) the balls carry the dead load and the moment: axial
    # components Q sin α (recorded contact angles) sum to W, their moment about x to M (2 %: the top
    # race still swings a little on its contacts)
    end = ex.t > 0.15
    axial = ex.ball_load_N[end] * np.sin(ex.run["angle"][end][:, ex.fixed])
    y = ex.run["q"][end][:, list(ex.balls.elements), 1]
    assert axial.sum(axis=1) == pytest.approx(np.full(end.sum(), ex.WEIGHT_N), rel=0.01)
    assert np.abs((axial * y).sum(axis=1)) == pytest.approx(np.full(end.sum(), ex.MOMENT_NM), rel=0.02)
    # the race's stress peaks once the moment is on
    assert ex.worst.time_s > 0.1
    assert (tmp_path / "flexible_race_dynamics" / "stress" / "stress.pvd").stat().st_size > 0
    assert (tmp_path / "flexible_race_dynamics" / "race_worst_0000.png").stat().st_size > 0


def _axial_ball_load(row, F_a: float, Z: int) -> tuple[float, float]:
    """(Q, α) of each ball of ``Z`` equally loaded ball pairs under the axial load ``F_a``, solved
    here independently: the moving groove centre moves axially by δ_a, so the centre distance is
    s = (A·cos α0 − P_d/2, A·sin α0 + δ_a) (radial, axial), δ = |s| − A, α = atan2(s_z, s_r),
    Q = K·δ^1.5 and Z·Q·sin α = F_a (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., ch. 7,
    thrust load on a ball bearing; the clearance as in ch. 2). K is the row's Hertz constant."""
    from scipy.optimize import brentq

    A, a0, c = row.curvature_centre_distance_m, row.contact_angle_rad, 0.5 * row.diametral_clearance_m
    K = row.contact_stiffness()

    def geometry(d_a):
        s_r, s_z = A * math.cos(a0) - c, A * math.sin(a0) + d_a
        delta = max(math.hypot(s_r, s_z) - A, 0.0)
        return K * delta**1.5, math.atan2(s_z, s_r)

    d_a = brentq(lambda d: Z * geometry(d)[0] * math.sin(geometry(d)[1]) - F_a, 0.0, A, xtol=1e-16, rtol=1e-14)
    return geometry(d_a)


def test_bearing_files(monkeypatch, tmp_path):
    """The example description files under a pure axial load F_a: every loaded ball carries
    Q = F_a/(Z·sin α) with α the loaded contact angle of the Hertz approach (independent solve
    above), and every loaded thrust roller F_a/Z, its slices q_k = (c_L/n_s)·(δ_a − gap − drop_k)^(10/9)
    with drop_k of the ISO/TS 16281 logarithmic profile, and the crossed rollers of each diagonal alike,
    evaluated here (1e-8 relative: the solver's equilibrium tolerance is 1e-10)."""
    from scipy.optimize import brentq

    ex = _run("bearing_files", monkeypatch, tmp_path)
    F = ex.AXIAL_N
    cases = {  # name: (rows that carry the load, the diagonal of four-point rows)
        "double-angular-contact": (["balls (1)"], None),  # back-to-back: only the row at −z, pushed +z
        "pitch-bearing-four-point": (["balls"], 0),  # the +α diagonal of every ball
        "double-four-point": (["balls (1)", "balls (2)"], 0),  # both rows alike
    }
    for name, (loaded, diagonal) in cases.items():
        res, bearing = ex.axial[name], ex.descriptions[name].bearing
        Z = sum(bearing.rows[[r.name for r in bearing.rows].index(n)].n_balls for n in loaded)
        for r, row in zip(res.rows, bearing.rows):
            Q = r.load_N if diagonal is None else r.contact_load_N[:, diagonal]
            angle = r.contact_angle_rad if diagonal is None else r.contact_angles_rad[:, diagonal]
            if r.name not in loaded:
                assert r.load_N.max() == 0.0, (name, r.name)
                continue
            Q_ref, alpha_ref = _axial_ball_load(row, F, Z)
            assert Q == pytest.approx(np.full(len(Q), Q_ref), rel=1e-8), (name, r.name)
            assert angle == pytest.approx(np.full(len(Q), alpha_ref), rel=1e-8), (name, r.name)
            assert Q_ref == pytest.approx(F / (Z * math.sin(alpha_ref)), rel=1e-12)
    # radial + thrust roller bearing: the front thrust row alone (towards +z), each roller F_a/Z
    res, rows = ex.axial["radial-thrust-roller"], ex.descriptions["radial-thrust-roller"].bearing.rows
    front, ns = rows[1], rows[1].n_slices
    L = front.roller_length_m
    x = -0.5 * L + (np.arange(ns) + 0.5) * L / ns
    drop = 0.00035 * front.roller_diameter_m * np.log(1.0 / (1.0 - (2.0 * x / L) ** 2))
    q = lambda d_a: front.contact_stiffness() / ns * np.clip(d_a - front.gap_m - drop, 0.0, None) ** (10.0 / 9.0)
    d_a = brentq(lambda d: q(d).sum() - F / front.n_rollers, front.gap_m, 1e-3, xtol=1e-18, rtol=1e-14)
    assert res.displacement[2] == pytest.approx(d_a, rel=1e-8)
    assert res.rows[1].load_N == pytest.approx(np.full(front.n_rollers, F / front.n_rollers), rel=1e-8)
    assert res.rows[1].slice_load_N == pytest.approx(np.tile(q(d_a), (front.n_rollers, 1)), rel=1e-7)
    assert res.rows[0].load_N.max() == 0.0 and res.rows[2].load_N.max() == 0.0
    # crossed roller bearing (preloaded): pushed along +z the ring moves by z alone (the rollers of each
    # diagonal are equally spaced, their radial components cancel); a slice of a +α0 roller approaches
    # by z·sin α0 − g − drop_k, of a −α0 roller by −z·sin α0 − g − drop_k (g = (P_d/2)·cos α0 < 0), and
    # (Z/2)·sin α0·(Q₊ − Q₋) = F_a
    res, row = ex.axial["crossed-roller"], ex.descriptions["crossed-roller"].bearing.rows[0]
    a, ns, L = row.contact_angle_rad, row.n_slices, row.roller_length_m
    x = -0.5 * L + (np.arange(ns) + 0.5) * L / ns
    drop = 0.00035 * row.roller_diameter_m * np.log(1.0 / (1.0 - (2.0 * x / L) ** 2))
    gap = 0.5 * (-0.02e-3) * math.cos(a)  # the file's diametral clearance
    q = lambda z, s: row.contact_stiffness() / ns * np.clip(s * z * math.sin(a) - gap - drop, 0.0, None) ** (10 / 9)
    Q = lambda z: (q(z, 1.0).sum(), q(z, -1.0).sum())
    z = brentq(lambda z: row.n_rollers / 2 * math.sin(a) * (Q(z)[0] - Q(z)[1]) - F, 0.0, 1e-3, xtol=1e-18, rtol=1e-14)
    assert res.displacement[2] == pytest.approx(z, rel=1e-8)
    assert res.rows[0].load_N[0::2] == pytest.approx(np.full(row.n_rollers // 2, Q(z)[0]), rel=1e-8)
    assert res.rows[0].load_N[1::2] == pytest.approx(np.full(row.n_rollers // 2, Q(z)[1]), rel=1e-8)
    # the outputs of the files' own loads: the pitch bearing's three load cases
    out = tmp_path / "bearing_files" / "pitch-bearing-four-point"
    assert len(ex.results["pitch-bearing-four-point"]) == 3
    assert (out / "contact_angles.png").stat().st_size > 10_000 and (out / "element_loads.csv").stat().st_size > 0


def test_modal_rings(monkeypatch, tmp_path):
    """The pitch bearing with modal rings (quick size): every load case in equilibrium (≤ 1e-9), and
    each point of the modal-ring limiting load curve, re-solved here, puts the most loaded contact
    at the ISO 76 limit p0 = 4200 MPa (s0 = 1, ball on steel raceway: ISO 76:2006, 4.2 GPa) to 1e-6."""
    from mbd_core.quasistatic import RingLoad
    from mbd_core.quasistatic.contacts import contact_sets

    ex = _run("modal_rings", monkeypatch, tmp_path)
    assert ex.modal.flexible
    assert all(r.equilibrium_error <= 1e-9 for r in ex.modal_results)
    curve = ex.curve_modal
    for k in np.flatnonzero(curve.carried)[:3]:
        dist = ex.modal.solve(RingLoad(Fx_N=curve.radial_N, Fz_N=float(curve.axial_N[k]), My_Nm=float(curve.moment_Nm[k])))
        p0 = max(float(np.max(s.max_pressure_Pa)) for s in contact_sets(ex.desc.bearing, dist) if len(s.max_pressure_Pa))
        assert p0 == pytest.approx(4200e6, rel=1e-6)
    assert (tmp_path / "modal_rings" / "limiting_load_curve.png").is_file()


def test_step_ring(monkeypatch, tmp_path):
    ex = _run("step_ring", monkeypatch, tmp_path)
    # acceptance of the bearing files: equilibrium residual ≤ 1e-9, with the STEP ring too
    for res in ex.results.values():
        assert res.equilibrium_error <= 1e-9
    # reference: OpenCASCADE's volume of the geared, drilled solid × density; quadratic tetrahedra
    # on its curved faces (holes, rings) hold it to 1e-3 (measured 7e-4 at 45 mm, 6e-4 at 30 mm)
    assert ex.mass_kg == pytest.approx(ex.solid.volume_m3 * ex.m.material.density_kg_m3, rel=1e-3)
    # the section names the raceway and the bolted face on the solid; teeth and hole walls are "other"
    assert {"raceway balls", "bottom", "other"} <= set(ex.ring.ring.facet_sets)
    # the solid carries the gear: more volume than its revolved section, less the holes
    section = ex.m.profile.revolved_properties(1.0)["mass_kg"]
    assert ex.solid.volume_m3 > section - ex.BOLTS * math.pi * (ex.HOLE_M / 2) ** 2 * 0.07


def test_high_speed_ball_bearing(monkeypatch, tmp_path):
    # a hybrid turbocharger-size bearing under spring preload at 10 000 and 200 000 rev/min, started at
    # its quasi-static high-speed equilibrium: both runs stay bounded (no divergence, all recorded
    # states finite), and the mean dynamic outer-contact loads lie within the quasi-static race-control
    # bracket (inner to outer control) and within 2 % of the outer-control solution (measured 0.1 % and 1.4 %; the step the
    # guard picks: 2.4e-7 s and 4.2e-8 s)
    monkeypatch.setenv("FLEXBEARING_EXAMPLE_RPM", "10000,200000")
    ex = _run("high_speed_ball_bearing", monkeypatch, tmp_path)
    from mbd_core.quasistatic import RingLoad, solve_high_speed_row
    for r in ex.rows:
        assert r["status"] == "complete", r
        assert r["outer_N"] == pytest.approx(r["quasi_static_outer_N"], rel=0.02)
        inner_control = solve_high_speed_row(ex.row, RingLoad(Fz_N=ex.preload_N), r["speed_rpm"] * math.pi / 30,
                                             control="inner")
        # (0.5 % beyond it allowed: at 10 000 rev/min the bracket is 0.1 % wide)
        assert 0.995 * inner_control.outer_load_N.mean() < r["outer_N"] < 1.005 * r["quasi_static_outer_N"]
    steps = [r["timestep_s"] for r in ex.rows]
    assert steps[1] < steps[0]               # the guard shortens the step as the speed grows
    assert (tmp_path / "high_speed_ball_bearing" / "steps.png").stat().st_size > 0


def test_rotor_campbell(monkeypatch, tmp_path):
    ex = _run("rotor_campbell", monkeypatch, tmp_path)
    # the lightly damped unbalance response peaks at a forward critical speed, found independently as
    # the crossing of a forward whirl with the running speed in the Campbell diagram; within the
    # run-up's speed step (the damped peak moves by O(ζ²) = 0.04 %)
    step_rpm = (ex.run_up_rad_s[1] - ex.run_up_rad_s[0]) * 30 / math.pi
    assert np.min(np.abs(ex.forward_critical_rpm - ex.peak_rpm)) <= step_rpm
    # the modes have integer angular orders: on this coarse mesh (4 mm on 44 mm wheels) a mode of one
    # order mixes with one of another only where they meet in the spinning frame; few are reported
    # mixed (measured: 1 of the 640 points of the 8 lowest modes)
    mixed = np.isnan(ex.diagram.fixed_Hz[1:])
    assert mixed.mean() < 0.02
    assert np.all(np.abs(ex.diagram.order[1:][~mixed] - np.round(ex.diagram.order[1:][~mixed])) <= 0.2)
    assert (tmp_path / "rotor_campbell" / "campbell.png").stat().st_size > 0
    assert (tmp_path / "rotor_campbell" / "unbalance.png").stat().st_size > 0


def test_unbalance_preload(monkeypatch, tmp_path):
    ex = _run("unbalance_preload", monkeypatch, tmp_path)
    loose, preloaded = ex.cases
    # the quasi-static high-speed solution under the unbalance force frozen in place (the reference)
    # leaves balls without load at 10 N axial and none at 300 N (79 N the least)
    assert loose["quasi_min_N"] == 0.0 and preloaded["quasi_min_N"] > 50.0
    # the dynamic run agrees: without preload the balls lose contact periodically (64 % of the time
    # measured), with preload never
    assert loose["unloaded_share"] > 0.2 and preloaded["unloaded_share"] == 0.0
    # the peaks overshoot the quasi-static ones by the lightly damped ring's ringing (27 %, 23 % measured)
    for c in ex.cases:
        assert c["quasi_max_N"] <= c["max_N"] <= 1.4 * c["quasi_max_N"]
    assert (tmp_path / "unbalance_preload" / "ball_loads.png").stat().st_size > 0
