"""Craig–Bampton reduction of fem_rings models into modal bodies for the floating frame (DESIGN §4).

The package has no public functions yet.
"""

__all__: list[str] = []
