"""The fast-reactor slewing ring (cases/slewing/README.md): case definition, scenes, studies (a)–(g).

Data flow: :mod:`.case` (TOML-backed dataclasses) → :mod:`.scene` (ball row, groove offsets,
reduced bodies) → :mod:`.quasistatic` / :mod:`.dynamic` (solvers) → :mod:`.studies` (figures and
key figures, with :mod:`.plots` and :mod:`.life`); :mod:`.presets` names the sub-cases.
"""

from .case import SlewingCase
from .presets import PRESETS, quick

__all__ = ["SlewingCase", "PRESETS", "quick"]
