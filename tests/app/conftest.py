"""GUI test setup: headless Qt, isolated QSettings, and a main window on the HBFD profile.

PySide6 is imported at module level on purpose, without a guard: if Qt cannot start, the GUI
suite fails instead of being skipped.
"""

from __future__ import annotations

import os
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
REQUESTED_PLATFORM = os.environ["QT_QPA_PLATFORM"]

import PySide6  # noqa: E402,F401
import pytest  # noqa: E402
from PySide6.QtCore import QSettings  # noqa: E402

import app.qt_compat  # noqa: E402,F401 - PySide6 6.12 on CPython 3.11 (see the module)
from analysis.profiles.io import bundled_profiles, load_profile  # noqa: E402

# Nothing a test does may touch the user's real preferences.
QSettings.setDefaultFormat(QSettings.Format.IniFormat)
QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, tempfile.mkdtemp(prefix="zwidth-qsettings-"))


@pytest.fixture(scope="session", autouse=True)
def _app_names(qapp):
    qapp.setOrganizationName("zwidth-tests")
    qapp.setApplicationName("zwidth-tests")
    qapp.setStyle("Fusion")
    yield qapp


@pytest.fixture(autouse=True)
def _no_unanswered_dialogs():
    """A modal dialog the test did not patch fails the test (with its text) instead of hanging it."""
    from modal_guard import ModalGuard

    guard = ModalGuard().install()
    yield guard
    guard.restore()


@pytest.fixture
def settings(tmp_path):
    from app.core.settings import Settings

    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, str(tmp_path / "user"))
    return Settings(QSettings(str(tmp_path / "zwidth-test.ini"), QSettings.Format.IniFormat))


@pytest.fixture
def hbfd_profile():
    return load_profile(bundled_profiles()["hbfd"])


def _main_window(qtbot, settings, profile):
    from app.window.main_window import MainWindow

    w = MainWindow(settings=settings, profile=profile)
    w.resize(1400, 900)
    w.show()
    qtbot.waitExposed(w)
    qtbot.waitUntil(lambda: not w.tabs.currentWidget().stale, timeout=5000)
    yield w
    # not qtbot.addWidget: pytest-qt would close it before this teardown and the unsaved-changes
    # question would block
    w.undo_stack.setClean()
    w.runner.shutdown()
    w.close()
    w.deleteLater()


@pytest.fixture
def win(qtbot, settings, hbfd_profile):
    """The real main window on the HBFD preset, shown offscreen at 1400x900."""
    yield from _main_window(qtbot, settings, hbfd_profile)


#: the B grid of :func:`zwidth_win` (the default section's has 100 points)
COARSE_B_POINTS = 25


@pytest.fixture
def zwidth_win(qtbot, settings, hbfd_profile):
    """The main window on the HBFD preset with a controller section on a coarse B grid
    (:data:`COARSE_B_POINTS` points, the default filter and B range): the Z-width region costs a
    quarter of the default's.  For tests of how the region follows edits, not of its resolution;
    the default section (``controller`` None) and its grid are drawn by the tests that take
    :func:`win` (the Z-width tab's)."""
    from analysis.profiles import ControllerSection

    profile = hbfd_profile.replace(controller=ControllerSection(b_points=COARSE_B_POINTS))
    yield from _main_window(qtbot, settings, profile)


#: the sampled-data stability map's points per axis and the exact chart's b_c points of :func:`coarse_win`
#: (the app's are 48 and 24)
COARSE_MAP_POINTS, COARSE_EXACT_POINTS = 12, 8


def coarse_profile(profile):
    """``profile`` with coarse grids in the sections that hold them: the Z-width region on
    :data:`COARSE_B_POINTS` B points, the renderable space on 9 x 11 (M, B) points, the workspace
    map on 6 x 5 points; every other setting (filter, qualities, linkage, handle) the default's."""
    from analysis.profiles import ControllerSection, MultiDofSection, RenderableSection

    return profile.replace(controller=ControllerSection(b_points=COARSE_B_POINTS),
                           renderable=RenderableSection(mass_points=9, damping_points=11),
                           multidof=MultiDofSection(x_points=6, y_points=5))


@pytest.fixture
def coarse_grids(monkeypatch):
    """Windows made in this test start the Sampled-data tab's stability map on
    :data:`COARSE_MAP_POINTS` points per axis (both displays) and its exact chart on
    :data:`COARSE_EXACT_POINTS` b_c points (the graph reads both when a window registers its nodes)."""
    import app.core.nodes_sampled as nodes_sampled

    monkeypatch.setattr(nodes_sampled, "MAP_POINTS", COARSE_MAP_POINTS)
    monkeypatch.setattr(nodes_sampled, "EXACT_POINTS", COARSE_EXACT_POINTS)


@pytest.fixture
def coarse_win(qtbot, settings, hbfd_profile, coarse_grids):
    """The main window on the HBFD preset with every tab's results on coarse grids
    (:func:`coarse_profile`, :func:`coarse_grids`): for the tests that go through every tab for its
    layout, colours or menus, which do not depend on the results' resolution (each window on the
    default grids costs about 18 s of CPU through every tab, this one about 7 s)."""
    yield from _main_window(qtbot, settings, coarse_profile(hbfd_profile))


@pytest.fixture
def eom_win(qtbot, settings):
    """The real main window on the Eom, Suh & Yi preset (wall and observer sections)."""
    yield from _main_window(qtbot, settings, load_profile(bundled_profiles()["eom"]))


# -- screenshots: saved to tmp_path and checked, not just written -----------------------------------

def distinct_colours(image, step: int = 7) -> int:
    """How many colours a grid of sampled pixels has (a blank frame has one or two)."""
    return len({image.pixel(x, y) for y in range(0, image.height(), step) for x in range(0, image.width(), step)})


def coloured_fraction(image) -> float:
    """The fraction of pixels that are clearly coloured (curves, markers, colour maps), not grey.

    Backgrounds, grid lines, axes and text are grey levels; the plotted data is drawn in colour.
    """
    from PySide6.QtGui import QColor

    n = hits = 0
    for y in range(0, image.height(), 2):
        for x in range(0, image.width(), 2):
            c = QColor(image.pixel(x, y))
            n += 1
            hits += max(c.red(), c.green(), c.blue()) - min(c.red(), c.green(), c.blue()) > 60
    return hits / max(n, 1)


def plot_area(view):
    """The image of a plot view's data area (inside the axes)."""
    vb = view.plot.getViewBox()
    rect = view.plot_widget.mapFromScene(vb.sceneBoundingRect()).boundingRect()
    return view.plot_widget.grab(rect).toImage()


def marker_drawn(view, item, tolerance: int = 40) -> bool:
    """Whether the marker ``item`` (a :func:`app.views.marker.design_marker` of ``view``) shows its
    fill colour at its place in the rendered plot (within 3 px), not hidden behind the data."""
    from PySide6.QtCore import QPointF
    from PySide6.QtGui import QColor

    xs, ys = item.getData()
    if xs is None or len(xs) == 0 or not item.isVisible():
        return False
    at = view.plot_widget.mapFromScene(item.mapToScene(QPointF(float(xs[0]), float(ys[0]))))
    image = view.plot_widget.grab().toImage()
    r = image.devicePixelRatio()
    cx, cy = int(at.x() * r), int(at.y() * r)
    fill = item.opts["brush"].color()
    for y in range(cy - 3, cy + 4):
        for x in range(cx - 3, cx + 4):
            if image.valid(x, y):
                c = QColor(image.pixel(x, y))
                if max(abs(c.red() - fill.red()), abs(c.green() - fill.green()), abs(c.blue() - fill.blue())) < tolerance:
                    return True
    return False


def background_lightness(image) -> int:
    """The grey level (0-255) of the most common colour of a grid of sampled pixels: the window's
    background (light in the light theme, dark in the dark one)."""
    from collections import Counter

    from PySide6.QtGui import QColor

    counts = Counter(image.pixel(x, y) for y in range(0, image.height(), 7) for x in range(0, image.width(), 7))
    return QColor(counts.most_common(1)[0][0]).lightness()


@pytest.fixture
def screenshot(tmp_path):
    """``screenshot(window, name, views)``: save the window under tmp_path and check the image.

    The saved file is read back: it must have the window's size and many colours, and the data
    area of every plot view in ``views`` must show data (coloured pixels), not an empty frame.
    """
    from PySide6.QtGui import QImage

    def take(window, name: str, views=()) -> QImage:
        path = tmp_path / f"{name}.png"
        pixmap = window.grab()
        assert pixmap.save(str(path))
        image = QImage(str(path))
        assert (image.width(), image.height()) == (pixmap.width(), pixmap.height())
        assert image.width() >= 1000 and image.height() >= 600
        assert distinct_colours(image) > 50
        for view in views:
            area = plot_area(view)
            assert area.width() > 100 and area.height() > 60, view.title
            # an empty plot is ~0.2 % coloured (its legend's samples); these plots with data 0.7-40 %
            assert coloured_fraction(area) > 0.005, f"no data drawn in {view.title}"
        return image

    return take
