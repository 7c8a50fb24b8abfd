"""The one atomic file writer (issue 21/22): always the old or the new file, never a torn one,
no temporary left behind on any error path, stale temporaries of killed saves swept."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from analysis.profiles import WriteError, atomic_write, sweep_temporaries
from analysis.profiles.files import STALE_AFTER, is_temporary

ROOT = Path(__file__).resolve().parents[1]


def _temporaries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if is_temporary(p.name))


def test_bytes_text_and_callback_write_the_file(tmp_path):
    target = tmp_path / "a.bin"
    atomic_write(target, b"\x00\x01binary")
    assert target.read_bytes() == b"\x00\x01binary"
    atomic_write(target, "grüße\n")
    assert target.read_bytes() == "grüße\n".encode("utf-8")
    seen = []

    def write(path: str) -> None:
        seen.append(path)
        Path(path).write_bytes(b"via callback")

    atomic_write(target, write)
    assert target.read_bytes() == b"via callback"
    assert Path(seen[0]).parent == tmp_path and is_temporary(Path(seen[0]).name)
    assert Path(seen[0]).name.startswith(".a.bin.zwidth-") and seen[0].endswith(".tmp")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.bin"]


def test_existing_permissions_kept_and_symlink_target_written(tmp_path):
    real = tmp_path / "real.txt"
    real.write_text("old")
    os.chmod(real, 0o640)
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    atomic_write(link, "new")
    assert link.is_symlink() and real.read_text() == "new"
    assert (os.stat(real).st_mode & 0o777) == 0o640


class Boom(RuntimeError):
    pass


@pytest.mark.parametrize("where", ["callback", "callback-oserror", "fsync", "replace", "chmod"])
def test_every_error_path_removes_the_temporary_and_keeps_the_old_file(tmp_path, monkeypatch, where):
    target = tmp_path / "keep.json"
    target.write_text("old")

    def write(path: str) -> None:
        Path(path).write_text("half")
        if where == "callback":
            raise Boom("renderer failed")
        if where == "callback-oserror":
            raise OSError(28, "No space left on device")

    def fail(*_a, **_k):
        raise OSError(28, "No space left on device")

    if where in ("fsync", "replace", "chmod"):
        monkeypatch.setattr(os, where, fail)
    expected = Boom if where == "callback" else WriteError
    with pytest.raises(expected) as info:
        atomic_write(target, write if where.startswith("callback") else b"new")
    monkeypatch.undo()
    if expected is WriteError:
        assert info.value.strerror == "No space left on device" and info.value.filename == str(target)
        assert str(info.value) == f"cannot write {target}: No space left on device"
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.json"]


def test_interrupt_in_the_callback_removes_the_temporary(tmp_path):
    def write(path: str) -> None:
        Path(path).write_text("half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write(tmp_path / "x.pdf", write)
    assert list(tmp_path.iterdir()) == []


def test_folder_target_and_missing_folder_say_why_and_leave_nothing(tmp_path):
    folder = tmp_path / "dir.html"
    folder.mkdir()
    (folder / "inside").write_text("x")
    called = []
    with pytest.raises(WriteError) as info:
        atomic_write(folder, lambda p: called.append(p))
    assert info.value.strerror == f"Is a folder: {folder}" and not called
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dir.html"]
    assert [p.name for p in folder.iterdir()] == ["inside"]
    with pytest.raises(WriteError, match="No such folder"):
        atomic_write(tmp_path / "no" / "x.csv", b"1")
    with pytest.raises(WriteError, match="not a usable file name"):
        atomic_write(str(tmp_path / "bad\0name"), b"1")


def test_sweep_removes_only_stale_temporaries_of_ours(tmp_path):
    old = time.time() - STALE_AFTER - 60
    stale = tmp_path / ".r.pdf.zwidth-abc123_x.tmp"
    fresh = tmp_path / ".r.pdf.zwidth-fresh000.tmp"  # a save in progress elsewhere
    foreign = tmp_path / ".r.pdf.other.tmp"  # not ours
    for p in (stale, fresh, foreign):
        p.write_bytes(b"x" * 100)
    os.utime(stale, (old, old))
    os.utime(foreign, (old, old))
    assert sweep_temporaries(tmp_path) == [stale]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([fresh.name, foreign.name])
    assert sweep_temporaries(tmp_path / "missing") == []


# The children import atomic_write's own module (analysis/profiles/files.py) without running the
# packages' __init__ (which import scipy and the whole numerical core: ~0.8 CPU-s a child, ~0.2 this way):
# the function killed mid-write is the same code, the process is what these tests are about.
_LEAF_IMPORT = f"""
import os, sys, types
for _name in ("analysis", "analysis.profiles"):
    _pkg = types.ModuleType(_name)
    _pkg.__path__ = [os.path.join({str(ROOT)!r}, *_name.split("."))]
    sys.modules[_name] = _pkg
from analysis.profiles.files import atomic_write
"""

# a child that saves in a loop, each save different and large enough to be caught half-written
_SAVER = _LEAF_IMPORT + """
import sys
target, n = sys.argv[1], 0
while True:
    n += 1
    atomic_write(target, (b"%08d" % n) * 250_000)  # 2 MB, every byte tells which save it was
    print(n, flush=True)
"""


def _valid(data: bytes) -> bool:
    return len(data) == 2_000_000 and data == data[:8] * 250_000


def test_a_save_killed_mid_write_leaves_the_old_or_new_file_and_the_next_save_sweeps(tmp_path):
    target = tmp_path / "big.bin"
    atomic_write(target, (b"%08d" % 0) * 250_000)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for delay in (0.05, 0.15, 0.3, 0.5, 0.8):
        child = subprocess.Popen([sys.executable, "-c", _SAVER, str(target)], env=env, cwd=ROOT,
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        assert child.stdout is not None
        child.stdout.readline()  # at least one save done: the interpreter is up and writing
        time.sleep(delay)
        child.send_signal(signal.SIGKILL)
        child.wait()
        assert _valid(target.read_bytes()), "torn file after SIGKILL"
    # killed saves may leave temporaries (how many depends on the machine); they are ours, and once
    # stale the next save removes them
    left = _temporaries(tmp_path)
    old = time.time() - STALE_AFTER - 1
    for name in left:
        os.utime(tmp_path / name, (old, old))
    atomic_write(target, (b"%08d" % 1) * 250_000)
    assert _temporaries(tmp_path) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.bin"]
    assert _valid(target.read_bytes())


def test_a_killed_save_is_swept_even_when_it_is_caught_mid_write(tmp_path):
    """A temporary left exactly as a SIGKILL leaves one (written, never renamed) is swept."""
    target = tmp_path / "p.json"
    target.write_text("old")
    marker = tmp_path / "started"
    code = (
        _LEAF_IMPORT
        + "import os, sys, time\n"
        "from pathlib import Path\n"
        "def write(path):\n"
        "    Path(path).write_text('half')\n"
        f"    Path({str(marker)!r} + '.w').write_text(path)\n"
        f"    os.replace({str(marker)!r} + '.w', {str(marker)!r})\n"
        "    time.sleep(60)\n"
        f"atomic_write({str(target)!r}, write)\n"
    )
    child = subprocess.Popen([sys.executable, "-c", code], env={**os.environ, "PYTHONPATH": str(ROOT)}, cwd=ROOT)
    try:
        deadline = time.monotonic() + 60
        while not marker.exists() and time.monotonic() < deadline:
            time.sleep(0.02)
        assert marker.exists()
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait()
    tmp = Path(marker.read_text())
    assert tmp.exists() and is_temporary(tmp.name) and target.read_text() == "old"
    atomic_write(target, "new")  # fresh: a save in progress elsewhere is never swept
    assert tmp.exists()
    old = time.time() - STALE_AFTER - 1
    os.utime(tmp, (old, old))
    atomic_write(target, "newer")
    assert not tmp.exists() and target.read_text() == "newer"
