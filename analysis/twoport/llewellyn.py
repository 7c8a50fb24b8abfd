"""Two-port tools: Llewellyn's criterion (eq. 1), the factor eta, and conversions.

An immittance array ``P`` maps ``(v1, -v2)``-type flows to forces in one of four forms:
impedance ``Z``, admittance ``Y``, hybrid ``H`` and alternate hybrid ``G``.  Llewellyn's
criterion for unconditional stability (eq. 1) reads, in any of them::

    Re p11 >= 0,   2 Re p11 Re p22 >= |p12 p21| + Re(p12 p21)   for all w,

and ``eta = (2 Re p11 Re p22 - Re(p12 p21)) / |p12 p21| >= 1`` (with ``Re p11 >= 0``) is
the same number whichever form is used (Rollett's invariance).
"""

from __future__ import annotations

import numpy as np

from analysis.twoport.results import TwoPort

__all__ = ["llewellyn", "eta", "convert", "FORMS"]

FORMS = ("z", "y", "h", "g")


def _arrays(p: TwoPort | tuple) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    if isinstance(p, TwoPort):
        return p.p11, p.p12, p.p21, p.p22
    a, b, c, d = (np.asarray(x, dtype=complex) for x in p)
    return a, b, c, d


def llewellyn(p: TwoPort | tuple) -> np.ndarray:
    """Boolean array: Llewellyn's conditions (eq. 1) hold at each frequency.

    Parameters
    ----------
    p : TwoPort or tuple of array_like
        The immittance array: a :class:`TwoPort`, or ``(p11, p12, p21, p22)``, each of
        shape (N,) (one value per frequency).

    Returns
    -------
    numpy.ndarray
        Booleans, shape (N,): ``Re p11 >= 0``, ``Re p22 >= 0`` and
        ``2 Re p11 Re p22 >= |p12 p21| + Re(p12 p21)``.
    """
    p11, p12, p21, p22 = _arrays(p)
    q = p12 * p21
    return (p11.real >= 0) & (p22.real >= 0) & (2 * p11.real * p22.real >= np.abs(q) + q.real)


def eta(p: TwoPort | tuple) -> np.ndarray:
    """Llewellyn/Rollett stability factor; ``>= 1`` with ``Re p11 >= 0`` means stable.

    Parameters
    ----------
    p : TwoPort or tuple of array_like
        The immittance array: a :class:`TwoPort`, or ``(p11, p12, p21, p22)``, each of
        shape (N,) (one value per frequency).

    Returns
    -------
    numpy.ndarray
        ``eta = (2 Re p11 Re p22 - Re(p12 p21)) / |p12 p21|`` (dimensionless), shape (N,);
        inf or NaN where ``p12 p21 = 0``.
    """
    p11, p12, p21, p22 = _arrays(p)
    q = p12 * p21
    with np.errstate(divide="ignore", invalid="ignore"):
        return (2 * p11.real * p22.real - q.real) / np.abs(q)


def _swap(form: str, a, b, c, d):
    """Between ``z`` and ``form``; each of these maps is its own inverse."""
    if form == "z":
        return a, b, c, d
    if form == "y":  # matrix inverse
        det = a * d - b * c
        return d / det, -b / det, -c / det, a / det
    if form == "h":  # [F1; v2] = H [v1; F2]
        return a - b * c / d, b / d, -c / d, 1 / d
    if form == "g":  # [v1; F2] = G [F1; v2]
        return 1 / a, -b / a, c / a, d - b * c / a
    raise ValueError(f"unknown two-port form {form!r}; use one of {FORMS}")


def convert(p: TwoPort | tuple, src: str, dst: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Convert a 2x2 immittance array between the forms ``z``, ``y``, ``h`` and ``g``.

    Parameters
    ----------
    p : TwoPort or tuple of array_like
        The immittance array: a :class:`TwoPort`, or ``(p11, p12, p21, p22)``, each of
        shape (N,) (one value per frequency).
    src : str
        The form of ``p``: one of :data:`FORMS`.
    dst : str
        The form wanted: one of :data:`FORMS`.

    Returns
    -------
    tuple of numpy.ndarray
        ``(q11, q12, q21, q22)`` in the form ``dst``, each complex of shape (N,).

    Raises
    ------
    ValueError
        When ``src`` or ``dst`` is not one of :data:`FORMS`.
    """
    a, b, c, d = _arrays(p)
    return _swap(dst, *_swap(src, a, b, c, d))
