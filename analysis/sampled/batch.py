"""A batch of devices: one per-device computation mapped over many devices, and the robust space (issue 24).

Users build more than one device, and identification gives a model with uncertainty (the
parameter box of :func:`analysis.identify.parameter_box`).  The **robust space** of a batch is
the intersection of the devices' spaces: for every cell of a grid, the smallest of the devices'
``k_max`` (a cell is renderable by the whole batch up to the K every device renders), and which
device binds it.

* :func:`map_devices` runs a picklable ``fn(device) -> array`` over the devices and returns the
  results in the devices' order; :func:`intersect_devices` reduces them to the elementwise
  minimum (:class:`RobustSpace`); :func:`robust_renderable_space` does so for
  :func:`~analysis.sampled.renderable.renderable_space`, for the space and for each quality.
* Where it runs: in this process (``workers=1``); on a local process pool
  (:class:`concurrent.futures.ProcessPoolExecutor`, ``workers=None`` for one per CPU, the
  default); or on a Dask distributed cluster when ``client=`` (a ``dask.distributed.Client``)
  is given.  Dask is an optional extra (``zwidth[distributed]``): this module never imports it
  (it only calls the client's methods, and ``distributed.wait`` through :mod:`importlib` once a
  client is given).
* Devices are sent in chunks of consecutive devices, one task each (``chunk_size``, by default
  about four tasks per worker and at most :data:`MAX_CHUNK` devices), to amortize the per-task
  overhead.  A chunk reduces its own devices when only the minimum is wanted, so a task returns
  one grid, not one per device.
* Deterministic: the minimum is exact (no rounding), and a tie keeps the lowest device index,
  in a chunk and between chunks, so the result is the same bit for bit for any number of
  workers, any chunk size and on a cluster.
* Progress and cancel follow :mod:`analysis.progress`: ``progress(done, total)`` counts devices
  as their chunks finish; ``cancelled()`` is polled between devices in this process and every
  :data:`POLL_SECONDS` while a pool or a cluster works, and stops the batch with
  :class:`~analysis.progress.OperationCancelled` at once: chunks not started are cancelled,
  the chunks already running finish in their workers and are dropped.
* A device whose computation fails stops the batch with :class:`DeviceFailed`, which names the
  device's index and the original error; when several fail, the lowest index is reported.

Devices from a parameter box: :func:`box_corners` (its ``2^p`` corners) and :func:`box_samples`
(``n`` points drawn uniformly in its coordinates by a seeded :func:`numpy.random.default_rng`:
the same seed gives the same devices), for any box with ``dim`` and ``device_at(u)`` such as
:class:`analysis.identify.ParameterBox`.
"""

from __future__ import annotations

import concurrent.futures as cf
import importlib
import itertools
import math
import multiprocessing
import os
import pickle
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import partial
from types import MappingProxyType
from typing import Any, Protocol

import numpy as np

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.errors import ValidationError
from analysis.progress import Cancelled, OperationCancelled, Progress, check_cancelled, report_progress
from analysis.sampled.qualities import QualitySettings, check_qualities
from analysis.sampled.renderable import renderable_space, space_volume
from analysis.sampled.rendered import AccelerationEstimate

__all__ = ["MAX_CHUNK", "MAX_DEVICES", "POLL_SECONDS", "DeviceBox", "DeviceFailed", "RobustSpace",
           "RobustRenderableSpace", "map_devices", "intersect_devices", "robust_renderable_space",
           "box_corners", "box_samples", "default_workers"]

#: Most devices in one task: bounds how long a cancel waits for the chunks already running.
MAX_CHUNK = 16
#: Most devices in one batch (corners or samples of a box).
MAX_DEVICES = 100_000
#: Seconds between two polls of ``cancelled()`` while a pool or a cluster works.
POLL_SECONDS = 0.05


class DeviceBox(Protocol):
    """What a box of devices offers (:class:`analysis.identify.ParameterBox` does)."""

    @property
    def dim(self) -> int:
        """Number of boxed parameters ``p``."""

    def device_at(self, u: np.ndarray) -> Device:
        """The device at box coordinates ``u`` in ``[0, 1]^p``."""


class DeviceFailed(RuntimeError):
    """The computation of one device of a batch raised an error.

    Parameters
    ----------
    index : int
        The device's index in the batch (from 0).
    detail : str
        The original error's type and message.

    Attributes
    ----------
    index : int
        The device's index in the batch.
    detail : str
        The original error's type and message.
    """

    def __init__(self, index: int, detail: str) -> None:
        super().__init__(index, detail)  # the args rebuild it after pickling (pool, cluster)
        self.index = int(index)
        self.detail = str(detail)

    def __str__(self) -> str:
        return f"device {self.index} of the batch failed: {self.detail}"


@dataclass(frozen=True)
class RobustSpace:
    """The elementwise minimum of the devices' results and which device binds each cell.

    Parameters
    ----------
    k_max : numpy.ndarray
        The smallest value of each cell over the devices, the shape of one result (read-only).
    binding : numpy.ndarray
        Index (from 0) of the device with that smallest value, the lowest on a tie; int, the
        shape of ``k_max`` (read-only).
    devices : int
        Number of devices in the batch.
    """

    k_max: np.ndarray
    binding: np.ndarray
    devices: int


@dataclass(frozen=True)
class RobustRenderableSpace:
    """The renderable (M, B, K) space that every device of a batch has (read-only arrays).

    Parameters
    ----------
    mass : numpy.ndarray
        Virtual masses M [kg], shape (NM,).
    damping : numpy.ndarray
        Virtual dampings B [N s/m], shape (NB,).
    k_max : numpy.ndarray
        ``k_max[i, j]`` [N/m]: the smallest over the devices of their ``k_max`` (every quality),
        shape (NM, NB).
    by_quality : Mapping of str to numpy.ndarray
        The same for each quality asked, shape (NM, NB) each.
    binding : numpy.ndarray
        Index of the device that binds ``k_max[i, j]`` (the lowest on a tie), shape (NM, NB).
    qualities : tuple of str
        The qualities asked.
    devices : int
        Number of devices in the batch.
    volume : float
        The volume of the robust space ``k_max`` [kg decades^2], by the one rule of a single
        device's space (:func:`~analysis.sampled.renderable.space_volume`), so that the two
        compare: at most every device's own volume.
    """

    mass: np.ndarray
    damping: np.ndarray
    k_max: np.ndarray
    by_quality: Mapping[str, np.ndarray]
    binding: np.ndarray
    qualities: tuple[str, ...]
    devices: int
    volume: float


# -- devices from a box -------------------------------------------------------------------------
def box_corners(box: DeviceBox) -> list[Device]:
    """The devices at the ``2^p`` corners of a box, in binary order (the last parameter fastest).

    Parameters
    ----------
    box : DeviceBox
        E.g. an :class:`analysis.identify.ParameterBox`.

    Returns
    -------
    list of Device
        ``2^p`` devices; corner ``c`` has parameter ``j`` at its high end when bit ``p-1-j`` of
        ``c`` is set.

    Raises
    ------
    ValidationError
        When ``2^p`` exceeds :data:`MAX_DEVICES` (``box``), or a corner is a device that
        :class:`~analysis.Device` refuses.
    """
    p = int(box.dim)
    if 2 ** p > MAX_DEVICES:
        raise ValidationError("box", f"at most {MAX_DEVICES} corners (p <= {int(math.log2(MAX_DEVICES))})",
                              f"{p} parameters")
    return [box.device_at(np.array(c, dtype=float)) for c in itertools.product((0.0, 1.0), repeat=p)]


def box_samples(box: DeviceBox, n: int, seed: int = 0) -> list[Device]:
    """``n`` devices drawn uniformly in the box's coordinates (logarithmic for a positive range).

    Parameters
    ----------
    box : DeviceBox
        E.g. an :class:`analysis.identify.ParameterBox`.
    n : int
        Number of devices, 1 to :data:`MAX_DEVICES`.
    seed : int, optional
        Seed of :func:`numpy.random.default_rng`: the same seed gives the same devices.

    Returns
    -------
    list of Device
        The devices at the rows of ``default_rng(seed).random((n, p))``.

    Raises
    ------
    ValidationError
        For ``n`` outside 1 to :data:`MAX_DEVICES` or a negative ``seed``.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= MAX_DEVICES:
        raise ValidationError("n", f"an integer from 1 to {MAX_DEVICES}", n)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValidationError("seed", "an integer >= 0", seed)
    u = np.random.default_rng(int(seed)).random((int(n), int(box.dim)))
    return [box.device_at(row) for row in u]


# -- the tasks (module level: a pool pickles them by reference) -------------------------------------
def _evaluate(fn: Callable[[Any], Any], index: int, device: Any) -> np.ndarray:
    try:
        r = np.asarray(fn(device), dtype=float)
    except Exception as exc:  # any failure of the user's function is the device's
        raise DeviceFailed(index, f"{type(exc).__name__}: {exc}") from None
    if np.isnan(r).any():
        raise DeviceFailed(index, "its result has NaN")
    return r


def _map_chunk(fn: Callable[[Any], Any], start: int, devices: Sequence[Any]) -> list[np.ndarray]:
    return [_evaluate(fn, i, d) for i, d in enumerate(devices, start)]


def _merge(acc: tuple[np.ndarray, np.ndarray] | None, value: np.ndarray, where: np.ndarray | int,
           index: int) -> tuple[np.ndarray, np.ndarray]:
    """Fold one result (or a chunk's minimum) into the running minimum; a tie keeps the earlier."""
    if acc is None:
        return value.copy(), np.broadcast_to(np.asarray(where, dtype=np.int64), value.shape).copy()
    low, bind = acc
    if value.shape != low.shape:
        raise DeviceFailed(index, f"its result has shape {value.shape}, the earlier devices' {low.shape}")
    better = value < low
    return np.where(better, value, low), np.where(better, where, bind)


def _min_chunk(fn: Callable[[Any], Any], start: int, devices: Sequence[Any]) -> tuple[np.ndarray, np.ndarray]:
    acc = None
    for i, d in enumerate(devices, start):
        acc = _merge(acc, _evaluate(fn, i, d), i, i)
    return acc


# -- running the chunks ------------------------------------------------------------------------------
def default_workers() -> int:
    """The number of CPUs this process may use (the default pool size).

    Returns
    -------
    int
        ``len(os.sched_getaffinity(0))`` where the platform has it, else ``os.cpu_count()``.
    """
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def _check_int(name: str, value: object, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValidationError(name, f"an integer >= {low} or None", value)
    return int(value)


def _chunks(n: int, workers: int, chunk_size: int | None) -> list[tuple[int, int]]:
    size = (min(MAX_CHUNK, max(1, -(-n // (4 * workers)))) if chunk_size is None
            else _check_int("chunk_size", chunk_size, 1))
    return [(s, min(n, s + size)) for s in range(0, n, size)]


def _pool_context(fn: Callable) -> multiprocessing.context.BaseContext:
    """``forkserver`` on Linux (a process with threads, such as the GUI or a Dask client, must not
    fork), else ``spawn``.  The fork server imports this module (numpy, scipy, the sampled loop)
    and the first pool's function's module once, when it starts, and forks every worker from
    that state: a pool of 2 then starts in about 0.1 s instead of the 2.5 s per worker of an
    import from scratch (measured under load)."""
    if not sys.platform.startswith("linux"):
        return multiprocessing.get_context("spawn")
    ctx = multiprocessing.get_context("forkserver")
    home = getattr(getattr(fn, "func", fn), "__module__", None)  # a partial's function's module
    ctx.set_forkserver_preload([__name__] + ([home] if home and home not in ("__main__", __name__) else []))
    return ctx


def _collect(futures: list, wait: Callable, sizes: list[int], progress: Progress | None,
             cancelled: Cancelled | None) -> list:
    """Results of the chunks' futures in order; cancel stops at once; a failure of the lowest
    failing chunk is raised once every earlier chunk is known to succeed."""
    results: dict[int, object] = {}
    failures: dict[int, BaseException] = {}
    pending = dict(enumerate(futures))
    total, done = sum(sizes), 0
    try:
        while pending:
            if cancelled is not None and cancelled():
                raise OperationCancelled("the batch was cancelled")
            for k in [k for k, f in pending.items() if f.done()]:
                f = pending.pop(k)
                exc = f.exception()
                if exc is None:
                    results[k] = f.result()
                    done += sizes[k]
                    report_progress(progress, done, total)
                else:
                    failures[k] = exc
            if failures:
                first = min(failures)
                for k in [k for k in pending if k > first]:
                    pending.pop(k).cancel()
                if not pending:
                    raise failures[first]
            if pending:
                wait(list(pending.values()))
    finally:
        for f in pending.values():
            f.cancel()
    return [results[k] for k in range(len(futures))]


def _run(task: Callable, fn: Callable, devices: Sequence[Any], workers: int | None, client: Any,
         chunk_size: int | None, progress: Progress | None, cancelled: Cancelled | None) -> list:
    """The chunks' results, in order, in this process, on a pool or on a cluster."""
    n = len(devices)
    if n == 0:
        raise ValidationError("devices", "at least one device", devices)
    if client is not None and workers is not None:
        raise ValidationError("workers", "None when a client is given (the cluster has its own)", workers)
    if client is not None:
        count = max(1, len(client.scheduler_info().get("workers", ())))
    else:
        count = default_workers() if workers is None else _check_int("workers", workers, 1)
    spans = _chunks(n, count, chunk_size)
    sizes = [b - a for a, b in spans]
    report_progress(progress, 0, n)
    if client is None and (count == 1 or len(spans) == 1):
        out = []
        for i in range(n):  # one device per step: cancel and progress between devices
            check_cancelled(cancelled, "the batch was cancelled")
            out.append(task(fn, i, devices[i:i + 1]))
            report_progress(progress, i + 1, n)
        return out
    if client is not None:
        distributed = importlib.import_module("distributed")
        futures = [client.submit(task, fn, a, list(devices[a:b]), pure=False) for a, b in spans]
        wait = partial(distributed.wait, timeout=POLL_SECONDS, return_when="FIRST_COMPLETED")
        return _collect(futures, _quiet(wait), sizes, progress, cancelled)
    try:
        pickle.dumps(fn)
    except Exception as exc:
        raise ValidationError("fn", "a picklable function (a module-level function or a partial of one)",
                              fn) from exc
    pool = cf.ProcessPoolExecutor(max_workers=min(count, len(spans)), mp_context=_pool_context(fn))
    try:
        futures = [pool.submit(task, fn, a, devices[a:b]) for a, b in spans]
        wait = partial(cf.wait, timeout=POLL_SECONDS, return_when=cf.FIRST_COMPLETED)
        out = _collect(futures, wait, sizes, progress, cancelled)
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)
    return out


def _quiet(wait: Callable) -> Callable:
    """``distributed.wait`` raises ``TimeoutError`` when nothing finished in time: that is a poll."""

    def poll(futures: list) -> None:
        try:
            wait(futures)
        except TimeoutError:
            pass

    return poll


def _combine(parts: Sequence[tuple[np.ndarray, np.ndarray]]) -> tuple[np.ndarray, np.ndarray]:
    acc = None
    for low, bind in parts:  # in the devices' order: a tie keeps the earlier chunk's device
        acc = _merge(acc, low, bind, int(bind.flat[0]))
    return acc


def _read_only(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


# -- the public calls -----------------------------------------------------------------------------
def map_devices(fn: Callable[[Any], Any], devices: Sequence[Any], *, workers: int | None = None,
                client: Any = None, chunk_size: int | None = None, progress: Progress | None = None,
                cancelled: Cancelled | None = None) -> list[np.ndarray]:
    """``fn(device)`` for every device, in the devices' order (module docstring).

    Parameters
    ----------
    fn : callable
        ``fn(device) -> array_like`` of floats without NaN; picklable for a pool (a module-level
        function or a :func:`functools.partial` of one; a cluster takes what cloudpickle takes).
    devices : sequence
        The devices (picklable), at least one.
    workers : int or None, optional
        Processes of the local pool; 1 runs in this process; ``None`` for
        :func:`default_workers`.  Must be ``None`` when ``client`` is given.
    client : dask.distributed.Client or None, optional
        Run on this Dask cluster instead of a local pool.
    chunk_size : int or None, optional
        Devices per task; ``None`` for about four tasks per worker, at most :data:`MAX_CHUNK`.
    progress : callable, optional
        ``progress(done, total)`` in devices, as their chunks finish.
    cancelled : callable, optional
        ``cancelled() -> bool``, polled between devices or every :data:`POLL_SECONDS`.

    Returns
    -------
    list of numpy.ndarray
        ``fn``'s result for each device, as float arrays.

    Raises
    ------
    DeviceFailed
        When ``fn`` fails for a device or returns NaN (the lowest such index).
    ValidationError
        For no devices, a bad ``workers`` or ``chunk_size``, both ``workers`` and ``client``, or
        an ``fn`` a pool cannot pickle.
    OperationCancelled
        When ``cancelled()`` turns true.
    """
    parts = _run(_map_chunk, fn, list(devices), workers, client, chunk_size, progress, cancelled)
    return [r for chunk in parts for r in chunk]


def intersect_devices(fn: Callable[[Any], Any], devices: Sequence[Any], *, workers: int | None = None,
                      client: Any = None, chunk_size: int | None = None, progress: Progress | None = None,
                      cancelled: Cancelled | None = None) -> RobustSpace:
    """The robust space: the elementwise minimum of ``fn(device)`` over the devices (module docstring).

    Each task returns its chunk's minimum and binding devices, not every result.

    Parameters
    ----------
    fn : callable
        ``fn(device) -> array_like`` of floats without NaN, the same shape for every device,
        e.g. a ``k_max`` grid; picklable as for :func:`map_devices`.
    devices : sequence
        The devices (picklable), at least one.
    workers : int or None, optional
        Processes of the local pool; 1 runs in this process; ``None`` for :func:`default_workers`.
    client : dask.distributed.Client or None, optional
        Run on this Dask cluster instead of a local pool.
    chunk_size : int or None, optional
        Devices per task (:func:`map_devices`).
    progress : callable, optional
        ``progress(done, total)`` in devices.
    cancelled : callable, optional
        ``cancelled() -> bool``.

    Returns
    -------
    RobustSpace
        The minimum and the binding device of each cell; the same bit for bit wherever it ran.

    Raises
    ------
    DeviceFailed
        When ``fn`` fails for a device, returns NaN or a shape unlike the earlier devices'.
    ValidationError
        As for :func:`map_devices`.
    OperationCancelled
        When ``cancelled()`` turns true.
    """
    devices = list(devices)
    low, bind = _combine(_run(_min_chunk, fn, devices, workers, client, chunk_size, progress, cancelled))
    return RobustSpace(k_max=_read_only(low), binding=_read_only(bind), devices=len(devices))


def _grid_values(name: str, values: object) -> np.ndarray:
    try:
        return _read_only(np.array(values, dtype=float).reshape(-1))
    except (TypeError, ValueError) as exc:
        raise ValidationError(name, "real numbers", values) from exc


def _space_layers(device: Device, mass: np.ndarray, damping: np.ndarray, delay_samples: int,
                  velocity_filter: VelocityFilter | None, acceleration: AccelerationEstimate | None,
                  qualities: tuple[str, ...], settings: QualitySettings | None) -> np.ndarray:
    """One device's space as layers: ``k_max``, then each quality's (the per-device task)."""
    s = renderable_space(device, mass, damping, delay_samples, velocity_filter, acceleration, qualities,
                         settings=settings)
    return np.stack([s.k_max, *(s.by_quality[q] for q in qualities)])


def robust_renderable_space(devices: Sequence[Device], mass, damping, delay_samples: int = 1,
                            velocity_filter: VelocityFilter | None = None,
                            acceleration: AccelerationEstimate | None = None,
                            qualities: Sequence[str] = ("stable",), *, settings: QualitySettings | None = None,
                            workers: int | None = None, client: Any = None, chunk_size: int | None = None,
                            progress: Progress | None = None,
                            cancelled: Cancelled | None = None) -> RobustRenderableSpace:
    """The renderable (M, B, K) space that every device of a batch has: the intersection of
    :func:`~analysis.sampled.renderable.renderable_space` over the devices (module docstring).

    Parameters
    ----------
    devices : sequence of Device
        The batch, e.g. :func:`box_corners` or :func:`box_samples` of an identified box.
    mass : array_like
        Virtual masses M [kg] (as for ``renderable_space``), shape (NM,).
    damping : array_like
        Virtual dampings B [N s/m], shape (NB,).
    delay_samples : int, optional
        Computation delay in samples (default 1).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter; ``None`` for the backward difference.
    acceleration : AccelerationEstimate or None, optional
        The acceleration estimate; ``None`` for the second backward difference.
    qualities : sequence of str, optional
        The qualities (default ``("stable",)``).
    settings : QualitySettings or None, optional
        The qualities' settings; ``None`` for the defaults.
    workers : int or None, optional
        Processes of the local pool; 1 runs in this process; ``None`` for :func:`default_workers`.
    client : dask.distributed.Client or None, optional
        Run on this Dask cluster instead of a local pool.
    chunk_size : int or None, optional
        Devices per task (:func:`map_devices`).
    progress : callable, optional
        ``progress(done, total)`` in devices.
    cancelled : callable, optional
        ``cancelled() -> bool``.

    Returns
    -------
    RobustRenderableSpace
        The smallest ``k_max`` over the devices, for the space and each quality, the device
        that binds each ``(M, B)`` of the space, and the robust space's volume.

    Raises
    ------
    ValidationError
        For an unknown quality, no devices or a bad ``workers``/``chunk_size``.
    DeviceFailed
        When a device's space fails (a grid out of range fails as device 0, naming the field).
    OperationCancelled
        When ``cancelled()`` turns true.
    """
    names = check_qualities(qualities)
    m, b = _grid_values("mass", mass), _grid_values("damping", damping)
    fn = partial(_space_layers, mass=m, damping=b, delay_samples=delay_samples, velocity_filter=velocity_filter,
                 acceleration=acceleration, qualities=names, settings=settings)
    r = intersect_devices(fn, devices, workers=workers, client=client, chunk_size=chunk_size, progress=progress,
                          cancelled=cancelled)
    layers = {q: _read_only(r.k_max[i + 1].copy()) for i, q in enumerate(names)}
    k = _read_only(r.k_max[0].copy())
    return RobustRenderableSpace(mass=m, damping=b, k_max=k, by_quality=MappingProxyType(layers),
                                 binding=_read_only(r.binding[0].copy()), qualities=names, devices=r.devices,
                                 volume=space_volume(m, b, k, settings))
