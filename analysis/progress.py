"""The one progress and cancel protocol of long computations (issue 21).

Every long computation of zwidth -- design charts, exact sweeps, stability maps, simulations,
Z-width regions, filter optima, fits, robust designs, the report -- follows one rule:

* it takes two optional keyword hooks: ``progress(done, total)`` (:data:`Progress`), called
  after each step, and ``cancelled() -> bool`` (:data:`Cancelled`), polled between steps (a fit
  polls it before every model evaluation);
* inside, it stops by raising :class:`OperationCancelled` (:func:`check_cancelled`), never by
  returning a sentinel that every layer would have to pass up;
* at the public boundary, the functions documented to return ``None`` once cancelled (the
  charts and sweeps of :mod:`analysis.twoport` and :mod:`analysis.sampled`, the computations of
  :mod:`analysis.study`) keep doing so: scripts rely on it.  They turn the exception into
  ``None`` with one helper, the decorator :func:`none_if_cancelled`, and nothing else catches
  it.  :func:`analysis.identify.fit_chain` raises it, as it always did (its former name
  ``FitCancelled``), and so does the report (``ReportCancelled``);
* the app's worker (``app.core.worker``) drops a cancelled job quietly either way: a ``None``
  result or an :class:`OperationCancelled` raised by the job.

``analysis.identify.FitCancelled`` and ``app.report.model.ReportCancelled`` are aliases of
:class:`OperationCancelled`, kept for one release; ``Progress`` and ``Cancelled`` are still
importable from :mod:`analysis.twoport` and ``app.core.compute_graph``, which re-export these.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import ParamSpec, TypeVar

__all__ = ["Progress", "Cancelled", "OperationCancelled", "check_cancelled", "report_progress",
           "none_if_cancelled"]

#: ``progress(done, total)``: called by a long computation after each of its ``total`` steps
Progress = Callable[[int, int], None]
#: ``cancelled() -> bool``: polled by a long computation between steps; true stops it
Cancelled = Callable[[], bool]

_P = ParamSpec("_P")
_R = TypeVar("_R")


class OperationCancelled(Exception):
    """A long computation stopped because its ``cancelled()`` hook returned true.

    Not a ``ValueError``: code that turns bad input into an error row or message never
    swallows a cancel.

    Parameters
    ----------
    message : str, optional
        What stopped, e.g. ``"the fit was cancelled"``.
    """

    def __init__(self, message: str = "cancelled") -> None:
        super().__init__(message)


def check_cancelled(cancelled: Cancelled | None, message: str = "cancelled") -> None:
    """Raise :class:`OperationCancelled` when the hook says so (``None``: never cancelled).

    Parameters
    ----------
    cancelled : Cancelled or None
        The computation's ``cancelled() -> bool`` hook, or ``None``.
    message : str, optional
        The exception's message.

    Raises
    ------
    OperationCancelled
        When ``cancelled()`` returns true.
    """
    if cancelled is not None and cancelled():
        raise OperationCancelled(message)


def report_progress(progress: Progress | None, done: int, total: int) -> None:
    """Call ``progress(done, total)`` unless the hook is ``None``.

    Parameters
    ----------
    progress : Progress or None
        The computation's progress hook, or ``None``.
    done : int
        Steps done, ``0 <= done <= total``.
    total : int
        Number of steps.
    """
    if progress is not None:
        progress(int(done), int(total))


def none_if_cancelled(func: Callable[_P, _R]) -> Callable[_P, _R | None]:
    """Decorate a public computation so that it returns ``None`` once cancelled.

    The one place where :class:`OperationCancelled` becomes ``None`` (the module's rule): the
    decorated function's body raises it (:func:`check_cancelled`) wherever it polls its hook.

    Parameters
    ----------
    func : callable
        The computation; its body may raise :class:`OperationCancelled`.

    Returns
    -------
    callable
        The same computation (same signature and docstring), returning ``None`` instead of
        raising :class:`OperationCancelled`.
    """

    @functools.wraps(func)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R | None:
        try:
            return func(*args, **kwargs)
        except OperationCancelled:
            return None

    return wrapper
