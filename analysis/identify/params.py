"""Parameter keys of a chain and the map between a :class:`~analysis.Device` and vectors.

Keys follow the profile's JSON names with 0-based indices: ``masses[i]`` (handle ``i = 0``,
actuator ``i = n - 1``, Adams et al. eq. 25), ``stiffnesses[i]`` and ``dampings[i]`` (element
``i`` joins mass ``i`` and ``i + 1``), ``ground_dampings[i]`` (damper from mass ``i`` to
ground; the paper's rigid-body damping ``b4`` of the HBFD is ``ground_dampings[3]``).

:class:`ChainParameters` is the batched form used by the model kernels: arrays of shape
``(P, n)`` / ``(P, n - 1)`` for ``P`` parameter sets at once (finite-difference Jacobians and
box searches evaluate many devices in one call).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from analysis.chain.device import Device
from analysis.identify.errors import ParameterKeyError

__all__ = ["FIELDS", "ChainParameters", "parameter_keys", "parameter_symbol", "parse_key", "device_value",
           "device_with", "device_values", "physical_range", "LOG_FLOOR"]

#: The four vector fields of a chain, in the order of :func:`parameter_keys`.
FIELDS = ("masses", "stiffnesses", "dampings", "ground_dampings")
#: Smallest value a parameter fitted in log space may take where the physical range starts at 0
#: (a lossless element or no damper to ground cannot be reached in log space).
LOG_FLOOR = 1e-9


def _physical(name: str) -> tuple[float, float]:
    """``(lo, hi)`` of a field from :data:`analysis.chain.limits.LIMITS` (the one definition of the
    physical ranges that :class:`~analysis.Device` enforces)."""
    try:
        from analysis.chain.limits import LIMITS
    except ImportError:  # pragma: no cover - a tree without the limits module: no range
        return 0.0, float("inf")
    lim = LIMITS[name]
    return float(lim.lo), float(lim.hi)


def physical_range(key: str, n: int) -> tuple[float, float]:
    """Physical ``(lo, hi)`` of the parameter ``key``, with ``lo`` raised to :data:`LOG_FLOOR`."""
    name, _ = parse_key(key, n)
    lo, hi = _physical(name)
    return max(lo, LOG_FLOOR), hi


_KEY = re.compile(r"^\s*(masses|stiffnesses|dampings|ground_dampings)\[(\d+)\]\s*$")


def parse_key(key: str, n: int) -> tuple[str, int]:
    """``"masses[2]"`` -> ``("masses", 2)``, checked against a chain of ``n`` masses."""
    mt = _KEY.match(str(key))
    if mt is None:
        raise ParameterKeyError(key, "a key like masses[0], stiffnesses[1], dampings[0] or ground_dampings[3]")
    name, i = mt.group(1), int(mt.group(2))
    size = n if name in ("masses", "ground_dampings") else n - 1
    if i >= size:
        raise ParameterKeyError(key, f"index 0..{size - 1} for {name} of a {n}-mass chain")
    return name, i


@lru_cache(maxsize=256)
def _slots(keys: tuple[str, ...], n: int) -> tuple[tuple[str, int], ...]:
    """:func:`parse_key` of each of ``keys`` (read once per key set, not at each of the thousands of
    model evaluations of a fit; a bad key raises as :func:`parse_key` does and is not cached)."""
    return tuple(parse_key(k, n) for k in keys)


def parameter_keys(n: int, ground: Iterable[int] | None = None) -> list[str]:
    """Keys of an ``n``-mass chain: masses, stiffnesses, dampings, then the selected ground
    dampings (``ground=None``: all ``n``).

    Parameters
    ----------
    n : int
        Number of masses of the chain.
    ground : iterable of int or None, optional
        Indices (0-based, handle 0) of the masses whose damper to ground is a parameter;
        ``None`` for all ``n``.  Duplicates are dropped and the indices sorted.

    Returns
    -------
    list of str
        ``n`` mass keys, ``n - 1`` stiffness keys, ``n - 1`` damping keys and the selected
        ground-damping keys, in that order (e.g. ``"masses[0]"``).
    """
    gs = range(n) if ground is None else sorted(set(int(g) for g in ground))
    return ([f"masses[{i}]" for i in range(n)] + [f"stiffnesses[{i}]" for i in range(n - 1)]
            + [f"dampings[{i}]" for i in range(n - 1)] + [f"ground_dampings[{i}]" for i in gs])


#: Each field's symbol and unit, as the device editor shows them (m₁ the handle's mass).
_SYMBOLS = {"masses": ("m", "kg"), "stiffnesses": ("k", "N/m"), "dampings": ("b", "N·s/m"),
            "ground_dampings": ("g", "N·s/m")}
_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def parameter_symbol(key: str) -> tuple[str, str]:
    """The symbol a person reads for a parameter key, 1-based as the device editor shows it, and its unit.

    ``"masses[0]"`` -> ``("m₁", "kg")``, ``"dampings[2]"`` -> ``("b₃", "N·s/m")``; the keys stay
    0-based in files and on the command line.  A key of another form is returned as it is, with no unit.

    Parameters
    ----------
    key : str
        A key of :func:`parameter_keys`.

    Returns
    -------
    tuple of str
        The symbol (Unicode subscript digits) and the SI unit.
    """
    mt = _KEY.match(str(key))
    if mt is None:
        return str(key), ""
    symbol, unit = _SYMBOLS[mt.group(1)]
    return symbol + str(int(mt.group(2)) + 1).translate(_SUBSCRIPT), unit


def device_value(device: Device, key: str) -> float:
    """The value of one parameter of ``device``.

    Parameters
    ----------
    device : Device
        The chain.
    key : str
        A parameter key such as ``"masses[0]"`` or ``"ground_dampings[3]"`` (module doc).

    Returns
    -------
    float
        The parameter's value in its unit: kg, N/m or N s/m.

    Raises
    ------
    ParameterKeyError
        When ``key`` does not name a parameter of ``device``'s chain (by :func:`parse_key`).
    """
    name, i = parse_key(key, device.n)
    return float(getattr(device, name)[i])


def device_values(device: Device, keys: Iterable[str]) -> np.ndarray:
    """The values of several parameters of ``device``."""
    return np.array([device_value(device, k) for k in keys], dtype=float)


def device_with(device: Device, values: Mapping[str, float]) -> Device:
    """A copy of ``device`` with the given parameters changed (validated by :class:`Device`).

    Parameters
    ----------
    device : Device
        The chain to copy; its other settings (sensor element, sample time, band) are kept.
    values : mapping of str to float
        ``{key: value}`` of the parameters to change, in kg, N/m or N s/m.

    Returns
    -------
    Device
        The changed copy; ``device`` itself is not modified.

    Raises
    ------
    ParameterKeyError
        When a key does not name a parameter of the chain (by :func:`parse_key`).
    ValidationError
        When a new value is outside the range :class:`Device` accepts.
    """
    arrays = {f: np.array(getattr(device, f), dtype=float) for f in FIELDS}
    for key, v in values.items():
        name, i = parse_key(key, device.n)
        arrays[name][i] = float(v)
    return device.replace(**arrays)


@dataclass(frozen=True)
class ChainParameters:
    """``P`` chains of ``n`` masses as arrays: ``masses`` (P, n), ``stiffnesses`` (P, n-1),
    ``dampings`` (P, n-1), ``ground_dampings`` (P, n).

    Parameters
    ----------
    masses : numpy.ndarray
        Masses [kg], handle first (column 0), actuator last, shape (P, n).
    stiffnesses : numpy.ndarray
        Element stiffnesses [N/m], element ``i`` between mass ``i`` and ``i + 1``, shape (P, n - 1).
    dampings : numpy.ndarray
        Element dampings [N s/m], shape (P, n - 1).
    ground_dampings : numpy.ndarray
        Dampings from each mass to ground [N s/m], shape (P, n).
    """

    masses: np.ndarray
    stiffnesses: np.ndarray
    dampings: np.ndarray
    ground_dampings: np.ndarray

    @property
    def n(self) -> int:
        return int(self.masses.shape[1])

    @property
    def count(self) -> int:
        return int(self.masses.shape[0])

    @classmethod
    def from_device(cls, device: Device) -> ChainParameters:
        """The one chain of ``device`` as a batch of size 1 (the arrays are copies).

        Parameters
        ----------
        device : Device
            The chain.

        Returns
        -------
        ChainParameters
            ``P = 1`` chain with ``device``'s masses, stiffnesses, dampings and ground dampings.
        """
        return cls(device.masses[None, :].copy(), device.stiffnesses[None, :].copy(),
                   device.dampings[None, :].copy(), device.ground_dampings[None, :].copy())

    @classmethod
    def from_rows(cls, keys: list[str], rows: np.ndarray, base: ChainParameters) -> ChainParameters:
        """``base`` (one chain) broadcast to ``len(rows)`` chains with ``keys`` set from ``rows``.

        Parameters
        ----------
        keys : list of str
            The parameter keys set from the columns of ``rows`` (module doc).
        rows : numpy.ndarray
            Parameter values (kg, N/m, N s/m), shape (P, len(keys)); one row (shape (len(keys),))
            is taken as ``P = 1``.
        base : ChainParameters
            Its first chain supplies every parameter not in ``keys``.

        Returns
        -------
        ChainParameters
            ``P`` chains of ``base.n`` masses, new arrays.

        Raises
        ------
        ParameterKeyError
            When a key does not name a parameter of an ``n``-mass chain (by :func:`parse_key`).
        """
        rows = np.atleast_2d(np.asarray(rows, dtype=float))
        P = rows.shape[0]
        arrays = {f: np.repeat(getattr(base, f)[:1], P, axis=0) for f in FIELDS}
        for j, (name, i) in enumerate(_slots(tuple(keys), base.n)):
            arrays[name][:, i] = rows[:, j]
        return cls(**arrays)

    def device(self, row: int, template: Device | None = None, **kwargs) -> Device:
        """Chain ``row`` as a :class:`Device` (sensor element, sample time and band from
        ``template`` or ``kwargs``).

        Parameters
        ----------
        row : int
            Index of the chain in the batch, ``0 <= row < P``.
        template : Device or None, optional
            A device whose other settings are kept (:meth:`Device.replace`); ``None``: a new
            :class:`Device` from the chain and ``kwargs``.
        **kwargs
            Further :class:`Device` fields, e.g. ``sensor_element``, ``sample_time``, ``band_min``.

        Returns
        -------
        Device
            The chain as a validated device.

        Raises
        ------
        ValidationError
            When a value is outside the range :class:`Device` accepts.
        """
        data = {f: getattr(self, f)[row] for f in FIELDS}
        if template is not None:
            return template.replace(**data, **kwargs)
        return Device(**data, **kwargs)
