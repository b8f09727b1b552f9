"""Open contacts on modal bodies are skipped without changing a force (mbd_core.kernels.forces).

A contact on a sampled surface of a modal body (a ball in a modal ring's groove, a roller slice or end
on a modal raceway or rib, an element in a modal cage's pocket) moves by at most
U + R·|p − p_s| when the surface deforms: U = Σ_k |η_k| max_s |D_s,k| and R = Σ_k |η_k| max_s |Ω_s,k|.
A step that may skip leaves out the deformation of a contact whose rigid-geometry gap exceeds 1.1 ×
that bound.

Checks:
- the bound holds: on random states of the synthetic scenes of test_kernels_modal_step (groove) and
  test_flexible_rollers (slices, ribs, pockets), the change of every contact's penetration by the
  deformation, from the kernel without skipping (which matches its numpy twin there), stays within the
  bound computed here from the model's tables;
- on those states the forces, moments and modal forces with skipping equal those without, bit for
  bit, and the far-open contacts were skipped;
- explicit runs of a ball bouncing off a modal cage's pocket wall and of a roller off a modal ring's
  raceway record the same samples, bit for bit, with and without skipping (the recorded steps form
  every contact), and most evaluations on the other steps were skipped.
"""

import math

import numpy as np
import pytest

from mbd_core.kernels import forces as FK
from mbd_core.kernels.flexible_surface import SKIP_MARGIN
from mbd_core.multibody.explicit import simulate
from mbd_core.multibody.model import make_work
from tests import test_flexible_rollers as rollers
from tests import test_kernels_modal_step as grooves

#: ball places on the groove scene: four in contact, four 0.2 mm out of it
FAR_GAP_M = 2e-4


def _groove_scene():
    deltas = [grooves.DELTA_0] * 4 + [-FAR_GAP_M] * 4
    return grooves._flexible_model(undulated=True, outer=False, deltas=deltas)


def _evaluate(model, st, skip: bool):
    w = make_work(model)
    w.flex_skip[1] = int(skip)
    assert FK.compute_forces(model.arrays, st.t, st.q, st.v, st.eta, st.eta_dot, w) == (FK.STATUS_OK, -1)
    return w


def _rigid_penetration(model, st):
    """Each contact's penetration with every modal coordinate zero (the rigid geometry)."""
    flat = type(st)(st.t, st.q, st.v, np.zeros_like(st.eta), np.zeros_like(st.eta_dot))
    return _evaluate(model, flat, skip=False).contact_delta


def _bounds(model, st, lever_m):
    """U + R·lever per contact (its body b's modal coordinates), 0 for a rigid surface."""
    a = model.arrays
    out = np.zeros(model.n_pairs)
    for c in range(model.n_pairs):
        j = a.body_modal[a.pair_b[c]]
        if j < 0:
            continue
        e = np.abs(st.eta[a.modal_off[j]:a.modal_off[j + 1]])
        out[c] = e @ a.modal_disp_max[a.modal_off[j]:a.modal_off[j + 1]] \
            + lever_m * (e @ a.modal_rot_max[a.modal_off[j]:a.modal_off[j + 1]])
    return out


def _states(scene_state, model, state, seed, **kw):
    rng = np.random.default_rng(seed)
    return [scene_state(model, state, rng, slow=k % 2 == 1, **kw) for k in range(6)]


@pytest.mark.parametrize("scene", ["groove", "rollers"])
def test_the_bound_holds_and_skipping_changes_no_force(scene):
    """Groove scene: η with |u| ~ 5 µm; roller scene: |u| ~ 1 µm (the scenes' own scales). Levers:
    the groove's curvature centre sits within F_D of its sampled point, the roller scene's contact
    points within 5 cm of theirs (the levers of the twin tests)."""
    if scene == "groove":
        model, state = _groove_scene()
        states = _states(grooves._scene_state, model, state, 7, jitter=1e-6)
        lever = grooves.F_D + 1e-3
    else:
        model, state = rollers._scene()
        states = _states(rollers._scene_state, model, state, 8, eta_scale=3e-6)
        lever = rollers.LEVER_M
    a = model.arrays
    flexible = a.body_modal[a.pair_b] >= 0
    skipped_any = 0
    for st in states:
        exact, fast = _evaluate(model, st, skip=False), _evaluate(model, st, skip=True)
        change = np.abs(exact.contact_delta - _rigid_penetration(model, st))
        bound = _bounds(model, st, lever)
        assert np.all(change[flexible] <= bound[flexible] * (1 + 1e-9)), (change, bound)
        for name in ("body_f", "body_t", "modal_f", "contact_fn", "contact_ft", "energy"):
            assert np.array_equal(getattr(exact, name), getattr(fast, name)), name
        checked, skipped = fast.flex_bound[:, 2].sum(), fast.flex_bound[:, 3].sum()
        assert exact.flex_bound[:, 2].sum() == 0 and checked > 0
        # a skipped contact carries no load and reports its rigid-geometry penetration, below the bound
        open_far = flexible & (fast.contact_delta != exact.contact_delta)
        assert np.all(exact.contact_fn[open_far] == 0.0)
        assert np.all(fast.contact_delta[open_far] + SKIP_MARGIN * bound[open_far] < 0.0)
        skipped_any += skipped
    assert skipped_any > 0
    print(f"{scene}: {skipped_any:.0f} contacts skipped over {len(states)} states")


@pytest.mark.parametrize("kind", ["pocket", "raceway"])
def test_explicit_runs_record_the_same_with_and_without_skipping(kind):
    """The bounce runs of test_flexible_rollers (6000 steps of 10 ns, a sample every 50)."""
    runs = []
    for skip in (True, False):
        model, state = rollers._bounce_model(kind)
        runs.append(simulate(model, state, 60e-6, timestep_s=1e-8, record_every=50, skip_open_contacts=skip))
    fast, exact = runs
    for name in ("t", "q", "v", "eta", "eta_dot", "fn", "delta", "slip", "ft", "point", "normal"):
        assert np.array_equal(fast[name], exact[name]), name
    assert exact["surface_contacts_skipped"] == 0.0
    assert fast["surface_contacts_skipped"] > 0.3
    assert fast["fn"].max() > 0.0
    print(f"{kind}: {fast['surface_contacts_skipped']:.1%} of the checked evaluations skipped")


def test_skipping_is_off_outside_the_explicit_loop():
    """A force evaluation by any other caller (statics, implicit steps, evaluate_forces) forms every
    contact: make_work leaves both flags clear, and the explicit loop clears its per-step flag."""
    model, state = rollers._bounce_model("raceway")
    w = make_work(model)
    assert list(w.flex_skip) == [0, 0]
    FK.compute_forces(model.arrays, state.t, state.q, state.v, state.eta, state.eta_dot, w)
    assert np.all(np.isinf(w.flex_bound[:, :2])) and w.flex_bound[:, 2].sum() == 0
    assert math.isinf(w.flex_bound[0, 0])
