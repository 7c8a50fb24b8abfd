"""Profile files on disk: strict JSON reading, atomic writing, and the bundled presets.

:func:`analysis.profiles.load_profile` and :func:`analysis.profiles.save_profile` are built on
these; every failure is a :class:`ProfileError` naming the file.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import json
import os
import stat
import tempfile
from pathlib import Path

from analysis.profiles.errors import NonFinite, ProfileError
from analysis.resources import resource_path

__all__ = ["bundled_profiles", "read_json", "write_atomically", "unwritable_reason"]


class _DuplicateKey(Exception):
    pass


def _reject_duplicates(pairs: list[tuple[str, object]]) -> dict:
    out: dict = {}
    for key, value in pairs:
        if key in out:
            raise _DuplicateKey(key)
        out[key] = value
    return out


def read_json(path: str | os.PathLike) -> object:
    """The parsed JSON of file ``path`` (UTF-8, optional BOM; no NaN, Infinity or duplicate keys).

    Raises :class:`ProfileError` and nothing else.
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
        return json.loads(text, parse_constant=NonFinite, object_pairs_hook=_reject_duplicates)
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
    except RecursionError:
        raise ProfileError("invalid JSON: nested too deeply", path=path) from None
    except Exception as exc:  # noqa: BLE001
        raise ProfileError(f"invalid JSON ({type(exc).__name__}: {exc})", path=path) from exc


def _target_path(path: str | os.PathLike) -> Path:
    """The real path that ``path`` names (symlinks resolved), for :func:`write_atomically`."""
    try:
        return Path(os.path.realpath(os.fspath(path)))
    except (TypeError, ValueError) as exc:
        raise ProfileError(f"not a usable file name: {exc}", path=str(path)) from exc


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


def write_atomically(path: str | os.PathLike, text: str) -> None:
    """Write ``text`` to the file ``path`` names (symlinks resolved) atomically.

    The text goes to a temporary file in the same directory, which is flushed, fsynced and then
    renamed over the target (keeping the permissions of an existing file); on any failure the
    temporary file is removed and an existing file is left untouched.  Raises
    :class:`ProfileError` naming ``path`` as given (with the OSError as its cause).
    """
    target = _target_path(path)
    tmp_name = None
    try:
        fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        try:
            mode = stat.S_IMODE(os.stat(target).st_mode)
        except FileNotFoundError:
            mode = _new_file_mode()
        os.chmod(tmp_name, mode)
        os.replace(tmp_name, target)
        tmp_name = None
    except Exception as exc:  # noqa: BLE001
        reason = unwritable_reason(path) or (exc.strerror if isinstance(exc, OSError) and exc.strerror
                                             else f"{type(exc).__name__}: {exc}")
        raise ProfileError(f"cannot save: {reason}", path=path) from exc
    finally:
        if tmp_name is not None:
            try:
                os.unlink(tmp_name)
            except OSError:
                pass
    try:  # make the rename itself durable; not possible everywhere
        dir_fd = os.open(target.parent, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dir_fd)
    except OSError:
        pass
    finally:
        os.close(dir_fd)


def bundled_profiles() -> dict[str, Path]:
    """The preset profiles shipped in ``resources/profiles``: file stem -> path, sorted by name."""
    try:
        folder = resource_path("profiles")
    except FileNotFoundError:
        return {}
    return {p.stem: p for p in sorted(folder.glob("*.json"))}
