"""Stresses over time of a modal ring: modal superposition against the full FE model, peak
history, worst instant, ParaView series and pictures.

References used below:

* The FE model's own stress recovery :func:`fem_rings.stress.nodal_stress_Pa` applied to the
  displacement Φ η(t) of the full field (linear elasticity: equal to the modal superposition up
  to round-off).
* A synthetic record with one spatial shape, η(t) = η̂ s(t), s(t) = sin(ωt) e^(−t/τ): its peak
  von Mises stress is |s(t)| times that of η̂, largest at the analytic maximum of s,
  t* = atan(ωτ)/ω (ds/dt = 0 ⇔ tan(ωt) = ωτ; first lobe, the envelope decays).
* ParaView's collection format (``.pvd``) and meshio's reader for the frames.
"""

from __future__ import annotations

import tracemalloc
import xml.etree.ElementTree as ET
from dataclasses import replace

import matplotlib.image
import meshio
import numpy as np
import pytest

from cms_reduction import (
    ReductionSpec,
    peak_von_mises_history,
    reduced_body,
    render_stress_pngs,
    stress_at,
    worst_time,
    write_stress_series,
)
from fem_rings import MeshSpec, build_model
from fem_rings.output import voigt_to_vtk_tensor
from fem_rings.profile import rectangle
from fem_rings.stress import nodal_stress_Pa, von_mises_Pa
from foundation.materials import ElasticMaterial

STEEL = ElasticMaterial("steel", 200e9, 0.3, 7850.0)
RING = rectangle("ring", 0.95, 1.05, -0.05, 0.05)
MESHES = {"hex27": MeshSpec(0.05, "hex27", n_theta=24), "tet10": MeshSpec(0.06, "tet10")}


def _model_and_body(element: str):
    """FE model and its reduced body with stress modes (6 free–free elastic modes)."""
    model = build_model(RING, MESHES[element], STEEL, use_cache=False)
    body = reduced_body(RING, MESHES[element], STEEL, ReductionSpec(n_modes=6, stress_modes=True),
                        use_cache=False)
    assert np.array_equal(model.nodes_m, body.nodes_m)  # the same mesh, so the same nodes
    return model, body


@pytest.fixture(scope="module")
def ring():
    return _model_and_body("hex27")


def _fe_stress_Pa(model, body, eta):
    """Reference: stress recovered by the FE model from the full displacement Φ η."""
    return nodal_stress_Pa(model, body.shapes @ eta)


def _random_record(n_modes: int, n_t: int, seed: int = 1):
    """A smooth record: a few sines per mode with random amplitudes (√kg) and phases."""
    rng = np.random.default_rng(seed)
    t_s = np.linspace(0.0, 0.2, n_t)
    freq_Hz = rng.uniform(5.0, 60.0, size=(3, n_modes))
    amp = rng.normal(size=(3, n_modes)) * 1e-2
    phase = rng.uniform(0.0, 2 * np.pi, size=(3, n_modes))
    eta_t = np.einsum("km,tkm->tm", amp, np.sin(2 * np.pi * freq_Hz * t_s[:, None, None] + phase))
    return t_s, eta_t


# ---------------------------------------------------------------------------------------------
# stresses at chosen times
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("element", ["hex27", "tet10"])
def test_stress_at_equals_fe_stress_of_the_modal_displacement(element):
    model, body = _model_and_body(element)
    t_s, eta_t = _random_record(body.n_modes, 21)
    # a recorded time, a time 30 % of the way from sample 7 to 8, and the last sample
    times_s = [t_s[4], t_s[7] + 0.3 * (t_s[8] - t_s[7]), t_s[-1]]
    eta_ref = [eta_t[4], 0.7 * eta_t[7] + 0.3 * eta_t[8], eta_t[-1]]
    got = stress_at(body, t_s, eta_t, times_s)
    np.testing.assert_allclose(got.eta, eta_ref, rtol=1e-12, atol=1e-15)
    for k, eta in enumerate(eta_ref):
        ref = _fe_stress_Pa(model, body, eta)
        scale = np.abs(ref).max()
        assert np.abs(got.stress_Pa[k] - ref).max() <= 1e-10 * scale
        assert np.abs(got.von_mises_Pa[k] - von_mises_Pa(ref)).max() <= 1e-10 * scale
    # nearest sample: 0.3 of a step after sample 7 → sample 7; 0.6 of a step → sample 8
    nearest = stress_at(body, t_s, eta_t, [times_s[1], t_s[7] + 0.6 * (t_s[8] - t_s[7])], method="nearest")
    np.testing.assert_array_equal(nearest.eta, eta_t[[7, 8]])


# ---------------------------------------------------------------------------------------------
# peak history and worst instant
# ---------------------------------------------------------------------------------------------
def test_peak_history_equals_brute_force_per_time(ring):
    model, body = ring
    # non-proportional record: mode 0 at 10 Hz, growing, and a smaller mode 2 at 30 Hz, so the
    # location of the peak moves round the ring (the growth makes the lobes differ: no tie)
    t_s = np.linspace(0.0, 0.1, 101)
    eta_t = np.zeros((len(t_s), body.n_modes))
    eta_t[:, 0] = 0.05 * np.sin(2 * np.pi * 10.0 * t_s) * (1.0 + 3.0 * t_s)
    eta_t[:, 2] = 0.01 * np.cos(2 * np.pi * 30.0 * t_s)
    vm_ref = np.array([von_mises_Pa(_fe_stress_Pa(model, body, eta)) for eta in eta_t])  # (n_t, N)
    peak_ref = vm_ref.max(axis=1)
    assert len(np.unique(vm_ref.argmax(axis=1))) > 1  # the peak does move
    # ragged chunks of times and blocks of nodes, whole chunks, everything in one block
    for block_bytes in (50_000, 10**6, 10**9):
        history = peak_von_mises_history(body, eta_t, block_bytes=block_bytes)
        np.testing.assert_allclose(history.von_mises_Pa, peak_ref, rtol=1e-10)
        # the reported node carries the peak
        np.testing.assert_allclose(vm_ref[np.arange(len(t_s)), history.node], peak_ref, rtol=1e-10)
        # the peak over a subset of the nodes (every third, from node 1) is the subset's own maximum
        subset = np.arange(1, len(body.nodes_m), 3)
        part = peak_von_mises_history(body, eta_t, block_bytes=block_bytes, nodes=subset)
        np.testing.assert_allclose(part.von_mises_Pa, vm_ref[:, subset].max(axis=1), rtol=1e-10)
        assert np.all(np.isin(part.node, subset))
        # a constant stress field added at every instant (a static correction)
        offset = 1e6 * np.random.default_rng(3).standard_normal((len(body.nodes_m), 6))
        vm_off = np.array([von_mises_Pa(_fe_stress_Pa(model, body, eta) + offset) for eta in eta_t])
        shifted = peak_von_mises_history(body, eta_t, block_bytes=block_bytes, nodes=subset, offset_Pa=offset)
        np.testing.assert_allclose(shifted.von_mises_Pa, vm_off[:, subset].max(axis=1), rtol=1e-10)
        np.testing.assert_allclose(vm_ref[np.arange(len(t_s)), part.node], part.von_mises_Pa, rtol=1e-10)
    worst = worst_time(body, t_s, eta_t)
    assert np.sort(peak_ref)[-2] < (1 - 1e-6) * peak_ref.max()      # a clear maximum
    assert worst.index == int(np.argmax(peak_ref))
    assert worst.time_s == t_s[worst.index]
    assert worst.von_mises_Pa == pytest.approx(peak_ref.max(), rel=1e-10)


def test_worst_time_is_the_analytic_maximum_of_a_one_shape_history(ring):
    model, body = ring
    omega_rad_s, tau_s, dt_s = 2 * np.pi * 10.0, 0.05, 1e-3
    t_s = np.arange(0.0, 0.1 + dt_s / 2, dt_s)
    s = np.sin(omega_rad_s * t_s) * np.exp(-t_s / tau_s)
    eta_hat = np.zeros(body.n_modes)
    eta_hat[0], eta_hat[3] = 0.05, 0.01          # one mode plus a smaller other one
    eta_t = s[:, None] * eta_hat
    peak_hat = von_mises_Pa(_fe_stress_Pa(model, body, eta_hat)).max()
    t_star = np.arctan(omega_rad_s * tau_s) / omega_rad_s  # 20.095 ms
    worst = worst_time(body, t_s, eta_t)
    assert worst.index == int(np.argmax(np.abs(s)))
    assert abs(worst.time_s - t_star) <= dt_s / 2
    assert worst.von_mises_Pa == pytest.approx(peak_hat * abs(s[worst.index]), rel=1e-10)
    # the sample is within 0.1 % of the analytic maximum and not above it
    peak_star = peak_hat * np.sin(omega_rad_s * t_star) * np.exp(-t_star / tau_s)
    assert peak_star * (1 - 1e-3) <= worst.von_mises_Pa <= peak_star * (1 + 1e-12)
    # the whole history: |s(t)| times the peak of η̂
    history = peak_von_mises_history(body, eta_t)
    np.testing.assert_allclose(history.von_mises_Pa, peak_hat * np.abs(s), rtol=1e-10, atol=1e-9 * peak_hat)


def test_peak_history_memory_stays_within_the_block_budget(ring):
    _, body = ring
    t_s, eta_t = _random_record(body.n_modes, 2000)
    block_bytes = 2 * 2**20
    all_at_once_bytes = eta_t.shape[0] * len(body.nodes_m) * 6 * 8  # 115 MB of stress tensors
    tracemalloc.start()
    try:
        peak_von_mises_history(body, eta_t, block_bytes=block_bytes)
        _, traced_peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    # budget + the two result arrays (16 B per time) + slack for small temporaries
    assert traced_peak <= block_bytes + 16 * len(t_s) + 2**20
    assert traced_peak < all_at_once_bytes / 20


# ---------------------------------------------------------------------------------------------
# ParaView series
# ---------------------------------------------------------------------------------------------
def _frames(pvd):
    return [(float(d.get("timestep")), pvd.parent / d.get("file"))
            for d in ET.parse(pvd).getroot().find("Collection").findall("DataSet")]


def test_series_round_trips_through_meshio(ring, tmp_path):
    model, body = ring
    t_s, eta_t = _random_record(body.n_modes, 10)
    pvd = write_stress_series(tmp_path / "run", body, t_s, eta_t, every=3)
    frames = _frames(pvd)
    assert [time for time, _ in frames] == list(t_s[[0, 3, 6, 9]])  # the pvd keeps full precision
    for (_, path), i in zip(frames, [0, 3, 6, 9]):
        data = meshio.read(path).point_data
        ref = _fe_stress_Pa(model, body, eta_t[i])
        scale = np.abs(ref).max()
        assert np.abs(data["von_mises_Pa"] - von_mises_Pa(ref)).max() <= 1e-10 * scale
        # stored in ParaView's tensor order xx yy zz xy yz xz
        assert np.abs(data["stress_Pa"] - voigt_to_vtk_tensor(ref)).max() <= 1e-10 * scale
        np.testing.assert_allclose(data["displacement_m"], (body.shapes @ eta_t[i]).reshape(-1, 3),
                                   rtol=1e-14, atol=0.0)
    # chosen times between samples: η interpolated linearly
    times_s = [0.5 * (t_s[1] + t_s[2]), t_s[5]]
    pvd = write_stress_series(tmp_path / "chosen", body, t_s, eta_t, times_s)
    frames = _frames(pvd)
    assert [time for time, _ in frames] == times_s
    ref = von_mises_Pa(_fe_stress_Pa(model, body, 0.5 * (eta_t[1] + eta_t[2])))
    np.testing.assert_allclose(meshio.read(frames[0][1]).point_data["von_mises_Pa"], ref,
                               rtol=1e-10, atol=1e-10 * ref.max())


def test_failed_series_leaves_no_collection_and_stale_frames_go(ring, tmp_path, monkeypatch):
    import fem_rings.output

    _, body = ring
    t_s, eta_t = _random_record(body.n_modes, 4)
    write_stress_series(tmp_path, body, t_s, eta_t)                 # 4 frames
    real_write_vtu, calls = fem_rings.output.write_vtu, []

    def fail_on_second_frame(*args, **kwargs):
        calls.append(args[0])
        if len(calls) == 2:
            raise OSError("disk full")
        return real_write_vtu(*args, **kwargs)

    monkeypatch.setattr(fem_rings.output, "write_vtu", fail_on_second_frame)
    with pytest.raises(OSError, match="disk full"):
        write_stress_series(tmp_path, body, t_s, eta_t)
    # the old collection is gone: it would have listed a mix of old and new frames
    assert not (tmp_path / "stress.pvd").exists()
    monkeypatch.undo()
    write_stress_series(tmp_path, body, t_s[:2], eta_t[:2])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["stress.pvd", "stress_0000.vtu", "stress_0001.vtu"]


# ---------------------------------------------------------------------------------------------
# pictures
# ---------------------------------------------------------------------------------------------
def _high_colour_pixels(path, width: int, height: int) -> int:
    """Pixels of the model region drawn in the top (yellow) end of viridis."""
    image = matplotlib.image.imread(path)[:, :, :3]
    assert image.shape == (height, width, 3)
    model = image[int(0.12 * height):, : int(0.8 * width)]           # left of the bar, below the title
    r, g, b = model[..., 0], model[..., 1], model[..., 2]
    return int(np.sum((r > 0.6) & (g > 0.6) & (b < 0.35)))


def test_pngs_share_one_colour_scale(ring, tmp_path):
    pytest.importorskip("pyvista")
    _, body = ring
    t_s = np.linspace(0.0, 1.0, 11)
    eta_hat = np.zeros(body.n_modes)
    eta_hat[0] = 0.05
    eta_t = np.outer(1.0 + t_s, eta_hat)                             # stress grows 1 … 2 × over the run
    width, height = 600, 400
    paths = render_stress_pngs(tmp_path / "png", body, t_s, eta_t, [0.0, 1.0], window_size=(width, height))
    assert [p.name for p in paths] == ["stress_0000.png", "stress_0001.png"]
    # shared range 0 … peak at t = 1 s: the t = 0 frame reaches only half of it, so none of its
    # pixels is in the top of the colour map; the t = 1 s frame has many
    low, high = (_high_colour_pixels(p, width, height) for p in paths)
    assert low == 0
    assert high > 0.01 * (0.88 * height) * (0.8 * width)
    # by default the worst recorded instant (t = 1 s here) is drawn: the same picture
    (worst,) = render_stress_pngs(tmp_path / "worst", body, t_s, eta_t, window_size=(width, height))
    assert worst_time(body, t_s, eta_t).index == 10
    np.testing.assert_array_equal(matplotlib.image.imread(worst), matplotlib.image.imread(paths[1]))


# ---------------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------------
def test_bad_input_names_the_field(ring, tmp_path):
    _, body = ring
    t_s, eta_t = _random_record(body.n_modes, 5)
    with pytest.raises(ValueError, match=r"no stress modes"):
        peak_von_mises_history(replace(body, extras={}), eta_t)
    with pytest.raises(ValueError, match=r"eta_t must have shape \(n_t, 6\)"):
        stress_at(body, t_s, eta_t[:, :4], 0.0)
    with pytest.raises(ValueError, match=r"t_s must have shape \(5,\)"):
        worst_time(body, t_s[:4], eta_t)
    with pytest.raises(ValueError, match=r"t_s must increase strictly; t_s\[3\]"):
        worst_time(body, t_s[[0, 1, 3, 2, 4]], eta_t)
    bad_eta = eta_t.copy()
    bad_eta[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"eta_t contains 1 non-finite values \(first at sample 2, mode 1"):
        write_stress_series(tmp_path, body, t_s, bad_eta)
    bad_t = t_s.copy()
    bad_t[3] = np.inf
    with pytest.raises(ValueError, match=r"t_s contains 1 non-finite"):
        render_stress_pngs(tmp_path, body, bad_t, eta_t)
    with pytest.raises(ValueError, match=r"times_s must lie within the record"):
        stress_at(body, t_s, eta_t, t_s[-1] + 1e-3)
    with pytest.raises(ValueError, match=r"either times_s or every"):
        write_stress_series(tmp_path, body, t_s, eta_t, [0.0], every=2)
    with pytest.raises(ValueError, match=r"method must be"):
        stress_at(body, t_s, eta_t, 0.0, method="cubic")
    with pytest.raises(ValueError, match=r"nodes must lie in 0 … "):
        peak_von_mises_history(body, eta_t, nodes=[0, len(body.nodes_m)])
    with pytest.raises(ValueError, match=r"nodes must be a non-empty 1-D sequence"):
        peak_von_mises_history(body, eta_t, nodes=[])
    with pytest.raises(ValueError, match=r"offset_Pa must be finite with shape"):
        peak_von_mises_history(body, eta_t, offset_Pa=np.zeros((3, 6)))
    assert list(tmp_path.iterdir()) == []                            # nothing written
