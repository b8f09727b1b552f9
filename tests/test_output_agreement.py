"""The outputs of a run agree with each other: the units of CSV columns, summary keys and plot
axes, the element numbers of tables and plots, the key figures and the data a figure draws, the
scales of figures meant to be compared, and the words of titles and descriptions.

Cheap: small synthetic series go straight into the plotting and reporting functions; the one
study run here (wind-static) is quasi-static with rigid rings.
"""

from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from cases.results import RunOutput
from cases.run import PRESETS, resolve_case
from cases.slewing import dynamic as slewing_dynamic
from cases.slewing.plots import plot_dynamic
from fem_rings.output import displacement_magnitude

README = Path(__file__).resolve().parents[1] / "README.md"


@pytest.fixture
def saved_figures(monkeypatch):
    """Figures a study saves, by file name, kept open for inspection (then closed)."""
    import matplotlib.pyplot as plt

    kept = {}

    def keep(self, fig, name):
        kept[name] = fig
        return self.path(name)

    monkeypatch.setattr(RunOutput, "save_figure", keep)
    yield kept
    for fig in kept.values():
        plt.close(fig)


def _line_data(ax):
    """The data lines of ``ax``: every Line2D with more than two points (not axhline/axvline)."""
    return [ln for ln in ax.get_lines() if len(np.atleast_1d(ln.get_xdata())) > 2]


def _x_extent(patch) -> tuple[float, float]:
    """Data x range of an axvspan (a Rectangle in newer matplotlib, a Polygon in older)."""
    if hasattr(patch, "get_width"):
        return patch.get_x(), patch.get_x() + patch.get_width()
    x = np.asarray(patch.get_xy())[:, 0]
    return float(x.min()), float(x.max())


# -- the spacer-force peak of summary.json is the peak the figure draws -------------------------
def _synthetic_spacer_run(n_balls=16, n_t=41, duration_s=0.4):
    """Ball loads near 42 kN with a 0.1 % ripple, spacer forces with a start-up impact of 2529 N
    at the second sample and a largest later value of 1723 N (the numbers of the filed report)."""
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, duration_s, n_t)
    q = 42_000.0 * (1.0 + 1e-3 * rng.standard_normal((n_t, n_balls)))
    fs = 600.0 * rng.random((n_t, 2 * n_balls))
    fs[1, 3] = 2529.0
    fs[30, 7] = 1723.0
    return t, q, fs


def test_spacer_peak_of_the_summary_is_the_peak_drawn_and_the_start_up_is_marked():
    t, q, fs = _synthetic_spacer_run()
    start_s, settled = slewing_dynamic.start_up_window(t)
    figures = slewing_dynamic.spacer_force_figures(fs[settled])
    case = PRESETS["slewing-rotation"]
    fig = plot_dynamic(t, q, fs, 42_000.0, case, start_s)
    try:
        ax_balls, ax_spacers = fig.axes[0], fig.axes[1]
        drawn = max(float(np.max(ln.get_ydata())) for ln in _line_data(ax_spacers))
        # reference: the series itself after the first tenth of the run (the start-up impact of
        # 2529 N falls in it): 1723 N
        assert drawn == figures["max_spacer_force_N"] == 1723.0
        assert min(float(np.min(ln.get_xdata())) for ln in _line_data(ax_spacers)) >= start_s
        # the start-up window is shaded and says that it is left out, on both axes; the spacers'
        # names the impact it leaves out
        assert "peak 2\u2009529 N" in next(str(p.get_label()) for p in ax_spacers.patches)
        for ax in (ax_balls, ax_spacers):
            spans = [p for p in ax.patches if "start-up" in str(p.get_label())]
            assert len(spans) == 1
            x = _x_extent(spans[0])
            assert x == (pytest.approx(t[0]), pytest.approx(start_s))
        # no leftover notes in the titles
        for ax in fig.axes:
            assert "at least" not in ax.get_title() and "±3 %" not in ax.get_title()
    finally:
        import matplotlib.pyplot as plt
        plt.close(fig)


def test_balls_are_numbered_alike_in_the_csv_columns_and_the_plot_legend():
    t, q, fs = _synthetic_spacer_run()
    start_s, _ = slewing_dynamic.start_up_window(t)
    fig = plot_dynamic(t, q, fs, 42_000.0, PRESETS["slewing-rotation"], start_s)
    try:
        legend = [x.get_text() for x in fig.axes[0].get_legend().get_texts()]
        plotted = [int(m.group(1)) for m in (re.fullmatch(r"ball (\d+)", s) for s in legend) if m]
        columns = [int(re.fullmatch(r"ball_(\d+)_N", c).group(1)) for c in slewing_dynamic.ball_columns(q.shape[1])]
        assert plotted == columns == list(range(1, 17))
        # spacer contacts: 32 lines coloured by spacer number on a bar from 1 to 16, the numbers
        # the CSV columns carry (spacer j touches balls j and j + 1, ball 17 being ball 1)
        bar = fig.axes[-1]
        assert bar.get_ylabel() == "spacer number" and bar.get_ylim() == (1.0, 16.0)
        cols = slewing_dynamic.spacer_columns(16)
        pairs = [tuple(map(int, re.fullmatch(r"ball_(\d+)_spacer_(\d+)_N", c).groups())) for c in cols]
        assert sorted({s for _, s in pairs}) == list(range(1, 17))
        assert all(b in (s, s % 16 + 1) for b, s in pairs)
    finally:
        import matplotlib.pyplot as plt
        plt.close(fig)


# -- one unit per quantity kind --------------------------------------------------------------
def test_csv_columns_and_summary_keys_carry_the_output_units(tmp_path):
    """Reference: the unit definitions, 1 m = 1000 mm, 1 Pa = 1e-6 MPa (stresses) = 1e-9 GPa
    (moduli), 1 rad/s = 60/(2π) r/min, 1 rad = 180/π deg; forces stay in N. A curvature in 1/m is
    not a length."""
    from cases.results import output_units
    out = RunOutput(tmp_path)
    out.write_csv("t.csv", ["ball", "load_N", "offset_m", "p0_Pa", "cage_rad_s", "angle_rad"],
                  [(1, 4.2e4, 4e-4, 2.0e9, 1.0, math.pi / 2)])
    with open(tmp_path / "t.csv") as fh:
        row = next(csv.DictReader(fh))
    assert set(row) == {"ball", "load_N", "offset_mm", "p0_MPa", "cage_rpm", "angle_deg"}
    assert float(row["offset_mm"]) == pytest.approx(0.4, rel=1e-9)
    assert float(row["p0_MPa"]) == pytest.approx(2000.0, rel=1e-9)
    assert float(row["cage_rpm"]) == pytest.approx(60.0 / (2.0 * math.pi), rel=1e-9)
    assert float(row["angle_deg"]) == pytest.approx(90.0, rel=1e-9)
    assert float(row["load_N"]) == 4.2e4
    out.summary = {"max_load_N": 4.2e4, "cases": [{"offset_m": 4e-4, "p0_Pa": [1e9, 2e9], "top_E_Pa": 1.5975e9}],
                   "cage": {"kinematic_rad_s": 2.0}, "curvature_sum_per_m": 5.0}
    s = json.loads(out.write_summary().read_text())
    assert s == {"max_load_N": 4.2e4,
                 "cases": [{"offset_mm": pytest.approx(0.4), "p0_MPa": [1000.0, 2000.0], "top_E_GPa": pytest.approx(1.5975)}],
                 "cage": {"kinematic_rpm": pytest.approx(120.0 / (2.0 * math.pi))}, "curvature_sum_per_m": 5.0}
    assert output_units(output_units(out.summary)) == output_units(out.summary)  # idempotent


def test_the_readme_tables_every_output_unit():
    from cases.results import OUTPUT_UNITS
    text = README.read_text(encoding="utf-8")
    section = text[text.index("## Output units"):]
    section = section[: section.index("\n## ", 4)]
    for suffix in ["_N", "_Nm"] + [new for new, _ in OUTPUT_UNITS.values()]:
        assert f"`{suffix}`" in section, suffix


def test_wind_static_csv_and_figure_agree_with_the_summary(tmp_path, saved_figures):
    """Every force column of max_roller_loads.csv ends in _N like the summary key; the load cases
    are numbered 1…32 in the CSV and on the figure's x axis; the figure draws the CSV's loads in N
    and its largest value is the summary's."""
    from cases.wind.studies import study_static

    out = RunOutput(tmp_path)
    study_static(resolve_case("wind-static", True), out)
    out.write_summary()
    s = json.loads((tmp_path / "summary.json").read_text())
    with open(tmp_path / "max_roller_loads.csv") as fh:
        rows = list(csv.DictReader(fh))
    force_columns = [c for c in rows[0] if "load" in c]
    assert force_columns and all(c.endswith("_N") for c in force_columns)
    assert [int(r["case"]) for r in rows] == list(range(1, 33))
    ax = saved_figures["max_roller_loads.png"].axes[0]
    assert ax.get_ylabel().endswith(", N")
    for line in ax.get_lines():
        name = line.get_label()
        column = f"{name.replace(' ', '_')}_max_load_N"
        np.testing.assert_array_equal(line.get_xdata(), [int(r["case"]) for r in rows])
        np.testing.assert_allclose(line.get_ydata(), [float(r[column]) for r in rows], rtol=1e-8)
        assert max(line.get_ydata()) == pytest.approx(s["max_roller_load_N"][name], rel=1e-8)


# -- comparison plots share their scale ------------------------------------------------------
def test_rigid_and_flexible_roller_speed_plots_share_their_y_scale(monkeypatch):
    """Two runs whose watched roller fluctuates ±0.1 and ±4 r/min about 100 r/min (the scales of
    the filed report): each row's y range is the same on both figures and holds both series; the
    legend names the roller by the number of the summary (``one_roller``, from 1)."""
    from cases.wind import plots

    to_rad_s = 2.0 * math.pi / 60.0
    t = np.linspace(0.0, 0.1, 50)

    def fake_run(amplitude_rpm):
        spin = (100.0 + amplitude_rpm * np.sin(2 * math.pi * 30 * t)) * to_rad_s
        return SimpleNamespace(spin=np.tile(spin[:, None], (1, 5)), t=t)

    monkeypatch.setattr(plots, "rolling_speeds", lambda row, w: (0.0, 100.0 * to_rad_s))
    monkeypatch.setattr(plots, "watched_roller", lambda sc, rec, k: 2)
    monkeypatch.setattr(plots, "roller_spin_rad_s", lambda sc, rec, k: rec["spin"])
    rows = SimpleNamespace(row_defs=[SimpleNamespace(name=n) for n in ("radial", "front thrust", "rear thrust")])
    runs = {}
    for label, amp in (("rigid", 0.1), ("flexible", 4.0)):
        case = SimpleNamespace(analysis=SimpleNamespace(speed_rpm=30.0, settle_s=0.02),
                               bodies=SimpleNamespace(rings=label, cages=label))
        r = fake_run(amp)
        runs[label] = (case, rows, {"t": r.t, "spin": r.spin})
    figs = plots.roller_speed_figures(runs)
    try:
        for k in range(3):
            lims = {label: f.axes[k].get_ylim() for label, f in figs.items()}
            assert lims["rigid"] == lims["flexible"]
            lo, hi = lims["rigid"]
            assert lo <= 96.0 and hi >= 104.0
            labels = [ln.get_label() for ln in figs["rigid"].axes[k].get_lines()]
            assert "roller 3 (relative to the cage)" in labels
            spans = [p for p in figs["rigid"].axes[k].patches if "settling" in str(p.get_label())]
            assert len(spans) == 1 and _x_extent(spans[0]) == (0.0, pytest.approx(0.02))
    finally:
        import matplotlib.pyplot as plt
        for f in figs.values():
            plt.close(f)


# -- colour bars -----------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(20))
def test_colour_bar_ticks_are_round_and_cover_the_field(seed):
    """Reference: the definition, ticks m·10^k apart (m in 1, 2, 2.5, 5), integer multiples of
    that step, at most 7, the first at or below the smallest value and the last at or above the
    largest (seeded random ranges over 16 decades, signs mixed; the
    tolerance is the rounding of ticks far from zero)."""
    from fem_rings.render import round_ticks

    rng = np.random.default_rng(seed)
    scale = 10.0 ** rng.integers(-8, 9)
    lo = rng.uniform(-1, 1) * scale
    hi = lo + rng.uniform(1e-3, 10.0) * scale  # fields that vary by 0.1 % of their size and more
    ticks = round_ticks(lo, hi)
    step = (ticks[-1] - ticks[0]) / (len(ticks) - 1)
    mantissa = step / 10.0 ** math.floor(math.log10(step))
    assert min(abs(mantissa - m) for m in (1.0, 2.0, 2.5, 5.0, 10.0)) < 1e-9 * max(1.0, abs(lo) / step)
    np.testing.assert_allclose(np.diff(ticks), step, rtol=1e-9)
    np.testing.assert_allclose(ticks / step, np.round(ticks / step), atol=1e-6)
    assert 2 <= len(ticks) <= 7
    span = hi - lo  # to rounding of 1e-9 of a step (a colour bar cannot show less)
    assert ticks[0] <= lo + 1e-9 * span and ticks[-1] >= hi - 1e-9 * span
    assert ticks[-1] - ticks[0] < 3.0 * (hi - lo)  # and not needlessly wide


def test_a_mode_shape_is_drawn_at_a_stated_physical_amplitude():
    """A mass-normalised shape (m/√kg) becomes a displacement whose largest nodal magnitude is
    MODE_AMPLITUDE_M = 1 mm, in the same direction everywhere (a scaled copy)."""
    from cases.fem_report import MODE_AMPLITUDE_M, shape_at_amplitude
    rng = np.random.default_rng(3)
    phi = 1e-3 * rng.standard_normal((200, 3))
    u = shape_at_amplitude(phi)
    assert MODE_AMPLITUDE_M == 1e-3
    assert displacement_magnitude(u).max() == pytest.approx(1e-3, rel=1e-12)
    ratio = u / phi
    np.testing.assert_allclose(ratio, ratio[0, 0], rtol=1e-12)


# -- words -----------------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(PRESETS))
def test_a_quick_case_describes_itself_as_quick(name):
    full = PRESETS[name]
    q = resolve_case(name, True)
    assert q.name == f"{name}-quick"
    assert q.description.startswith(f"quick variant of {name}")
    assert q.description != full.description


def test_quick_description_names_what_it_reduces():
    from cases.quick import quick_variant
    case = PRESETS["slewing-rotation"]
    q = quick_variant(case, {"analysis": {"duration_s": 0.4, "record_every": 100}})
    assert "analysis.duration_s = 0.4" in q.description and "analysis.record_every = 100" in q.description
    assert q.analysis.duration_s == 0.4


@pytest.mark.parametrize("n, text", [(0, "0 balls"), (1, "1 ball"), (2, "2 balls"), (116, "116 balls")])
def test_counts_agree_with_their_noun(n, text):
    from cases.results import plural
    assert plural(n, "ball") == text


def test_loaddist_csv_and_summary_agree_in_numbering_and_units(tmp_path):
    """element_loads.csv numbers the 116 balls 1…116 and carries the summary's approach in mm:
    the same numbers under the same names (reference: the summary itself, 1 m = 1000 mm from the
    model's SI result written by LoadDistribution.to_dict)."""
    from cases.catalog import builtin_bearing
    from cases.cli import main
    from mbd_core.quasistatic import solve_load_distribution

    out = tmp_path / "slewing"
    assert main(["loaddist", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "element_loads.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [int(r["element"]) for r in rows] == list(range(1, 117))
    row = summary["rows"][0]
    assert "approach_mm" in row and "approach_mm" in rows[0]
    np.testing.assert_allclose([float(r["approach_mm"]) for r in rows], row["approach_mm"], rtol=1e-8)
    np.testing.assert_allclose([float(r["load_N"]) for r in rows], row["load_N"], rtol=1e-8)
    case = builtin_bearing("slewing-ring")
    direct = solve_load_distribution(case.bearing, case.default_load).rows[0]
    np.testing.assert_allclose(row["approach_mm"], direct.approach_m * 1e3, rtol=1e-9)


def test_roller_slices_in_warnings_are_numbered_from_1():
    """The ISO 76 warning of an overloaded roller row names its most loaded slice as "slice k of n",
    k from 1 (reference: the index of the largest slice load of the solution, plus one)."""
    from cases.catalog import builtin_bearing
    from mbd_core.quasistatic import RingLoad, solve_load_distribution

    case = builtin_bearing("three-row-roller")
    res = solve_load_distribution(case.bearing, RingLoad(Fy_N=-2.0e7))
    radial = res.rows[0]
    k, j = np.unravel_index(int(np.argmax(radial.slice_load_N)), radial.slice_load_N.shape)
    found = [w for w in res.warnings if w.startswith("row 'radial'") and "ISO 76" in w]
    assert found and f"slice {j + 1} of {radial.slice_load_N.shape[1]}:" in found[0]
