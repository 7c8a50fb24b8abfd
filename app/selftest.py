"""Hidden self-check of an installed or frozen zwidth (``ZWIDTH_SELFTEST=1 zwidth`` or ``zwidth selftest``).

It runs offscreen and checks what a PyInstaller build can silently miss: the bundled profiles,
the icon files and Qt's PNG plugin, pyqtgraph's Qt-specific template modules and colormap data,
the About box (package metadata), and that the main window (or, before it exists, a pyqtgraph plot
of the HBFD bound) builds and renders.  Prints one ``selftest: ...`` line per check and returns 0
when all pass, 1 otherwise.  A watchdog ends the process with exit code 3 if it hangs (e.g. on a
modal dialog); ``ZWIDTH_SELFTEST_TIMEOUT`` sets it (seconds, default 120).

``ZWIDTH_SELFTEST_IMAGE=path.png`` saves the rendered window.  The line
``selftest: window shown after X s`` is the start-up time from process start (Linux) or from the
import of this module.
"""

from __future__ import annotations

import importlib
import os
import sys
import threading
import time
import traceback
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # Qt is imported late on purpose (the self-test times the import)
    from PySide6.QtGui import QIcon
    from PySide6.QtWidgets import QApplication, QWidget

__all__ = ["run_selftest", "process_age"]

_T_IMPORT = time.perf_counter()


def process_age() -> float | None:
    """Seconds since this process started (Linux /proc), or None."""
    try:
        with open("/proc/self/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        start_ticks = int(fields[19])  # field 22 of stat(5); fields[0] is field 3
        with open("/proc/uptime", "rb") as f:
            uptime = float(f.read().split()[0])
        return uptime - start_ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, AttributeError):
        return None


def _since_start() -> float:
    age = process_age()
    return age if age is not None else time.perf_counter() - _T_IMPORT


def _say(message: str) -> None:
    print(f"selftest: {message}", flush=True)


def _watchdog(seconds: float) -> threading.Timer:
    def expire() -> None:
        print(f"selftest: FAILED: no answer after {seconds:g} s (hung?)", file=sys.stderr, flush=True)
        os._exit(3)

    timer = threading.Timer(seconds, expire)
    timer.daemon = True
    timer.start()
    return timer


def _check_pyqtgraph() -> None:
    import pyqtgraph as pg
    from pyqtgraph.Qt import QT_LIB
    from pyqtgraph.icons import getGraphPixmap

    # The .ui templates: ``_generic`` since pyqtgraph 0.13, one per binding before.
    for base in ("pyqtgraph.graphicsItems.ViewBox.axisCtrlTemplate",
                 "pyqtgraph.graphicsItems.PlotItem.plotConfigTemplate",
                 "pyqtgraph.GraphicsScene.exportDialogTemplate"):
        errors = []
        for suffix in ("generic", QT_LIB.lower()):
            try:
                importlib.import_module(f"{base}_{suffix}")
                break
            except ModuleNotFoundError as exc:
                errors.append(str(exc))
        else:
            raise RuntimeError(f"pyqtgraph template missing: {'; '.join(errors)}")
    cmap = pg.colormap.get("viridis")  # a CSV data file of pyqtgraph
    if cmap is None or len(cmap.getColors()) < 2:
        raise RuntimeError("pyqtgraph colormap data missing")
    if getGraphPixmap("auto").isNull():  # the plot's auto-range button (a PNG data file)
        raise RuntimeError("pyqtgraph icons missing")
    _say(f"pyqtgraph {pg.__version__} ({QT_LIB}): templates, colormaps and icons ok")


def _wait_idle(window: object, app: object, seconds: float) -> None:
    runner = getattr(window, "runner", None)
    deadline = time.monotonic() + seconds
    spins = 0
    while time.monotonic() < deadline:
        app.processEvents()
        spins += 1
        busy = bool(runner is not None and getattr(runner, "is_running", lambda: False)())
        if not busy and spins > 20:
            return
        time.sleep(0.01)
    _say(f"note: computations still running after {seconds:g} s")


def _fallback_plot(profile: object) -> object:
    """Before the main window exists: a plot of the bound of eq. (9) for the profile."""
    import numpy as np
    import pyqtgraph as pg

    from analysis import ImpedanceDisplay

    display = ImpedanceDisplay(profile.device)
    w = display.frequencies()
    bound = np.asarray(display.bound(w), dtype=float)
    widget = pg.PlotWidget(title=f"{profile.name}: bound")
    widget.setLogMode(x=True, y=False)
    widget.plot(w / (2 * np.pi), np.where(np.isfinite(bound), bound, np.nan), pen="c")
    widget.resize(800, 500)
    return widget


def _render(widget: object, app: object) -> object:
    image = widget.grab().toImage()
    if image.isNull() or image.width() < 50 or image.height() < 50:
        raise RuntimeError(f"rendering failed ({image.width()}x{image.height()})")
    small = image.scaled(32, 32)
    colours = {small.pixel(x, y) for x in range(32) for y in range(32)}
    if len(colours) < 4:
        raise RuntimeError("rendered window is blank")
    target = os.environ.get("ZWIDTH_SELFTEST_IMAGE")
    if target:
        image.save(target)
        _say(f"saved {target}")
    return image


def run_selftest() -> int:
    """Run the checks offscreen; 0 if they all pass."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    timer = _watchdog(float(os.environ.get("ZWIDTH_SELFTEST_TIMEOUT", "120")))
    try:
        return _run()
    except Exception:  # report everything: this is a diagnostic
        traceback.print_exc()
        _say("FAILED")
        return 1
    finally:
        timer.cancel()


def _check_icon(app: QApplication) -> QIcon:
    """The application icon (all sizes) from the packaged icon files; set on ``app``."""
    from app.window.about import app_icon, icon_path

    icon = app_icon()
    if icon.isNull() or icon.pixmap(256, 256).isNull():
        raise RuntimeError(f"application icon missing (looked for {icon_path(256)})")
    app.setWindowIcon(icon)
    _say(f"icon ok: {len(icon.availableSizes())} sizes from {icon_path(256).parent}")
    return icon


def _check_about(window: QWidget, app: QApplication) -> None:
    """The About box renders and reads the package versions (zwidth's own from its metadata)."""
    from app.window.about import AboutDialog, app_version

    about = AboutDialog(window)
    about.show()
    app.processEvents()
    if about.grab().isNull():
        raise RuntimeError("the About box did not render")
    if "not installed" in about.body_label.text():
        _say("note: some dependency versions could not be read")
    about.close()
    _say(f"about box ok: zwidth {app_version()}")


def _run() -> int:
    _say(f"python {sys.version.split()[0]}, frozen={bool(getattr(sys, 'frozen', False))}, "
         f"platform={os.environ.get('QT_QPA_PLATFORM')}")
    from analysis.profiles.io import load_profile
    from analysis.resources import resource_path

    hbfd = resource_path("profiles", "hbfd.json")
    profile = load_profile(hbfd)
    _say(f"profile {profile.name!r} from {hbfd}")

    from app import qt_compat  # noqa: F401 - before any Qt call
    from PySide6.QtWidgets import QApplication

    try:
        main_window = importlib.import_module("app.window.main_window")
    except ModuleNotFoundError as exc:
        if exc.name != "app.window.main_window":
            raise
        main_window = None
    make_application = getattr(main_window, "make_application", None)
    app = QApplication.instance() or (make_application() if make_application else QApplication(sys.argv[:1]))
    app.setApplicationName("zwidth")
    app.setDesktopFileName("zwidth")

    icon = _check_icon(app)
    _check_pyqtgraph()

    window_class = getattr(main_window, "MainWindow", None)
    if window_class is not None:
        window = window_class()
        opener = getattr(window, "open_path", None)
        if opener is not None and opener(str(hbfd), ask=False) is False:
            raise RuntimeError(f"the main window refused {hbfd}")
        kind = "main window"
    else:
        window = _fallback_plot(profile)
        kind = "pyqtgraph plot (app.window.main_window has no MainWindow yet)"
    window.setWindowIcon(icon)
    window.show()
    app.processEvents()
    _say(f"window shown after {_since_start():.2f} s")
    _wait_idle(window, app, 30.0)
    image = _render(window, app)
    _say(f"{kind} rendered {image.width()}x{image.height()}")

    _check_about(window, app)
    runner = getattr(window, "runner", None)
    if runner is not None and hasattr(runner, "shutdown"):
        runner.shutdown()
    window.hide()
    window.deleteLater()
    app.processEvents()
    _say(f"ok ({_since_start():.2f} s)")
    return 0
