"""The main window: parameter panel, verdict, analysis tabs; it composes the window's parts.

The parts live in their own modules: :mod:`~app.window.menus` (actions and menus),
:mod:`~app.window.documents` (open, save, recent files, presets), :mod:`~app.window.theme`,
:mod:`~app.window.live_refresh` (the verdict and the visible tab follow the graph),
:mod:`~app.window.design_actions` (Maximize k_c, Minimize m_c) and :mod:`~app.window.exports`.

``run_gui(profile_path)`` is what the ``zwidth`` command calls.
"""

from __future__ import annotations

import sys

from app import qt_compat  # noqa: F401 - before any Qt call (PySide6 6.12 on Python 3.11)
from PySide6.QtCore import Qt
from PySide6.QtGui import QCloseEvent, QDragEnterEvent, QDropEvent, QUndoStack
from PySide6.QtWidgets import QApplication, QMainWindow, QSplitter, QTabWidget, QVBoxLayout, QWidget

from analysis.profiles.io import Profile

from app.core.commands import UNDO_LIMIT, Editor
from app.core.model import ProfileModel
from app.core.nodes_stability import build_graph
from app.core.settings import Settings
from app.core.worker import TaskRunner
from app.panels.parameter_panel import ParameterPanel
from app.tabs import AnalysisTab, AppContext, tab_classes
from app.views.base import PlotView
from app.views.verdict import VerdictView
from app.widgets.task_progress import TaskProgress
from app.widgets.tab_list_button import TabListButton
from app.window.design_actions import DesignActions
from app.window.robust_actions import RobustActions
from app.window.documents import APP_NAME, Documents, default_profile, dropped_files
from app.window.exports import export_view
from app.window.live_refresh import LiveRefresh
from app.window.menus import WindowActions, build_menus
from app.window.theme import Theme

__all__ = ["MainWindow", "run_gui", "default_profile", "make_application"]


class MainWindow(QMainWindow):
    """The zwidth window on one profile (``profile``, or the bundled HBFD preset)."""

    def __init__(self, settings: Settings | None = None, profile: Profile | None = None,
                 chart_points: int = 40) -> None:
        super().__init__()
        from app.window.about import app_icon

        self.setWindowIcon(app_icon())
        self.settings = settings if settings is not None else Settings()
        self.model = ProfileModel(profile if profile is not None else default_profile(), self)
        self.undo_stack = QUndoStack(self)
        self.undo_stack.setUndoLimit(UNDO_LIMIT)
        self.editor = Editor(self.model, self.undo_stack, self)
        self.runner = TaskRunner(self)
        self.graph = build_graph(self.model, self.runner, chart_points)
        self.ctx = AppContext(self.model, self.graph, self.editor, self.settings)
        self.documents = Documents(self, self.model, self.undo_stack, self.settings, self.runner,
                                   lambda: self.maybe_save(), "hbfd" if profile is None else None)
        self.window_actions = WindowActions(self)
        self.act_maximize, self.act_minimize = self.window_actions.maximize, self.window_actions.minimize
        self.design = DesignActions(self.model, self.graph, self.editor, self.act_maximize, self.act_minimize,
                                    self.statusBar().showMessage, self)
        self._build_layout()
        self.theme = Theme(self.settings, lambda: [self.verdict, *self.analysis_tabs], self)
        self.live = LiveRefresh(self.graph, self.verdict, self.tabs, self.analysis_tabs, self)
        build_menus(self, self.window_actions)
        self.robust_actions = RobustActions(self, self.model, self.graph, self.editor,
                                            self.statusBar().showMessage, self.verdict)
        self._connect()
        self.setAcceptDrops(True)
        self.resize(1400, 900)
        geometry = self.settings.geometry()
        if geometry is not None:
            self.restoreGeometry(geometry)
        self.apply_theme()
        self.documents.update_title()
        self.refresh_visible()

    def _build_layout(self) -> None:
        """The verdict across the window above parameter panel | analysis tabs; the task progress in the
        status bar.  The verdict spans the whole width so that its badge and six numbers fit on a laptop
        screen (1280 px)."""
        self.panel = ParameterPanel(self.model, self.editor, self.act_maximize, self.act_minimize)
        self.verdict = VerdictView()
        self.tabs = QTabWidget()
        self.tabs.setDocumentMode(True)
        self.analysis_tabs: list[AnalysisTab] = []
        for cls in tab_classes():
            cls.register_nodes(self.graph)
            tab = cls(self.ctx)  # its widgets and views are built when it is first shown (AnalysisTab)
            tab.viewsBuilt.connect(lambda t=tab: self._connect_exports(t))
            self.analysis_tabs.append(tab)
            self.tabs.addTab(tab, cls.title)
        self.tab_list = TabListButton(self.tabs)  # the tabs behind the bar's scroll arrows at 1280 px
        self.splitter = QSplitter(Qt.Orientation.Horizontal)
        self.splitter.addWidget(self.panel)
        self.splitter.addWidget(self.tabs)
        self.splitter.setStretchFactor(1, 1)
        self.splitter.setSizes([380, 1020])
        self.splitter.setChildrenCollapsible(False)
        central = QWidget()
        cl = QVBoxLayout(central)
        cl.setContentsMargins(4, 4, 4, 0)
        cl.setSpacing(4)
        cl.addWidget(self.verdict)
        cl.addWidget(self.splitter, 1)
        self.setCentralWidget(central)
        self.progress = TaskProgress(self.graph)
        self.statusBar().addPermanentWidget(self.progress)

    def _connect(self) -> None:
        self.editor.dragChanged.connect(self.graph.set_interactive)
        self.graph.failed.connect(lambda name, msg: self.statusBar().showMessage(f"{name} failed: {msg}", 10000))
        self.undo_stack.cleanChanged.connect(self.documents.update_title)
        self.model.profileReplaced.connect(self.documents.update_title)
        self.editor.refused.connect(lambda f, r: self.statusBar().showMessage(f"{f}: {r}", 5000))
        QApplication.styleHints().colorSchemeChanged.connect(lambda _s: self.apply_theme())

    # -- tabs and views ----------------------------------------------------------------------------
    def _connect_exports(self, tab: AnalysisTab) -> None:
        """A plot's right-click export, connected when its tab is built."""
        for view in tab.views():
            view.exportRequested.connect(lambda fmt, v=view: self.export_view(v, fmt))

    def plot_views(self) -> list[PlotView]:
        """Every tab's plot views (this builds the tabs not built yet)."""
        return [v for t in self.analysis_tabs for v in t.plot_views()]

    def tab(self, cls: type[AnalysisTab]) -> AnalysisTab:
        """The tab of class ``cls``, built (so that its widgets can be used even while hidden)."""
        tab = next(t for t in self.analysis_tabs if isinstance(t, cls))
        tab.ensure_built()
        return tab

    def refresh_visible(self) -> None:
        """Update the verdict and the visible tab from the graph now."""
        self.live.refresh_visible()

    @property
    def verdict_stale(self) -> bool:
        """Whether the verdict waits for a refresh (an edit changed the stability result)."""
        return self.live.verdict_stale

    # -- design actions ------------------------------------------------------------------------------
    def maximize_kc(self) -> None:
        self.design.maximize_kc()

    def minimize_mc(self) -> None:
        self.design.minimize_mc()

    # -- documents -------------------------------------------------------------------------------------
    @property
    def path(self) -> str | None:
        return self.documents.path

    @property
    def preset(self) -> str | None:
        return self.documents.preset

    def is_modified(self) -> bool:
        return self.documents.is_modified()

    def maybe_save(self) -> bool:
        """Ask before unsaved changes are lost; False means the user cancelled."""
        return self.documents.maybe_save()

    def new_profile(self) -> bool:
        return self.documents.new_profile()

    def open_path(self, path: str, ask: bool = True) -> bool:
        return self.documents.open_path(path, ask)

    def load_preset(self, name: str) -> bool:
        return self.documents.load_preset(name)

    def open_dialog(self) -> None:
        self.documents.open_dialog()

    def fill_recent_menu(self) -> None:
        self.documents.fill_recent_menu(self.recent_menu)

    def save_to(self, path: str) -> bool:
        return self.documents.save_to(path)

    def save(self) -> bool:
        return self.documents.save()

    def save_as(self) -> bool:
        return self.documents.save_as()

    def export_view(self, view: PlotView, fmt: str, path: str | None = None, width: int | None = None) -> bool:
        return export_view(self, self.settings, view, fmt, path, width)

    # -- theme ------------------------------------------------------------------------------------------
    @property
    def dark(self) -> bool:
        return self.theme.dark

    def set_theme(self, theme: str) -> None:
        self.theme.set_theme(theme)

    def apply_theme(self) -> None:
        self.verdict.setStyleSheet("")
        self.theme.apply()

    # -- drag and drop, close, about ------------------------------------------------------------------
    def dragEnterEvent(self, event: QDragEnterEvent) -> None:  # noqa: N802 - Qt API
        if dropped_files(event):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dropEvent(self, event: QDropEvent) -> None:  # noqa: N802 - Qt API
        files = dropped_files(event)
        if files:
            event.acceptProposedAction()
            self.open_path(files[0])

    def closeEvent(self, event: QCloseEvent) -> None:  # noqa: N802 - Qt API
        if not self.maybe_save():
            event.ignore()
            return
        self.settings.set_geometry(self.saveGeometry())
        self.settings.sync()
        self.runner.shutdown()
        event.accept()

    def show_about(self) -> None:
        from app.window.about import show_about

        show_about(self)


def make_application(argv: list[str] | None = None) -> QApplication:
    app = QApplication.instance()
    if not isinstance(app, QApplication):
        app = QApplication(argv if argv is not None else sys.argv[:1])
    app.setOrganizationName(APP_NAME)
    app.setApplicationName(APP_NAME)
    app.setStyle("Fusion")
    from app.window.about import app_icon

    app.setDesktopFileName("zwidth")  # matches packaging/zwidth.desktop (window grouping, icon)
    app.setWindowIcon(app_icon())
    return app


def run_gui(profile_path: str | None) -> int:
    """Open the main window (on ``profile_path`` if given) and run the event loop."""
    app = make_application()
    window = MainWindow()
    if profile_path:
        window.open_path(str(profile_path), ask=False)
    window.show()
    return int(app.exec())
