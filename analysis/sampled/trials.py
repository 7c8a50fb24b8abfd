"""Hardware Z-width trials scored against the exact region (and, for the old import path, the
optimum velocity filter, now :mod:`analysis.sampled.filter_optimum`).

Measured trials
---------------
Colgate & Brown (ICRA 1994) measured the Z-width point by point: a wall ``(B, K)`` is tried on
the hardware and judged stable or not.  :func:`load_trials` reads such a CSV with the one CSV reader
(:func:`analysis.csvtable.read_table`: UTF-8, a header row, blank lines and ``#`` comments
skipped): columns ``b`` and ``k`` (finite, >= 0) and ``stable`` (``1`` or ``0``, nothing else),
in any order, other columns ignored; every problem is a :class:`TrialsError` (a
:class:`~analysis.errors.ValidationError`) naming the file, the line and the column.  :func:`score_trials` compares each trial with the region
(:meth:`~analysis.sampled.zwidth.ZWidthRegion.k_limit`) and lists those the analysis gets wrong.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from analysis.csvtable import CsvError, read_table
from analysis.errors import ValidationError
from analysis.sampled.filter_optimum import FilterOptimum, optimal_filter
from analysis.sampled.zwidth import ZWidthRegion

__all__ = ["FilterOptimum", "optimal_filter", "MeasuredTrials", "TRIAL_COLUMNS", "STABLE_VALUES", "TrialsError",
           "load_trials", "TrialScore", "score_trials"]

#: The columns of a trials file (any order; other columns are ignored).
TRIAL_COLUMNS = ("b", "k", "stable")


@dataclass(frozen=True)
class MeasuredTrials:
    """Hardware trials: wall damping ``b`` (N s/m), stiffness ``k`` (N/m), ``stable`` flags, file lines.

    Parameters
    ----------
    path : str
        The CSV file read.
    b : numpy.ndarray
        Wall damping of each trial [N s/m], shape (M,).
    k : numpy.ndarray
        Wall stiffness of each trial [N/m], shape (M,).
    stable : numpy.ndarray
        Whether each trial was stable, bool, shape (M,).
    lines : numpy.ndarray
        File line of each trial, shape (M,).
    """

    path: str
    b: np.ndarray
    k: np.ndarray
    stable: np.ndarray
    lines: np.ndarray

    def __len__(self) -> int:
        return int(self.b.size)


class TrialsError(CsvError, ValidationError):
    """A trials file that cannot be used: a :class:`~analysis.csvtable.CsvError` (``file``, ``line``,
    ``column``, ``reason``) that is also a :class:`~analysis.errors.ValidationError` (``field`` is
    the place, ``allowed`` the reason), so that every caller of a validation error shows it."""

    def __init__(self, reason: str, *, file: str | os.PathLike | None = None, line: int | None = None,
                 column: str | None = None):
        CsvError.__init__(self, reason, file=file, line=line, column=column)
        self.field, self.allowed, self.value, self.index, self.within = self.where, reason, None, None, ()


#: The spellings of the ``stable`` column (the guide: "stable (1 or 0)").
STABLE_VALUES = {"1": 1.0, "0": 0.0}


def load_trials(path: str | os.PathLike) -> MeasuredTrials:
    """Read a CSV of trials (module docstring) with :func:`analysis.csvtable.read_table`.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file (relative paths: to the working directory; a profile's is resolved by
        :func:`analysis.study.profile_trials`).

    Returns
    -------
    MeasuredTrials
        The trials in file order, with the file line of each.

    Raises
    ------
    TrialsError
        For every fault, naming the file, the line and the column (a
        :class:`~analysis.errors.ValidationError`).
    """
    t = read_table(path, TRIAL_COLUMNS, required=TRIAL_COLUMNS, other_columns=True,
                   choices={"stable": STABLE_VALUES}, error=TrialsError)
    if not len(t):
        raise t.fail("a header only: at least one trial row is needed")
    for col in ("b", "k"):
        bad = np.flatnonzero(t.columns[col] < 0)
        if bad.size:
            raise t.fail(f"{float(t.columns[col][bad[0]])!r} is negative: must be >= 0", int(bad[0]), col)
    return MeasuredTrials(path=t.path, b=t.columns["b"], k=t.columns["k"], stable=t.columns["stable"] == 1.0,
                          lines=t.lines)


@dataclass(frozen=True)
class TrialScore:
    """Trials against a region: ``predicted`` stable flags, ``wrong`` indices (analysis disagrees),
    ``outside`` indices (B outside the region's range: not scored).

    Parameters
    ----------
    predicted : numpy.ndarray
        Predicted stable flag of each trial, bool, shape (M,) (False outside the range).
    wrong : numpy.ndarray
        Indices of the scored trials where prediction and measurement disagree.
    outside : numpy.ndarray
        Indices of the trials whose B is outside the region's range.
    scored : int
        Number of trials scored (inside the range).
    """

    predicted: np.ndarray
    wrong: np.ndarray
    outside: np.ndarray
    scored: int

    @property
    def wrong_count(self) -> int:
        return int(self.wrong.size)

    def describe(self, trials: MeasuredTrials) -> list[str]:
        """One line per wrong trial: file line, (B, K), measured and predicted.

        Parameters
        ----------
        trials : MeasuredTrials
            The trials that were scored.

        Returns
        -------
        list of str
            One line per index of ``wrong``.
        """
        word = {True: "stable", False: "unstable"}
        return [f"line {trials.lines[i]}: B = {trials.b[i]:.4g} N s/m, K = {trials.k[i]:.4g} N/m measured "
                f"{word[bool(trials.stable[i])]}, predicted {word[bool(self.predicted[i])]}" for i in self.wrong]


def score_trials(region: ZWidthRegion, trials: MeasuredTrials) -> TrialScore:
    """Predicted stable iff ``k <= K_max(b)`` of the region (interpolated in log B).

    Parameters
    ----------
    region : ZWidthRegion
        The exact region.
    trials : MeasuredTrials
        The hardware trials.

    Returns
    -------
    TrialScore
        The predictions and the disagreements.
    """
    lim = region.k_limit(trials.b)
    outside = np.isnan(lim)
    predicted = np.where(outside, False, trials.k <= np.nan_to_num(lim, nan=0.0))
    wrong = np.flatnonzero(~outside & (predicted != trials.stable))
    return TrialScore(predicted=predicted, wrong=wrong, outside=np.flatnonzero(outside),
                      scored=int(np.count_nonzero(~outside)))
