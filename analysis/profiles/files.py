"""Profile files on disk: strict JSON reading, the one atomic file writer, and the bundled presets.

:func:`analysis.profiles.load_profile` and :func:`analysis.profiles.save_profile` are built on
these; every failure is a :class:`ProfileError` naming the file.  :func:`atomic_write` is the one
way zwidth writes any file (profiles, plot exports, reports): both layers use it.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import json
import os
import re
import stat
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from analysis.profiles.errors import NonFinite, ProfileError
from analysis.resources import resource_path

__all__ = ["bundled_profiles", "read_json", "write_atomically", "unwritable_reason", "atomic_write", "WriteError",
           "sweep_temporaries", "is_temporary", "STALE_AFTER"]


class _DuplicateKey(Exception):
    pass


def _reject_duplicates(pairs: list[tuple[str, object]]) -> dict:
    out: dict = {}
    for key, value in pairs:
        if key in out:
            raise _DuplicateKey(key)
        out[key] = value
    return out


class _LongNumber(Exception):
    pass


def _parse_int(text: str) -> int:
    try:
        return int(text)
    except ValueError:  # more digits than sys.get_int_max_str_digits(): Python's message is about sys
        raise _LongNumber(text) from None


def _long_number(text: str, number: str) -> str:
    """Where ``number`` is in ``text``, as :class:`json.JSONDecodeError` words it."""
    pos = max(text.find(number), 0)
    line = text.count("\n", 0, pos) + 1
    column = pos - text.rfind("\n", 0, pos)
    return f"line {line}, column {column}"


def read_json(path: str | os.PathLike) -> object:
    """The parsed JSON of a file (UTF-8, optional BOM; no NaN, Infinity or duplicate keys).

    Parameters
    ----------
    path : str or os.PathLike
        The file to read.

    Returns
    -------
    object
        The parsed JSON value.

    Raises
    ------
    ProfileError
        The file cannot be read or is not such JSON (and nothing else is raised).
    """
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise ProfileError(f"cannot read the file: {exc.strerror or exc}", path=path) from exc
    except (TypeError, ValueError) as exc:  # not a path at all, or an embedded NUL
        raise ProfileError(f"not a usable file name: {exc}", path=str(path)) from exc
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ProfileError(f"not UTF-8 text (byte {exc.start}): {exc.reason}", path=path) from exc
    try:
        return json.loads(text, parse_constant=NonFinite, object_pairs_hook=_reject_duplicates,
                          parse_int=_parse_int)
    except json.JSONDecodeError as exc:
        raise ProfileError(
            f"invalid JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}",
            path=path,
            expected="valid JSON",
        ) from exc
    except _DuplicateKey as exc:
        raise ProfileError(
            f"invalid JSON: duplicate key {json.dumps(exc.args[0])} in an object", path=path
        ) from None
    except _LongNumber as exc:
        digits = len(exc.args[0].lstrip("-"))
        raise ProfileError(f"invalid JSON at {_long_number(text, exc.args[0])}: number too long ({digits} digits)",
                           path=path, expected="valid JSON") from None
    except RecursionError:
        raise ProfileError("invalid JSON: nested too deeply", path=path) from None
    except Exception as exc:  # noqa: BLE001
        raise ProfileError(f"invalid JSON ({type(exc).__name__}: {exc})", path=path) from exc


def _target_path(path: str | os.PathLike) -> Path:
    """The real path that ``path`` names (symlinks resolved), for :func:`atomic_write`."""
    try:
        name = os.fspath(path)
        if "\0" in str(name):
            raise ValueError("embedded null character")
        return Path(os.path.realpath(name))
    except (TypeError, ValueError) as exc:
        raise WriteError(str(path), f"not a usable file name: {exc}") from exc


def _new_file_mode() -> int:
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def unwritable_reason(path: str | os.PathLike) -> str | None:
    """Why a file cannot be written at ``path``, in words (``"No such folder: /x"``), or ``None``
    when nothing is visibly wrong.  Used for every "cannot write" message, which otherwise only
    repeats the path (Qt's writers give no reason)."""
    target = Path(os.path.abspath(os.fspath(path)))
    folder = target.parent
    if not folder.exists():
        missing = folder
        while not missing.parent.exists() and missing.parent != missing:
            missing = missing.parent
        return f"No such folder: {missing}"
    if not folder.is_dir():
        return f"Not a folder: {folder}"
    if target.is_dir():
        return f"Is a folder: {target}"
    if not os.access(folder, os.W_OK) or (target.exists() and not os.access(target, os.W_OK)):
        return f"Permission denied: {target if target.exists() else folder}"
    return None


# -- the one atomic file writer ------------------------------------------------------------------

#: how the temporary files of an unfinished save are named: ``.<name>.zwidth-<random>.tmp``
TEMP_MARK = ".zwidth-"
_TEMP_NAME = re.compile(r"^\..+\.zwidth-[A-Za-z0-9_]+\.tmp$")
#: a temporary file of ours this old (seconds) belongs to a save that was killed: the next save sweeps it
STALE_AFTER = 600.0


class WriteError(OSError):
    """A file could not be written: ``str()`` is ``cannot write <path>: <reason>``.

    Parameters
    ----------
    path : str or os.PathLike
        The file as the caller named it (``filename``).
    reason : str
        Why, in words (``"No such folder: /x"``): the error's ``strerror``.
    errno : int or None
        The operating system's error number, where there was one.
    """

    def __init__(self, path: str | os.PathLike, reason: str, errno: int | None = None) -> None:
        super().__init__(errno, reason)
        self.filename = os.fspath(path)

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}"


def is_temporary(name: str) -> bool:
    """Whether a file name is one of :func:`atomic_write`'s temporaries.

    Parameters
    ----------
    name : str
        A file name without its folder.

    Returns
    -------
    bool
        ``True`` for ``.<name>.zwidth-<random>.tmp``.
    """
    return bool(_TEMP_NAME.match(name))


def sweep_temporaries(folder: str | os.PathLike, older_than: float = STALE_AFTER) -> list[Path]:
    """Remove the stale temporaries of :func:`atomic_write` in a folder (saves killed before their rename).

    Parameters
    ----------
    folder : str or os.PathLike
        The folder to sweep; a missing or unreadable folder is left alone.
    older_than : float
        Only temporaries last written more than this many seconds ago are removed (a younger one
        may belong to a save still in progress).

    Returns
    -------
    list of Path
        The files removed.  Never raises.
    """
    removed: list[Path] = []
    limit = time.time() - older_than
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        if not is_temporary(entry.name):
            continue
        try:
            if entry.is_file(follow_symlinks=False) and entry.stat(follow_symlinks=False).st_mtime < limit:
                os.unlink(entry.path)
                removed.append(Path(entry.path))
        except OSError:
            continue
    return removed


def _fsync_folder(folder: Path) -> None:
    """Make a rename in ``folder`` durable (not possible everywhere)."""
    try:
        dir_fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dir_fd)
    except OSError:
        pass
    finally:
        os.close(dir_fd)


def _reason(path: str | os.PathLike, exc: BaseException) -> str:
    """The reason in words: what is visibly wrong with ``path``, else the error's own words."""
    if isinstance(exc, OSError):
        return unwritable_reason(path) or exc.strerror or str(exc)
    return unwritable_reason(path) or f"{type(exc).__name__}: {exc}"


def atomic_write(path: str | os.PathLike, data: bytes | str | Callable[[str], object], *,
                 encoding: str = "utf-8") -> None:
    """Write the file ``path`` names (symlinks resolved) so that it is always the old or the new file.

    ``data`` is bytes, text (``encoding``), or a callback ``write(temp_path)`` that writes the
    file itself (Qt's ``QPdfWriter``, exporters that take a file name).  The content goes to a
    temporary file ``.<name>.zwidth-<random>.tmp`` in the same folder, which is fsynced and renamed
    over the target (keeping an existing file's permissions), then the folder is fsynced.  On
    every error path, an exception from the callback included, the temporary file is removed and
    an existing file is left untouched.  Each save first sweeps the folder's temporaries of ours
    older than :data:`STALE_AFTER` (left by saves that were killed).

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    data : bytes, str or callable
        The content, or ``write(temp_path)`` that writes it.
    encoding : str
        The encoding of text ``data``.

    Raises
    ------
    WriteError
        The file cannot be written (an ``OSError``, with the reason in words); an exception of the
        callback that is not an ``OSError`` is passed on unchanged.
    """
    target = _target_path(path)
    if target.is_dir():  # checked first: a folder is never replaced, and nothing is left behind
        raise WriteError(path, f"Is a folder: {target}")
    sweep_temporaries(target.parent)
    tmp_name: str | None = None
    try:
        fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}{TEMP_MARK}", suffix=".tmp", dir=target.parent)
        if callable(data):
            os.close(fd)
            data(tmp_name)
            fd = os.open(tmp_name, os.O_RDONLY)
            try:
                os.fsync(fd)
            finally:
                os.close(fd)
        else:
            with os.fdopen(fd, "wb") as fh:
                fh.write(data.encode(encoding) if isinstance(data, str) else data)
                fh.flush()
                os.fsync(fh.fileno())
        try:
            mode = stat.S_IMODE(os.stat(target).st_mode)
        except FileNotFoundError:
            mode = _new_file_mode()
        os.chmod(tmp_name, mode)
        os.replace(tmp_name, target)
        tmp_name = None
    except OSError as exc:
        raise WriteError(path, _reason(path, exc), getattr(exc, "errno", None)) from exc
    except (TypeError, ValueError) as exc:
        if callable(data):
            raise
        raise WriteError(path, _reason(path, exc)) from exc
    finally:
        if tmp_name is not None:
            try:
                os.unlink(tmp_name)
            except OSError:
                pass
    _fsync_folder(target.parent)


def write_atomically(path: str | os.PathLike, text: str) -> None:
    """Write text to a file with :func:`atomic_write`, failing as a profile error.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    text : str
        Its new content (UTF-8).

    Raises
    ------
    ProfileError
        The file cannot be written: ``cannot save: <reason>``, naming ``path`` as given, with the
        :class:`WriteError` as its cause.
    """
    try:
        atomic_write(path, text)
    except WriteError as exc:
        raise ProfileError(f"cannot save: {exc.strerror}", path=path) from exc


def bundled_profiles() -> dict[str, Path]:
    """The preset profiles shipped in ``resources/profiles``.

    Returns
    -------
    dict of str to Path
        File stem -> path, sorted by name (empty when the folder is missing).
    """
    try:
        folder = resource_path("profiles")
    except FileNotFoundError:
        return {}
    return {p.stem: p for p in sorted(folder.glob("*.json"))}
