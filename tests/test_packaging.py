"""The standalone (PyInstaller) build: it starts, finds its data, writes a report, and contains
nothing it does not need.

The frozen-app tests (marker ``package``) test ``dist/zwidth``, which ``make package`` builds
right before running this file (``python packaging/build.py``; about 3.5 minutes), or the build
``ZWIDTH_FROZEN_EXE=/path/to/zwidth`` names.  They never build it themselves.  Without a build,
or with a build older than the sources, they skip in a plain ``pytest`` run; in CI (``CI=true``)
or with ``ZWIDTH_PACKAGE_TEST=1`` (what ``make package`` sets) a missing build, or a missing
PyInstaller to read it, fails them instead, so that no run can pass without having tested the
build.

The size limit and the contents checks are packaging/build.py's (``SIZE_LIMIT``,
``check_build``), which also fails the build itself.
"""

from __future__ import annotations

import configparser
import importlib.util
import os
import subprocess
import sys
import warnings
from importlib import metadata
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGING = ROOT / "packaging"
#: what must never be frozen whatever the spec says (issue 21: Sphinx and babel were, 49 MB)
NEVER_FROZEN = ("sphinx", "babel", "docutils", "pytest", "jinja2", "pygments", "matplotlib", "hypothesis")

package = pytest.mark.package


def _load_build() -> ModuleType:
    # by path: the folder "packaging" would shadow the PyPA package of that name
    spec = importlib.util.spec_from_file_location("zwidth_packaging_build", PACKAGING / "build.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


build = _load_build()


def build_required() -> bool:
    """In CI (``CI=true``) or with ``ZWIDTH_PACKAGE_TEST=1``, the frozen tests must run."""
    return (os.environ.get("CI", "").strip().lower() in ("true", "1", "yes")
            or os.environ.get("ZWIDTH_PACKAGE_TEST", "").strip() == "1")


def _unavailable(reason: str) -> None:
    """Fail where the build is required, skip elsewhere."""
    if build_required():
        pytest.fail(f"{reason} (the build is required here: CI=true or ZWIDTH_PACKAGE_TEST=1)", pytrace=False)
    pytest.skip(reason)


def _sources() -> list[Path]:
    files = [PACKAGING / "zwidth.spec", PACKAGING / "zwidth_entry.py"]
    for folder in ("app", "analysis"):
        files += (ROOT / folder).rglob("*.py")
    files += (ROOT / "resources").rglob("*.*")
    return [f for f in files if f.is_file()]


def _newer_source(exe: Path) -> Path | None:
    built = exe.stat().st_mtime
    return next((f for f in _sources() if f.stat().st_mtime > built), None)


def _frozen_env(tmp_path: Path, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "ZWIDTH_"))}
    env.update(QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=str(tmp_path / "config"),
               HOME=os.environ.get("HOME", str(tmp_path)))
    env.update(extra)
    return env


@pytest.fixture(scope="module")
def frozen_exe() -> Path:
    given = os.environ.get("ZWIDTH_FROZEN_EXE")
    exe = Path(given) if given else build.executable()
    if not exe.is_file():
        _unavailable(f"no standalone build at {exe}: `make package` (or python packaging/build.py) builds it")
    newer = None if given else _newer_source(exe)
    if newer is not None:
        message = f"{exe} is older than {newer.relative_to(ROOT)}; `make package` rebuilds it"
        if not build_required():
            pytest.skip(message)
        warnings.warn(f"{message}: testing it anyway", stacklevel=1)
    return exe


def _internal(exe: Path) -> Path:
    folder = exe.parent / "_internal"
    return folder if folder.is_dir() else exe.parent


@package
def test_frozen_selftest(frozen_exe: Path, tmp_path: Path) -> None:
    """Offscreen: HBFD profile, icon, pyqtgraph templates/colormaps, main window, About box."""
    image = tmp_path / "window.png"
    env = _frozen_env(tmp_path, ZWIDTH_SELFTEST="1", ZWIDTH_SELFTEST_IMAGE=str(image))
    proc = subprocess.run([str(frozen_exe)], env=env, capture_output=True, text=True, timeout=300)
    output = proc.stdout + proc.stderr
    assert proc.returncode == 0, output
    assert "selftest: ok" in proc.stdout, output
    assert "frozen=True" in proc.stdout, output
    assert "hbfd.json" in proc.stdout and "icon ok" in proc.stdout, output
    assert "templates, colormaps and icons ok" in proc.stdout, output
    # zwidth's metadata is bundled: the About box shows the installed version, not "unknown"
    assert f"about box ok: zwidth {metadata.version('zwidth')}" in proc.stdout, output
    if (ROOT / "app" / "window" / "main_window.py").exists():  # the GUI exists: the build must contain it
        assert "main window rendered" in proc.stdout, output
    assert image.exists() and image.stat().st_size > 1000


@package
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


@package
def test_frozen_contents_and_size(frozen_exe: Path) -> None:
    """Data files are bundled; unused Qt modules, test and docs tools are not; under 250 MB on Linux."""
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

    if importlib.util.find_spec("PyInstaller") is None:
        _unavailable("PyInstaller is not installed (it reads the build's archive); "
                     "`make package` (pip install -e '.[package]') installs it")
    frozen = build.frozen_packages(frozen_exe)
    assert {"analysis", "app", "numpy", "scipy", "pyqtgraph", "PySide6"} <= frozen, sorted(frozen)
    dev_only = set(build.dev_only())
    assert set(NEVER_FROZEN) <= dev_only, "packaging/zwidth.spec's DEV_ONLY must keep these out"
    assert not frozen & (dev_only | set(NEVER_FROZEN)), sorted(frozen & (dev_only | set(NEVER_FROZEN)))
    assert build.foreign_packages(frozen) == {}
    if sys.platform.startswith("linux"):
        total = build.tree_size(frozen_exe.parent)
        assert total < build.SIZE_LIMIT, f"{total / 1e6:.1f} MB unpacked (limit {build.SIZE_LIMIT / 1e6:.0f} MB)"
    assert build.check_build(frozen_exe) == []


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


def test_build_checks_tell_runtime_from_test_packages() -> None:
    """packaging/build.py's contents check: zwidth's runtime requirements, and nothing of its
    test extra, count as needed; the spec's DEV_ONLY parses and names the issue-21 packages."""
    needed = build.runtime_distributions()
    assert {"zwidth", "numpy", "scipy", "pyside6-essentials", "shiboken6", "pyqtgraph"} <= needed
    assert not needed & {"sphinx", "babel", "docutils", "pytest", "hypothesis", "pyinstaller"}
    # stdlib modules and zwidth's own packages are never foreign; pytest (installed, as this test
    # runs) is
    frozen = {"os", "json", "unittest", "analysis", "app", "numpy", "scipy", "pyqtgraph", "pytest"}
    assert build.foreign_packages(frozen) == {"pytest": ["pytest"]}
    assert set(NEVER_FROZEN) <= set(build.dev_only())
