"""stochnav.run and stochnav.compare: the library's runs (``stochnav run``, ``stochnav
compare``) write their files into a folder, a temporary one unless ``out`` is given, and the
tables come back as dicts of numpy columns."""

import dataclasses
import os
import tempfile
import typing
import warnings

import numpy as np

from . import _stochnav

# The files of a run folder (experiment/navigation_run.hpp) and the RunResult field of each.
_RUN_TABLES = {
    "navigation": "nav.csv",
    "biases": "biases.csv",
    "covariance": "covariance.csv",
    "innovations": "innovations.csv",
    "errors": "errors.csv",
    "survey": "survey.csv",
}


def read_columns(path):
    """A CSV with a header row as a dict of numpy columns (float64; text columns as str)."""
    with open(path, encoding="utf-8") as table:
        names = table.readline().strip().split(",")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a header-only file: no rows
        try:
            values = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        except ValueError:  # text columns (innovations.csv: aid, type)
            values = None
    if values is not None and values.size == 0:
        return {name: np.empty(0) for name in names}
    if values is not None:
        return {name: values[:, index].copy() for index, name in enumerate(names)}
    with open(path, encoding="utf-8") as table:
        rows = [line.rstrip("\n").split(",") for line in table.readlines()[1:] if line.strip()]
    columns = {}
    for index, name in enumerate(names):
        cells = [row[index] for row in rows]
        try:
            columns[name] = np.array([float(cell) if cell else np.nan for cell in cells])
        except ValueError:
            columns[name] = np.array(cells)
    return columns


def _survey_station_count(survey):
    """The survey stations of survey.csv's columns: the rows of station_type "survey" (not the
    tie-on row, nor a projection to the bit)."""
    if "station_type" in survey:
        return int(np.count_nonzero(survey["station_type"] == "survey"))
    return len(survey.get("t_s", []))


@dataclasses.dataclass
class RunResult:
    """A navigation run (stochnav.run). Tables are dicts of numpy columns named as in the run's
    CSV files (docs/navigation.md): navigation (nav.csv: t, lat, lon (deg), h (m), ve, vn, vu
    (m/s), inclination, toolface, azimuth (deg)), biases, covariance (1-sigma of the core states),
    innovations (every update attempt), errors (None without truth: the nine errors, their
    1-sigma and NEES), survey (survey.csv: the tie-on row, then the stations at the connections;
    column station_type says which). metrics is metrics.json."""

    navigation: dict
    biases: dict
    covariance: dict
    innovations: dict
    errors: typing.Optional[dict]
    survey: dict
    metrics: dict
    epochs: int
    duration_s: float
    wall_seconds: float
    filter_ok: bool
    warnings: list
    out: typing.Optional[str]

    def __repr__(self):
        lines = [f"<RunResult: {self.epochs} epochs ({self.duration_s:.0f} s of data) in "
                 f"{self.wall_seconds:.2f} s; filter health {'ok' if self.filter_ok else 'TROUBLE'}"
                 f"; {_survey_station_count(self.survey)} survey station(s)"
                 f"{'; files in ' + self.out if self.out else ''}>"]
        metrics = self.metrics.get("metrics") or {}
        for name, values in metrics.items():
            if values.get("max_abs") is not None:
                lines.append(f"  {name:<22} max |error| {values['max_abs']:<12.6g} "
                             f"rms {values['rms']:.6g}")
        return "\n".join(lines)


def run(config, data=None, out=None, plot=False, progress=False):
    """Run the MWD navigation filter on a record or simulated scenario (``stochnav run``).

    Parameters
    ----------
    config : dict or path
        The run config (configs/runs/*.json, docs/navigation.md). A dict's relative paths start
        in the working folder; a file's in its folder.
    data : path, optional
        A recording folder replacing the config's "data": imu.csv, optional aids.csv and
        truth.csv (a ``simulate_scenario`` folder), as ``stochnav run --data``.
    out : path, optional
        Keep the run's files there (nav.csv, ..., metrics.json); default a temporary folder,
        removed after reading.
    plot : bool
        Draw errors.png and survey.png into out (needs gnuplot).
    progress : bool
        A progress bar on standard error.

    Returns
    -------
    RunResult
        navigation, biases, covariance, innovations, errors, survey as dicts of numpy columns,
        metrics (metrics.json as a dict), epochs, duration_s, wall_seconds, filter_ok.
    """
    if out is None:
        with tempfile.TemporaryDirectory(prefix="stochnav_run_") as folder:
            return _run(config, data, os.path.join(folder, "run"), False, progress, None)
    return _run(config, data, os.fspath(out), plot, progress, os.fspath(out))


def _run(config, data, folder, plot, progress, kept):
    summary = _stochnav._run_into_folder(config, data, folder, plot, progress)
    tables = {}
    for field, name in _RUN_TABLES.items():
        path = os.path.join(folder, name)
        tables[field] = read_columns(path) if os.path.exists(path) else None
    return RunResult(metrics=summary["metrics"], epochs=summary["epochs"],
                     duration_s=summary["duration_s"], wall_seconds=summary["wall_seconds"],
                     filter_ok=summary["filter_ok"], warnings=summary["warnings"], out=kept,
                     **tables)


@dataclasses.dataclass
class CompareResult:
    """A comparison (stochnav.compare): results is results.json (per variant "fitted",
    "consistency", metrics over the seeds, and the "pairs"), table is table.md; for a sweep,
    sweep is sweep.json and the others are None."""

    results: typing.Optional[dict]
    table: typing.Optional[str]
    sweep: typing.Optional[dict]
    out: typing.Optional[str]

    def __repr__(self):
        if self.sweep is not None:
            return f"<CompareResult: sweep over {len(self.sweep['levels'])} levels>"
        return self.table


def compare(experiment, seeds=None, out=None, progress=False):
    """Compare filter variants on the same data over Monte-Carlo seeds (``stochnav compare``).

    Parameters
    ----------
    experiment : dict or path
        The experiment (configs/experiments/*.json, docs/compare-and-cluster.md).
    seeds : list of int, optional
        Replace the experiment's seeds (simulated data only).
    out : path, optional
        Keep results.json, table.md and the plots there; default a temporary folder.
    progress : bool
        A progress bar on standard error.

    Returns
    -------
    CompareResult
        results (results.json as a dict) and table (table.md), or sweep (sweep.json).
    """
    if out is None:
        with tempfile.TemporaryDirectory(prefix="stochnav_compare_") as folder:
            return _compare(experiment, seeds, os.path.join(folder, "compare"), progress, None)
    return _compare(experiment, seeds, os.fspath(out), progress, os.fspath(out))


def _compare(experiment, seeds, folder, progress, kept):
    summary = _stochnav._compare_into_folder(experiment, seeds, folder, progress)
    return CompareResult(results=summary.get("results"), table=summary.get("table"),
                         sweep=summary.get("sweep"), out=kept)
