"""Parameter sweeps: many runs of one case with some keys varied, as independent Dask tasks.

Data flow: :mod:`.spec` (the varied keys and their points) → :mod:`.runner` (validate every
point, reuse the folders already computed, run the rest) → :mod:`.engine` (a LocalCluster or an
existing scheduler; one ordinary run per task) → :mod:`.collect` (the table, plots and
``sweep.json`` rebuilt from the point folders). The command line is :mod:`.command`.
"""
