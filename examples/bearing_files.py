"""Your own bearing: description files of five bearing types, solved under their loads.

``examples/bearings/`` holds a four-point contact pitch bearing (Ø2.5 m, one row, a three-case
load spectrum in a CSV beside it), a double-row four-point slewing bearing, a double-row
angular-contact bearing (back-to-back), a radial + thrust roller bearing with logarithmic
roller profiles and a preloaded crossed roller slewing bearing (Ø1.0 m, 100 rollers alternating
between the ±45° diagonals) (format: ``cases/bearings/README.md``). Each is read, solved under the load of its
file (every case of a spectrum) and written to ``results/examples/bearing-files/<name>/``
(or ``$FLEXBEARING_EXAMPLE_OUT``) as ``flexbearing loaddist FILE.toml --out …`` writes it. Then
each takes a pure axial load, whose ball and roller loads have a closed form (checked in
``tests/test_examples.py``).

The same from the command line::

    flexbearing loaddist examples/bearings/pitch-bearing-four-point.toml --out results/pitch
    flexbearing loaddist examples/bearings/double-angular-contact.toml --Fz-N 5e4

Run: ``python examples/bearing_files.py``.
"""

import os
from pathlib import Path

from cases.bearing_file import read_bearing_file
from cases.report import write_load_distribution
from mbd_core.quasistatic import RingLoad, solve_load_distribution

HERE = Path(__file__).resolve().parent / "bearings"
OUT = Path(os.environ.get("FLEXBEARING_EXAMPLE_OUT", "results/examples/bearing-files"))
#: pure axial load of the closed-form check, N (towards +z on the moving ring)
AXIAL_N = 2.0e5

descriptions = {p.stem: read_bearing_file(p) for p in sorted(HERE.glob("*.toml"))}
results = {}
for name, d in descriptions.items():
    results[name] = [solve_load_distribution(d.bearing, load) for load in d.load_cases]
    write_load_distribution(results[name] if len(results[name]) > 1 else results[name][0], OUT / name,
                            {"case": name, "description": d.description}, d.time_share)
    worst = max(r.max_load_N for res in results[name] for r in res.rows)
    print(f"{d.name}: {len(d.load_cases)} load case(s), largest element load {worst:.0f} N -> {OUT / name}")

axial = {name: solve_load_distribution(d.bearing, RingLoad(Fz_N=AXIAL_N)) for name, d in descriptions.items()}
