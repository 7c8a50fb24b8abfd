"""The main window: parameter panel, verdict, analysis tabs, menus, files, undo, export.

``run_gui(profile_path)`` is what the ``zwidth`` command calls.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from app import qt_compat  # noqa: F401 - before any Qt call (PySide6 6.12 on Python 3.11)
from PySide6.QtCore import QIODevice, QSaveFile, Qt, QTimer, Slot
from PySide6.QtGui import QAction, QActionGroup, QCloseEvent, QColor, QDragEnterEvent, QDropEvent, QKeySequence, \
    QPalette, QUndoStack
from PySide6.QtWidgets import (
    QApplication,
    QFileDialog,
    QInputDialog,
    QMainWindow,
    QMessageBox,
    QSplitter,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from analysis.profiles.io import Profile, ProfileError, bundled_profiles, load_profile, profile_to_dict

from app.views import export
from app.core.commands import Editor
from app.core.compute_graph import build_graph
from app.core.model import ProfileModel
from app.core.settings import THEMES, Settings, resolve_dark
from app.tabs import AnalysisTab, AppContext, tab_classes
from app.views.base import PlotView
from app.views.verdict import VerdictView
from app.panels.parameter_panel import ParameterPanel
from app.widgets.task_progress import TaskProgress
from app.core.worker import TaskRunner

__all__ = ["MainWindow", "run_gui", "default_profile"]

APP_NAME = "zwidth"
PROFILE_FILTER = "zwidth profiles (*.json);;All files (*)"


def default_profile() -> Profile:
    """The profile a new document starts from (the bundled HBFD preset)."""
    presets = bundled_profiles()
    return load_profile(presets.get("hbfd") or next(iter(presets.values())))


def _is_bundled(path: str | os.PathLike) -> bool:
    real = os.path.realpath(path)
    return any(os.path.realpath(p) == real for p in bundled_profiles().values())


class MainWindow(QMainWindow):
    def __init__(self, settings: Settings | None = None, profile: Profile | None = None,
                 chart_points: int = 40) -> None:
        super().__init__()
        from app.window.about import app_icon

        self.setWindowIcon(app_icon())
        self.settings = settings if settings is not None else Settings()
        self.path: str | None = None
        self.preset: str | None = "hbfd" if profile is None else None
        self.model = ProfileModel(profile if profile is not None else default_profile(), self)
        self.undo_stack = QUndoStack(self)
        self.editor = Editor(self.model, self.undo_stack, self)
        self.runner = TaskRunner(self)
        self.graph = build_graph(self.model, self.runner, chart_points)
        self.ctx = AppContext(self.model, self.graph, self.editor, self.settings)
        self._pending_min_mass = False
        self._refresh_scheduled = False
        self._verdict_stale = True

        self._make_actions()
        self.panel = ParameterPanel(self.model, self.editor, self.act_maximize, self.act_minimize)
        self.verdict = VerdictView()
        self.tabs = QTabWidget()
        self.tabs.setDocumentMode(True)
        self.analysis_tabs: list[AnalysisTab] = []
        for cls in tab_classes():
            cls.register_nodes(self.graph)
            tab = cls(self.ctx)
            self.analysis_tabs.append(tab)
            self.tabs.addTab(tab, cls.title)
        right = QWidget()
        rl = QVBoxLayout(right)
        rl.setContentsMargins(0, 0, 0, 0)
        rl.setSpacing(4)
        rl.addWidget(self.verdict)
        rl.addWidget(self.tabs, 1)
        self.splitter = QSplitter(Qt.Orientation.Horizontal)
        self.splitter.addWidget(self.panel)
        self.splitter.addWidget(right)
        self.splitter.setStretchFactor(1, 1)
        self.splitter.setSizes([430, 970])
        self.splitter.setChildrenCollapsible(False)
        self.setCentralWidget(self.splitter)
        self.progress = TaskProgress(self.graph)
        self.statusBar().addPermanentWidget(self.progress)
        self._make_menus()

        self.editor.dragChanged.connect(self.graph.set_interactive)
        self.graph.invalidated.connect(self._on_invalidated)
        self.graph.ready.connect(self._on_ready)
        self.graph.failed.connect(self._on_failed)
        self.tabs.currentChanged.connect(self._on_tab_changed)
        self.undo_stack.cleanChanged.connect(self._update_title)
        self.model.fieldChanged.connect(self._on_field)
        self.model.profileReplaced.connect(self._on_replaced)
        self.editor.refused.connect(lambda f, r: self.statusBar().showMessage(f"{f}: {r}", 5000))
        for view in self.plot_views():
            view.exportRequested.connect(lambda fmt, v=view: self.export_view(v, fmt))
        QApplication.styleHints().colorSchemeChanged.connect(lambda _s: self.apply_theme())

        self.setAcceptDrops(True)
        self.resize(1400, 900)
        geometry = self.settings.geometry()
        if geometry is not None:
            self.restoreGeometry(geometry)
        self.apply_theme()
        self._update_actions()
        self._update_title()
        self.refresh_visible()

    # -- actions and menus --------------------------------------------------------------------------
    def _action(self, text: str, slot, shortcut: QKeySequence | str | None = None, tip: str = "") -> QAction:
        act = QAction(text, self)
        if shortcut is not None:
            act.setShortcut(QKeySequence(shortcut))
        if tip:
            act.setStatusTip(tip)
            act.setToolTip(tip)
        act.triggered.connect(lambda _=False: slot())
        return act

    def _make_actions(self) -> None:
        K = QKeySequence.StandardKey
        self.act_new = self._action("&New", self.new_profile, K.New, "Start from the default profile")
        self.act_open = self._action("&Open…", self.open_dialog, K.Open, "Open a profile file")
        self.act_save = self._action("&Save", self.save, K.Save, "Save the profile")
        self.act_save_as = self._action("Save &As…", self.save_as, K.SaveAs, "Save the profile to a new file")
        self.act_quit = self._action("&Quit", self.close, K.Quit)
        self.act_undo = self.undo_stack.createUndoAction(self, "&Undo")
        self.act_undo.setShortcut(QKeySequence(K.Undo))
        self.act_redo = self.undo_stack.createRedoAction(self, "&Redo")
        self.act_redo.setShortcut(QKeySequence(K.Redo))
        self.act_maximize = self._action("Maximize k_c", self.maximize_kc, "Ctrl+M",
                                         "Set k_c to the largest value satisfying eq. (9) for the current b_c")
        self.act_minimize = self._action("Minimize m_c", self.minimize_mc, "Ctrl+Shift+M",
                                         "Set (m_c, b_c) to the smallest m_c satisfying eq. (21)")

    def _make_menus(self) -> None:
        bar = self.menuBar()
        file = bar.addMenu("&File")
        file.addAction(self.act_new)
        file.addAction(self.act_open)
        self.recent_menu = file.addMenu("Open &Recent")
        self.recent_menu.aboutToShow.connect(self._fill_recent)
        self.presets_menu = file.addMenu("&Presets")
        for name, path in bundled_profiles().items():
            try:
                title = load_profile(path).name
            except ProfileError:
                title = name
            act = self.presets_menu.addAction(title.replace("&", "&&"))  # "&" is a mnemonic marker
            act.triggered.connect(lambda _=False, n=name: self.load_preset(n))
        file.addSeparator()
        file.addAction(self.act_save)
        file.addAction(self.act_save_as)
        file.addSeparator()
        self.export_menu = file.addMenu("&Export")
        for view in self.plot_views():
            sub = self.export_menu.addMenu(view.title.split(":")[0])
            for fmt, label in (("png", "PNG image…"), ("svg", "SVG drawing…"), ("csv", "CSV data…")):
                act = sub.addAction(label)
                act.triggered.connect(lambda _=False, v=view, f=fmt: self.export_view(v, f))
        from app.report.action import export_report  # File → Export Report… (issue 6)
        self.act_export_report = file.addAction("Export &Report…", lambda: export_report(self))
        file.addSeparator()
        file.addAction(self.act_quit)

        edit = bar.addMenu("&Edit")
        edit.addAction(self.act_undo)
        edit.addAction(self.act_redo)

        view = bar.addMenu("&View")
        theme = view.addMenu("&Theme")
        group = QActionGroup(self)
        self.theme_actions: dict[str, QAction] = {}
        for name in THEMES:
            act = theme.addAction(name.capitalize())
            act.setCheckable(True)
            act.setChecked(name == self.settings.theme())
            group.addAction(act)
            act.triggered.connect(lambda _=False, n=name: self.set_theme(n))
            self.theme_actions[name] = act

        design = bar.addMenu("&Design")
        design.addAction(self.act_maximize)
        design.addAction(self.act_minimize)

        helpm = bar.addMenu("&Help")
        helpm.addAction(self._action("&About zwidth", self._about))

    def plot_views(self) -> list[PlotView]:
        return [v for t in self.analysis_tabs for v in t.plot_views()]

    def tab(self, cls: type[AnalysisTab]) -> AnalysisTab:
        return next(t for t in self.analysis_tabs if isinstance(t, cls))

    # -- live refresh -----------------------------------------------------------------------------------
    @Slot(object)
    def _on_invalidated(self, names: set[str]) -> None:
        # an edit: running jobs step aside while the visible views catch up (worker.py)
        self.runner.defer_to_gui(0.05)
        if "stability" in names:
            self._verdict_stale = True
        for tab in self.analysis_tabs:
            if tab.nodes & names:
                tab.stale = True
        self._schedule_refresh()

    def _schedule_refresh(self) -> None:
        if not self._refresh_scheduled:
            self._refresh_scheduled = True
            QTimer.singleShot(0, self.refresh_visible)

    @Slot()
    def refresh_visible(self) -> None:
        """Update the verdict and the visible tab from the graph (hidden tabs stay stale)."""
        self._refresh_scheduled = False
        if self._verdict_stale:
            self.verdict.update_result(self.graph.get(self.graph.stability_name))
            self._verdict_stale = False
        current = self.tabs.currentWidget()
        if isinstance(current, AnalysisTab) and current.stale:
            current.refresh()

    @Slot(int)
    def _on_tab_changed(self, _index: int) -> None:
        self._schedule_refresh()

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "display":
            self._update_actions()

    @Slot()
    def _on_replaced(self) -> None:
        self._update_actions()
        self._update_title()

    def _update_actions(self) -> None:
        imp = self.model.profile.display == "impedance"
        self.act_maximize.setEnabled(imp)
        self.act_minimize.setEnabled(not imp)

    # -- design actions --------------------------------------------------------------------------------
    @Slot()
    def maximize_kc(self) -> None:
        """k_c := the analysis core's conservative largest k_c for the current b_c."""
        if self.model.profile.display != "impedance":
            return
        d = self.graph.get("max_stiffness")
        if d.kc is None:
            self.statusBar().showMessage(f"No k_c ≥ 0 satisfies eq. (9) with b_c = {d.bc:g} N·s/m", 8000)
            return
        if d.kc == float("inf"):
            self.statusBar().showMessage("Every k_c satisfies eq. (9) for this device: k_c is unlimited", 8000)
            return
        self.editor.edit_many({"kc": d.kc}, "Maximize k_c")
        self.statusBar().showMessage(f"k_c = {d.kc:.6g} N/m (binding at {d.frequency:.4g} rad/s)", 8000)

    @Slot()
    def minimize_mc(self) -> None:
        """(m_c, b_c) := the analysis core's smallest feasible coupling mass (runs on the worker)."""
        if self.model.profile.display != "admittance":
            return
        self._pending_min_mass = True
        if self.graph.request("min_mass") is not None and self.graph.is_fresh("min_mass"):
            self._apply_min_mass()

    def _apply_min_mass(self) -> None:
        self._pending_min_mass = False
        d = self.graph.node("min_mass").value
        self.editor.edit_many({"mc": d.mc, "bc_adm": d.bc}, "Minimize m_c")
        self.statusBar().showMessage(f"m_c = {d.mc:.6g} kg, b_c = {d.bc:.6g} N·s/m", 8000)

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == "min_mass" and self._pending_min_mass and self.graph.is_fresh("min_mass"):
            self._apply_min_mass()

    @Slot(str, str)
    def _on_failed(self, name: str, message: str) -> None:
        if name == "min_mass":
            self._pending_min_mass = False
        self.statusBar().showMessage(f"{name} failed: {message}", 10000)

    # -- documents ------------------------------------------------------------------------------------
    def _update_title(self, *_args: object) -> None:
        if self.path:
            name = os.path.basename(self.path)
        elif self.preset:
            name = f"{self.model.profile.name} (preset)"
        else:
            name = "Untitled"
        self.setWindowTitle(f"{name}[*] — {APP_NAME}")
        self.setWindowModified(not self.undo_stack.isClean())

    def is_modified(self) -> bool:
        return not self.undo_stack.isClean()

    def maybe_save(self) -> bool:
        """Ask before unsaved changes are lost; False means the user cancelled."""
        if not self.is_modified():
            return True
        answer = QMessageBox.question(
            self,
            "Unsaved changes",
            "The profile has unsaved changes.  Save them first?",
            QMessageBox.StandardButton.Save | QMessageBox.StandardButton.Discard | QMessageBox.StandardButton.Cancel,
            QMessageBox.StandardButton.Save,
        )
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard

    def _load(self, profile: Profile, path: str | None, preset: str | None) -> None:
        self.graph.runner.cancel_all()
        self.model.replace_profile(profile)
        self.undo_stack.clear()
        self.undo_stack.setClean()
        self.path, self.preset = path, preset
        self._update_title()

    @Slot()
    def new_profile(self) -> bool:
        if not self.maybe_save():
            return False
        self._load(default_profile().replace(name="Untitled"), None, None)
        return True

    def open_path(self, path: str, ask: bool = True) -> bool:
        """Open a profile file; a bad file is refused and the current profile stays."""
        if ask and not self.maybe_save():
            return False
        try:
            profile = load_profile(path)
        except ProfileError as err:
            QMessageBox.critical(self, "Cannot open profile", str(err))
            return False
        if _is_bundled(path):
            self._load(profile, None, Path(path).stem)
        else:
            self._load(profile, os.path.abspath(path), None)
            self.settings.add_recent_file(path)
            self.settings.set_last_directory(os.path.dirname(os.path.abspath(path)))
        self.statusBar().showMessage(f"Opened {path}", 5000)
        return True

    def load_preset(self, name: str) -> bool:
        presets = bundled_profiles()
        if name not in presets:
            raise KeyError(name)
        if not self.maybe_save():
            return False
        try:
            profile = load_profile(presets[name])
        except ProfileError as err:
            QMessageBox.critical(self, "Cannot open preset", str(err))
            return False
        self._load(profile, None, name)
        return True

    @Slot()
    def open_dialog(self) -> None:
        if not self.maybe_save():
            return
        path, _ = QFileDialog.getOpenFileName(self, "Open profile", self.settings.last_directory(), PROFILE_FILTER)
        if path:
            self.open_path(path, ask=False)

    def _fill_recent(self) -> None:
        self.recent_menu.clear()
        files = self.settings.recent_files()
        for f in files:
            act = self.recent_menu.addAction(os.path.basename(f).replace("&", "&&"))
            act.setToolTip(f)
            act.setStatusTip(f)
            act.triggered.connect(lambda _=False, p=f: self.open_path(p))
        if not files:
            self.recent_menu.addAction("(none)").setEnabled(False)
        else:
            self.recent_menu.addSeparator()
            self.recent_menu.addAction("Clear list", self.settings.clear_recent_files)

    def save_to(self, path: str) -> bool:
        """Write the profile atomically (QSaveFile); on failure say why and keep the edits."""
        try:
            data = (json.dumps(profile_to_dict(self.model.profile), indent=2, allow_nan=False) + "\n").encode()
        except (TypeError, ValueError) as exc:
            QMessageBox.critical(self, "Cannot save profile", f"{path}: {exc}")
            return False
        f = QSaveFile(path)
        ok = f.open(QIODevice.OpenModeFlag.WriteOnly)
        if ok:
            ok = f.write(data) == len(data)
            if not ok:
                reason = f.errorString()
                f.cancelWriting()
            else:
                ok = f.commit()
                reason = f.errorString()
        else:
            reason = f.errorString()
        if not ok:
            QMessageBox.critical(self, "Cannot save profile", f"{path}: {reason}\n\nYour changes are kept.")
            return False
        self.path, self.preset = os.path.abspath(path), None
        self.undo_stack.setClean()
        self.settings.add_recent_file(path)
        self.settings.set_last_directory(os.path.dirname(os.path.abspath(path)))
        self._update_title()
        self.statusBar().showMessage(f"Saved {path}", 5000)
        return True

    @Slot()
    def save(self) -> bool:
        if self.path is None:
            return self.save_as()
        return self.save_to(self.path)

    @Slot()
    def save_as(self) -> bool:
        start = os.path.join(self.settings.last_directory(), (self.preset or "profile") + ".json")
        path, _ = QFileDialog.getSaveFileName(self, "Save profile", start, PROFILE_FILTER)
        if not path:
            return False
        if not path.lower().endswith(".json"):
            path += ".json"
        return self.save_to(path)

    # -- export ---------------------------------------------------------------------------------------
    def export_view(self, view: PlotView, fmt: str, path: str | None = None, width: int | None = None) -> bool:
        if path is None:
            base = view.title.split(":")[0].strip().lower().replace(" ", "_").replace("(", "").replace(")", "")
            start = os.path.join(self.settings.last_directory(), f"{base}.{fmt}")
            path, _ = QFileDialog.getSaveFileName(self, f"Export {fmt.upper()}", start, export.FORMATS[fmt])
            if not path:
                return False
        if fmt == "png" and width is None:
            w0 = view.plot_widget.viewport().width() * 2
            width, ok = QInputDialog.getInt(self, "PNG resolution", "Width in pixels:", w0, 16, 20000, 100)
            if not ok:
                return False
        try:
            if fmt == "png":
                export.export_png(view, path, int(width or 1600))
            elif fmt == "svg":
                export.export_svg(view, path)
            elif fmt == "csv":
                export.export_csv(view, path)
            else:
                raise ValueError(f"unknown export format {fmt!r}")
        except OSError as exc:
            QMessageBox.critical(self, "Export failed", str(exc))
            return False
        self.settings.set_last_directory(os.path.dirname(os.path.abspath(path)))
        self.statusBar().showMessage(f"Exported {path}", 5000)
        return True

    # -- theme ----------------------------------------------------------------------------------------
    def set_theme(self, theme: str) -> None:
        self.settings.set_theme(theme)
        self.theme_actions[theme].setChecked(True)
        self.apply_theme()

    def apply_theme(self) -> None:
        theme = self.settings.theme()
        dark = resolve_dark(theme)
        app = QApplication.instance()
        if isinstance(app, QApplication):
            app.setPalette(_palette(dark))
        self.verdict.setStyleSheet("")
        for tab in self.analysis_tabs:
            tab.apply_theme(dark)
        self.dark = dark

    # -- drag and drop, close --------------------------------------------------------------------------
    def dragEnterEvent(self, event: QDragEnterEvent) -> None:  # noqa: N802 - Qt API
        urls = event.mimeData().urls() if event.mimeData().hasUrls() else []
        if any(u.isLocalFile() for u in urls):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dropEvent(self, event: QDropEvent) -> None:  # noqa: N802 - Qt API
        files = [u.toLocalFile() for u in event.mimeData().urls() if u.isLocalFile()]
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

    def _about(self) -> None:
        from app.window.about import show_about

        show_about(self)


def _palette(dark: bool) -> QPalette:
    app = QApplication.instance()
    base = app.style().standardPalette() if isinstance(app, QApplication) else QPalette()
    if not dark:
        return base
    p = QPalette(base)
    roles = {
        QPalette.ColorRole.Window: "#2b2d30",
        QPalette.ColorRole.WindowText: "#dfe1e5",
        QPalette.ColorRole.Base: "#1e1f22",
        QPalette.ColorRole.AlternateBase: "#2b2d30",
        QPalette.ColorRole.ToolTipBase: "#3c3f41",
        QPalette.ColorRole.ToolTipText: "#dfe1e5",
        QPalette.ColorRole.Text: "#dfe1e5",
        QPalette.ColorRole.Button: "#3c3f41",
        QPalette.ColorRole.ButtonText: "#dfe1e5",
        QPalette.ColorRole.BrightText: "#ff6b6b",
        QPalette.ColorRole.Highlight: "#3574f0",
        QPalette.ColorRole.HighlightedText: "#ffffff",
        QPalette.ColorRole.Mid: "#8c8f94",
        QPalette.ColorRole.PlaceholderText: "#8c8f94",
    }
    for role, color in roles.items():
        p.setColor(role, QColor(color))
    p.setColor(QPalette.ColorGroup.Disabled, QPalette.ColorRole.Text, QColor("#6f737a"))
    p.setColor(QPalette.ColorGroup.Disabled, QPalette.ColorRole.ButtonText, QColor("#6f737a"))
    p.setColor(QPalette.ColorGroup.Disabled, QPalette.ColorRole.WindowText, QColor("#6f737a"))
    return p


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


