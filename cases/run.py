"""``flexbearing run``: from a case name or TOML file to a complete results folder.

Resolution order: the named sub-case (or the TOML file), then ``--quick``, then every ``--set
key=value``; the resolved case is validated before any meshing starts and saved as ``case.toml``
beside the results, so a folder always says exactly what produced it. A key that the case's
study does not read (it sets or sweeps that value itself) is refused when given with ``--set`` or
changed in a case file, naming the key that does the job (:mod:`cases.overrides`).

Without ``--out`` the results go to ``results/<case name>``; a folder there that holds the results
of a run from another named case or case file (a copied ``case.toml`` keeps the original's name)
is not replaced: :func:`default_out_dir` refuses it, naming ``--out``.

The explicit runs of a case keep their pieces in ``.NAME.fb-resume/`` beside the results folder
(:func:`cases.integrate.checkpoints`) until the results are in place; after an interruption
``flexbearing run … --resume`` (``run_case(..., resume=True)``) goes on from the last stored
piece of the same resolved case and writes results identical to those of an uninterrupted run.
"""

from __future__ import annotations

import dataclasses
import logging
import platform
import resource
import shutil
import time
import tomllib
from pathlib import Path

from mbd_core.multibody import warmup

from .config import FAMILY_KEY, CaseError, dumps_case, from_mapping, qualified_message, read_toml, with_overrides
from .integrate import ResumeError, checkpoints
from .overrides import check_case, reference_case
from .outdir import OutputTargetError, atomic_folder, check_output_target, is_results_folder, marker_source
from .results import RunOutput, output_units
from .crb import presets as crb_presets
from .crb import studies as crb_studies
from .crb.case import CrbCase
from .described import presets as described_presets
from .described import studies as described_studies
from .described.case import DescribedCase
from .dma import presets as dma_presets
from .dma import studies as dma_studies
from .dma.case import DmaCase
from .slewing import presets as slewing_presets
from .slewing import studies as slewing_studies
from .slewing.case import SlewingCase
from .turbocharger import presets as turbocharger_presets
from .turbocharger import studies as turbocharger_studies
from .turbocharger.case import TurbochargerCase
from .wind import presets as wind_presets
from .wind import studies as wind_studies
from .wind.case import WindCase

__all__ = ["CASES", "case_source", "default_out_dir", "resolve_case", "resume_folder", "run_case", "runs_variants", "studies_of"]

log = logging.getLogger(__name__)

#: the bearings with cases: case class → (presets module, studies module)
_FAMILIES = {SlewingCase: (slewing_presets, slewing_studies), WindCase: (wind_presets, wind_studies),
             DescribedCase: (described_presets, described_studies), DmaCase: (dma_presets, dma_studies),
             CrbCase: (crb_presets, crb_studies), TurbochargerCase: (turbocharger_presets, turbocharger_studies)}
PRESETS = {name: c for presets, _ in _FAMILIES.values() for name, c in presets.PRESETS.items()}
#: named cases: name → one-line description
CASES = {name: c.description for name, c in PRESETS.items()}


#: tables that only one family's case files have (to read files written before ``family`` existed)
_OWN_TABLES = {SlewingCase: {"geometry", "load", "undulation", "thermal", "top", "bottom"},
               WindCase: {"rollers", "bodies", "loads"}, DescribedCase: {"bearing", "life"},
               DmaCase: {"operation", "traction"}, CrbCase: {"lubrication", "surfaces", "catalogue"},
               TurbochargerCase: {"rotor", "damper", "defect"}}


def _case_class(data: dict, source: str) -> type:
    """The case class a case file's table names through its ``family`` key.

    A file without the key (written before it existed) is read when its tables belong to one
    family only; otherwise it is refused with the line to add.
    """
    by_name = {cls.FAMILY: cls for cls in _FAMILIES}
    family = data.get(FAMILY_KEY)
    if family is None:
        owners = [cls for cls, tables in _OWN_TABLES.items() if tables & set(data)]
        if len(owners) == 1:
            return owners[0]
        raise CaseError(f"{source}: {FAMILY_KEY}: missing key; add {FAMILY_KEY} = "
                        f"{' or '.join(repr(f) for f in by_name)} at the top of the file")
    if not isinstance(family, str) or family not in by_name:
        raise CaseError(f"{source}: {FAMILY_KEY}: must be one of {', '.join(map(repr, by_name))}, got {family!r:.60}")
    return by_name[family]


def resolve_case(name_or_path: str, quick_run: bool = False, overrides=()):
    """The case a command line describes (raises :class:`CaseError` naming the bad key or file)."""
    if name_or_path in PRESETS:
        case = PRESETS[name_or_path]
    elif name_or_path.endswith(".toml"):
        path = Path(name_or_path)
        if not _is_file(path, "case file"):
            raise CaseError(f"case file {name_or_path!r} does not exist")
        data = read_toml(path)
        try:
            case = from_mapping(_case_class(data, str(path)), data)
        except CaseError as exc:
            raise CaseError(exc.args[0] if exc.args[0].startswith(str(path)) else f"{path}: {exc}") from None
    else:
        raise CaseError(f"unknown case {name_or_path!r}: give a TOML file or one of {', '.join(sorted(PRESETS))}")
    if quick_run:
        try:
            case = _FAMILIES[type(case)][0].quick(case)
        except ValueError as exc:  # a dataclass's own check, without the table's name
            raise CaseError(f"--quick: {qualified_message(type(case), str(exc))}") from None
    file_case = case if name_or_path not in PRESETS else None
    if overrides:
        case = with_overrides(case, list(overrides))
        said = "; ".join(x for x in (case.description, f"changed by --set {', '.join(overrides)}") if x)
        case = dataclasses.replace(case, description=said)  # the case says what ran
    _check_unused(case, overrides, file_case, name_or_path)
    for key, file in getattr(case, "input_files", dict)().items():
        if not _is_file(Path(file), key):
            raise CaseError(f"{key}: no such file: {file!r}")
    return case


def studies_of(case):
    """The studies module of the case's family (``run_study``, ``uses_dynamics``, ``STUDIES``, …)."""
    return _FAMILIES[type(case)][1]


def runs_variants(case) -> bool:
    """True when the case's study runs variants of it that can go to Dask workers
    (:func:`cases.sweep.variants.run_variants`)."""
    return studies_of(case).STUDIES[case.study.kind].variants


def _is_file(path: Path, what: str) -> bool:
    """Whether ``path`` is a file; a name the system refuses (too long, …) is a :class:`CaseError`
    naming ``what`` (the key or the case file), not a traceback."""
    try:
        return path.is_file()
    except OSError as exc:
        raise CaseError(f"{what}: not a usable file name ({exc.strerror}): {str(path)!r:.80}") from None


def _check_unused(case, overrides, file_case, source: str) -> None:
    """Refuse keys the case's study does not read (:mod:`cases.overrides`): set with ``--set``,
    or changed in the case file from the study's named case."""
    presets, studies = _FAMILIES[type(case)]
    unused = studies.case_unused_keys(case)
    reference = None
    if file_case is not None:
        reference = reference_case(type(case), presets.PRESETS, file_case.study.kind)
        file_unused = studies.case_unused_keys(file_case)
        check_case(file_case, file_unused, source_case=file_case, reference=reference, source=source)
    check_case(case, unused, list(overrides))


def _peak_rss_mb() -> float:
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return kb / (1024.0 * 1024.0) if platform.system() == "Darwin" else kb / 1024.0


def resume_folder(out_dir) -> Path:
    """Where the explicit runs of a case writing to ``out_dir`` keep their pieces."""
    out = Path(out_dir).resolve()
    return out.with_name(f".{out.name}.fb-resume")


def _flat(d: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in d.items():
        out.update(_flat(v, f"{prefix}{k}.") if isinstance(v, dict) else {f"{prefix}{k}": v})
    return out


def _check_same_case(stored_toml: Path, case_toml: str) -> None:
    """Refuse to resume a run of another case, naming the entries that differ."""
    try:
        old = _flat(tomllib.loads(stored_toml.read_text(encoding="utf-8")))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ResumeError(f"{stored_toml}: stored case unreadable ({exc}); run again without --resume") from None
    new = _flat(tomllib.loads(case_toml))
    differ = sorted(k for k in set(old) | set(new) if old.get(k) != new.get(k))
    if differ:
        shown = "; ".join(f"{k}: {old.get(k, '(absent)')!r} in the interrupted run, {new.get(k, '(absent)')!r} now"
                          for k in differ[:5])
        raise ResumeError(f"cannot resume: the case differs from the interrupted run's ({shown}"
                          f"{'; …' if len(differ) > 5 else ''}); run again without --resume")


def _open_resume_folder(folder: Path, case_toml: str, resume: bool) -> None:
    stored = folder / "case.toml"
    if resume and folder.is_dir() and stored.exists():
        _check_same_case(stored, case_toml)
        log.info("resuming from %s", folder)
        return
    if resume:
        log.warning("nothing to resume in %s: running from the start", folder)
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir()
    stored.write_text(case_toml, encoding="utf-8")


def case_source(name_or_path: str) -> str:
    """What a run's case comes from, as its results folder's marker records it: the named case,
    or the resolved path of the case file."""
    return name_or_path if name_or_path in PRESETS else str(Path(name_or_path).resolve())


def default_out_dir(case, source: str) -> Path:
    """``results/<case name>``, the folder a run writes to without ``--out``.

    Raises
    ------
    cases.outdir.OutputTargetError
        The folder holds the results of a run from another source (a copied ``case.toml`` keeps
        the original's name): only ``--out`` may name a folder to replace then.
    """
    out = Path("results") / case.name
    if not is_results_folder(out):
        return out
    name, stored = marker_source(out)
    # folders written before the marker recorded a source: the named case of that name only
    same = stored == source if stored is not None else (source in PRESETS and name in (source, f"{source}-quick"))
    if not same:
        shown = stored if stored is not None else "an earlier run"
        raise OutputTargetError(f"{out} holds the results of {shown}, not of {source}; choose the results "
                                f"folder with --out (giving --out {out} replaces them)")
    return out


def run_case(case, out_dir, progress=None, resume: bool = False, source: str | None = None,
             summary_extra: dict | None = None) -> RunOutput:
    """Run ``case`` into ``out_dir`` (replaced only when the run completes); returns the output.

    ``summary_extra``: entries added to ``summary.json`` (e.g. the fidelity chosen for a tolerance).

    ``source``: what the case comes from (:func:`case_source`), recorded in the folder's marker.

    ``resume``: reuse the explicit-run pieces stored by an interrupted run of the same case into
    the same folder (:func:`resume_folder`). Raises :class:`cases.outdir.OutputTargetError` before
    any work when ``out_dir`` may not be replaced, :class:`cases.integrate.ResumeError` when the
    stored run belongs to another case or model.
    """
    t0 = time.perf_counter()
    check_output_target(out_dir)
    text = dumps_case(case)
    keep = resume_folder(out_dir)
    keep.parent.mkdir(parents=True, exist_ok=True)
    _open_resume_folder(keep, text, resume)
    studies = _FAMILIES[type(case)][1]
    # a run inside another one (a variant of its study) leaves the warm-up to the outer run
    owner = not warmup.started()
    if owner and studies.uses_dynamics(case):
        warmup.start()  # compiles the kernels on another core while the rings are meshed and reduced
    try:
        with atomic_folder(out_dir, case.name, source) as tmp, checkpoints(keep, resume):
            out = RunOutput(tmp)
            out.path("case.toml").write_text(text)
            studies.run_study(case, out, progress)
            out.summary = output_units({"case": case.name, "study": case.study.kind, "description": case.description,
                                        **out.summary, **(summary_extra or {}), "wall_time_s": time.perf_counter() - t0,
                                        "peak_rss_mb": _peak_rss_mb()})
            out.write_summary()
    except BaseException:
        if owner:
            warmup.stop()
        if any(keep.glob("run_*/piece_*.npz")) or any(keep.glob("points/*/summary.json")):
            log.warning("the explicit runs done so far are kept in %s: continue with --resume", keep)
        else:  # nothing worth resuming
            shutil.rmtree(keep, ignore_errors=True)
        raise
    if owner:
        warmup.stop()  # (a run that never built a model did not wait for it)
    shutil.rmtree(keep, ignore_errors=True)
    out.folder = Path(out_dir)
    return out
