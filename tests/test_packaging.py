"""The standalone (PyInstaller) build: it starts, finds its data and writes a report.

The frozen-app tests need PyInstaller (``pip install -e '.[package]'``, which ``make package``
does) and are skipped without it.  They use ``dist/zwidth`` when it is newer than the sources
(``make package`` builds it right before running this file), and otherwise build it first
(about a minute).  ``ZWIDTH_FROZEN_EXE=/path/to/zwidth`` tests a given build instead.

The report step uses ``zwidth report`` when the build has that command (``zwidth report --help``
exits 0), and ``zwidth analyze --json`` into a file otherwise.
"""

from __future__ import annotations

import configparser
import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGING = ROOT / "packaging"
DIST_APP = ROOT / "dist" / "zwidth"
EXE = DIST_APP / ("zwidth.exe" if sys.platform == "win32" else "zwidth")
SIZE_LIMIT = 250e6  # bytes, unpacked, Linux

HAVE_PYINSTALLER = importlib.util.find_spec("PyInstaller") is not None
needs_pyinstaller = pytest.mark.skipif(
    not HAVE_PYINSTALLER,
    reason="PyInstaller is not installed; `make package` (pip install -e '.[package]') installs it",
)


def _sources() -> list[Path]:
    files = [PACKAGING / "zwidth.spec", PACKAGING / "zwidth_entry.py"]
    for folder in ("app", "analysis"):
        files += (ROOT / folder).rglob("*.py")
    files += (ROOT / "resources").rglob("*.*")
    return [f for f in files if f.is_file()]


def _stale(exe: Path) -> bool:
    if not exe.exists():
        return True
    built = exe.stat().st_mtime
    return any(f.stat().st_mtime > built for f in _sources())


def _frozen_env(tmp_path: Path, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "ZWIDTH_"))}
    env.update(QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=str(tmp_path / "config"),
               HOME=os.environ.get("HOME", str(tmp_path)))
    env.update(extra)
    return env


@pytest.fixture(scope="module")
def frozen_exe() -> Path:
    if not HAVE_PYINSTALLER:
        pytest.skip("PyInstaller is not installed; `make package` (pip install -e '.[package]') installs it")
    given = os.environ.get("ZWIDTH_FROZEN_EXE")
    if given:
        return Path(given)
    lock_path = ROOT / "build" / "package.lock"
    lock_path.parent.mkdir(parents=True, exist_ok=True)
    with open(lock_path, "w") as lock:
        try:
            import fcntl

            fcntl.flock(lock, fcntl.LOCK_EX)  # one build at a time when test runs overlap
        except ImportError:  # Windows
            pass
        if _stale(EXE):
            subprocess.run([sys.executable, str(PACKAGING / "build.py")], cwd=ROOT, check=True)
    assert EXE.exists(), f"the build did not produce {EXE}"
    return EXE


def _internal(exe: Path) -> Path:
    folder = exe.parent / "_internal"
    return folder if folder.is_dir() else exe.parent


@needs_pyinstaller
def test_frozen_selftest(frozen_exe: Path, tmp_path: Path) -> None:
    """Offscreen: HBFD profile, icon, pyqtgraph templates/colormaps, main window, About box."""
    image = tmp_path / "window.png"
    env = _frozen_env(tmp_path, ZWIDTH_SELFTEST="1", ZWIDTH_SELFTEST_IMAGE=str(image))
    proc = subprocess.run([str(frozen_exe)], env=env, capture_output=True, text=True, timeout=300)
    output = proc.stdout + proc.stderr
    assert proc.returncode == 0, output
    assert "selftest: ok" in proc.stdout, output
    assert "hbfd.json" in proc.stdout and "icon ok" in proc.stdout, output
    assert "templates, colormaps and icons ok" in proc.stdout, output
    if (ROOT / "app" / "main_window.py").exists():  # the GUI exists: the build must contain it
        assert "main window rendered" in proc.stdout, output
    assert image.exists() and image.stat().st_size > 1000


@needs_pyinstaller
def test_frozen_report(frozen_exe: Path, tmp_path: Path) -> None:
    """The build opens the bundled HBFD profile and writes its PDF and HTML reports."""
    profile = _internal(frozen_exe) / "resources" / "profiles" / "hbfd.json"
    assert profile.is_file()
    env = _frozen_env(tmp_path)
    for name in ("hbfd-report.pdf", "hbfd-report.html"):
        out = tmp_path / name
        cmd = [str(frozen_exe), "report", str(profile), "--output", str(out), "--no-sampled"]
        proc = subprocess.run(cmd, env=env, capture_output=True, timeout=300)
        assert proc.returncode == 0, (cmd, proc.stdout.decode(errors="replace"), proc.stderr.decode(errors="replace"))
        data = out.read_bytes()
        if name.endswith(".pdf"):
            assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF") and b"/Page" in data
        else:
            text = data.decode()
            assert "<html" in text.lower() and "HBFD" in text and "<svg" in text


@needs_pyinstaller
def test_frozen_contents_and_size(frozen_exe: Path) -> None:
    """Data files are bundled; unused Qt modules and dev tools are not; under 250 MB on Linux."""
    internal = _internal(frozen_exe)
    for name in ("eom.json", "hbfd.json", "rigid.json"):
        assert (internal / "resources" / "profiles" / name).is_file()
    for size in (16, 32, 48, 64, 128, 256, 512):
        assert (internal / "resources" / "icons" / f"zwidth-{size}.png").is_file()
    assert list((internal / "pyqtgraph" / "colors" / "maps").glob("*.csv"))
    assert (internal / "pyqtgraph" / "icons" / "auto.png").is_file()
    names = {p.name.split(".")[0] for p in (internal / "PySide6").iterdir()}
    for unused in ("QtWebEngineCore", "Qt3DCore", "QtQuick", "QtQml", "QtMultimedia", "QtNetwork",
                   "QtPrintSupport", "QtSql", "QtDesigner"):
        assert unused not in names, f"{unused} should be excluded"
    for unused in ("tkinter", "matplotlib", "IPython", "mpmath", "control", "pytest", "hypothesis"):
        assert not (internal / unused).exists(), f"{unused} should be excluded"
    if sys.platform.startswith("linux"):
        total = sum(p.stat().st_size for p in frozen_exe.parent.rglob("*") if p.is_file() and not p.is_symlink())
        assert total < SIZE_LIMIT, f"{total / 1e6:.1f} MB unpacked (limit {SIZE_LIMIT / 1e6:.0f} MB)"


# -- files that need no build ---------------------------------------------------------------------


def test_desktop_entry() -> None:
    entry = configparser.ConfigParser(interpolation=None)
    entry.optionxform = str  # keys are case-sensitive
    entry.read(PACKAGING / "zwidth.desktop", encoding="utf-8")
    desktop = entry["Desktop Entry"]
    assert desktop["Type"] == "Application"
    assert desktop["Name"] == "zwidth"
    assert desktop["StartupWMClass"] == "zwidth"  # QApplication.setApplicationName/setDesktopFileName
    assert desktop["Icon"] == "zwidth"
    assert desktop["Exec"].split()[0] == "zwidth"
    assert desktop["Categories"].endswith(";")


def test_icons_match_the_svg() -> None:
    """The committed PNGs are what packaging/make_icons.py renders from resources/icons/zwidth.svg."""
    pytest.importorskip("PySide6.QtSvg", reason="PySide6.QtSvg is not installed")
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env["QT_QPA_PLATFORM"] = "offscreen"
    proc = subprocess.run([sys.executable, str(PACKAGING / "make_icons.py"), "--check"], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr


@pytest.mark.gui
def test_about_box_and_icon(qtbot) -> None:
    """app.about: the icon has every size; the About box names the papers and the licenses."""
    from app.window.about import AboutDialog, app_icon, app_version

    icon = app_icon()
    assert not icon.isNull()
    assert {s.width() for s in icon.availableSizes()} >= {16, 32, 48, 64, 128, 256}
    dialog = AboutDialog()
    qtbot.addWidget(dialog)
    text = dialog.title_label.text() + dialog.body_label.text()
    assert app_version() in text
    for needle in ("Stability and Performance of Haptic Displays", "Adams, Moreyra &amp; Hannaford",
                   "Considering Transparency and Robust Stability", "Eom, Suh &amp; Yi",
                   "NumPy", "SciPy", "PySide6", "pyqtgraph", "BSD-3-Clause", "LGPL", "MIT"):
        assert needle in text, needle
    assert not dialog.windowIcon().isNull()
