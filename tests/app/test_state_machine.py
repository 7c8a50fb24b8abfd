"""The real main window under random use: a hypothesis state machine drives it through its widgets.

Actions: typed values in the spin boxes (in and out of range), slider drags (one drag token each),
undo and redo (the Edit menu's actions), the display switch, adding and removing a mass, the
design actions (Maximize k_c, Minimize m_c), tab switches, save/load round trips and preset loads.
After every step the invariants hold:

- no exception reached Qt's event loop (``sys.excepthook``) and Qt reported no critical message;
- the model and the views agree: every field of the parameter panel shows the model's value, and
  the verdict shows the headline that :mod:`analysis.study` computes from the model;
- undo back to the start restores the starting profile exactly (and redo the current one);
- a saved file loads to the same profile (in the round-trip action).

:class:`GuiDriver` holds the actions and the checks; the hypothesis machine draws its arguments, and
``tests/benchmarks/bench_state_machine.py`` runs the same driver for 10^4 random steps.  Seeded
(``derandomize=True``): ``make test`` runs the same few hundred steps every time.
"""

from __future__ import annotations

import json
import math
import sys
import tempfile
from pathlib import Path
from typing import Any

import hypothesis.strategies as st
from hypothesis import HealthCheck, settings
from hypothesis.stateful import RuleBasedStateMachine, invariant, rule, run_state_machine_as_test
from PySide6.QtCore import QCoreApplication, QEvent, QSettings, QtMsgType, qInstallMessageHandler
from PySide6.QtWidgets import QApplication

from analysis.profiles.io import bundled_profiles, load_profile, profile_from_dict, profile_to_dict
from analysis.study import Headline, stability
from app.core.settings import Settings
from app.widgets.display_selector import DisplaySelector
from app.window.main_window import MainWindow

PRESETS = sorted(bundled_profiles())
#: typed values, relative to the field's slider range: inside it, or clearly outside any sane range
TYPED = ("inside", "negative", "zero", "huge")
VERDICT_KEYS = {"reserve": "stability_reserve", "margin": "worst_margin", "eta": "min_eta", "kmax": "k_max",
                "bmin": "b_min"}


def profile_json(profile: Any) -> str:
    """The profile as its file would hold it (exact floats): equal text, equal profile."""
    return json.dumps(profile_to_dict(profile), sort_keys=True)


class GuiDriver:
    """One main window, its actions through its widgets, and the invariants."""

    def __init__(self, folder: Path, preset: str = "hbfd") -> None:
        self.folder = folder
        self.errors: list[str] = []
        self._old_hook = sys.excepthook
        sys.excepthook = lambda kind, err, tb: self.errors.append(f"{kind.__name__}: {err}")
        self._old_handler = qInstallMessageHandler(self._on_qt_message)
        self.app = QApplication.instance()
        qs = QSettings(str(folder / "zwidth-state-machine.ini"), QSettings.Format.IniFormat)
        self.win = MainWindow(settings=Settings(qs), profile=load_profile(bundled_profiles()[preset]))
        self.win.maybe_save = lambda: True  # never the unsaved-changes question
        self.win.resize(1400, 900)
        self.win.show()
        self.steps = 0
        self.saves = 0
        self.pump()
        self.start = profile_json(self.win.model.profile)

    def _on_qt_message(self, kind: QtMsgType, _context: object, message: str) -> None:
        if kind in (QtMsgType.QtCriticalMsg, QtMsgType.QtFatalMsg):
            self.errors.append(f"Qt: {message}")

    def close(self) -> None:
        w = self.win
        w.undo_stack.setClean()
        w.runner.shutdown()
        w.close()
        w.deleteLater()
        self.pump()
        sys.excepthook = self._old_hook
        qInstallMessageHandler(self._old_handler)

    def pump(self, rounds: int = 4) -> None:
        """Let the window catch up: the coalesced refresh and its repaints (not the worker's jobs),
        and the deferred deletions (``deleteLater``) that ``exec()`` would do: without them every
        rebuilt widget would stay alive and the memory figure of the long run would mean nothing."""
        for _ in range(rounds):
            self.app.processEvents()
        QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)

    # -- the widgets -------------------------------------------------------------------------------
    def fields(self) -> dict[Any, Any]:
        """Every slider field of the parameter panel, by model field (chain: (field, index))."""
        panel = self.win.panel
        return {**panel.fields, **{k: f for k, f in panel.chain.fields.items() if k[0] != "ratios"}}

    def model_value(self, key: Any) -> float | None:
        model = self.win.model
        if isinstance(key, tuple):
            values = model.get(key[0])
            return float(values[key[1]]) if key[1] < len(values) else None
        return float(model.get(key))

    def field_names(self) -> list[str]:
        return sorted(map(str, self.fields()))

    def field(self, name: str) -> Any:
        return next(f for k, f in self.fields().items() if str(k) == name)

    # -- actions -------------------------------------------------------------------------------------
    def type_value(self, name: str, kind: str, fraction: float) -> None:
        """Type a number into the field's spin box and press Enter (interpretText)."""
        f = self.field(name)
        lo, hi = f.position_to_value(1), f.position_to_value(f.slider.maximum())
        inside = lo + fraction * (hi - lo) if lo <= 0 else 10 ** (math.log10(lo) + fraction * math.log10(hi / lo))
        value = {"inside": inside,
                 "negative": -abs(hi) * (0.1 + fraction), "zero": 0.0, "huge": 1e30}[kind]
        f.spin.lineEdit().setText(f"{value:.6g}")
        f.spin.interpretText()
        self.pump()

    def drag(self, name: str, moves: list[int]) -> None:
        """Press the slider, move it through ``moves`` (relative positions), release it."""
        slider = self.field(name).slider
        slider.setSliderDown(True)
        for m in moves:
            slider.setValue(min(max(slider.value() + m, slider.minimum()), slider.maximum()))
            self.pump(2)
        slider.setSliderDown(False)
        self.pump()

    def undo(self) -> None:
        self.win.window_actions.undo.trigger()
        self.pump()

    def redo(self) -> None:
        self.win.window_actions.redo.trigger()
        self.pump()

    def switch_display(self, name: str) -> None:
        self.win.panel.findChild(DisplaySelector).buttons[name].click()
        self.pump()

    def add_mass(self) -> None:
        self.win.panel.chain.add_button.click()
        self.pump()

    def remove_mass(self) -> None:
        self.win.panel.chain.remove_button.click()
        self.pump()

    def design(self, which: str) -> None:
        """Trigger Maximize k_c or Minimize m_c (the latter computes on the worker first)."""
        w = self.win
        (w.act_maximize if which == "maximize" else w.act_minimize).trigger()
        for _ in range(6000):
            if not w.design.pending_min_mass:
                break
            self.pump(1)
            w.runner.wait(5)
        self.pump()

    def switch_tab(self, index: int) -> None:
        self.win.tabs.setCurrentIndex(index % self.win.tabs.count())
        self.pump()

    def save_and_load(self) -> None:
        """Save to a file, read it back (the same profile), and open it in the window."""
        self.saves += 1
        path = self.folder / f"round-trip-{self.saves % 3}.json"
        before = profile_json(self.win.model.profile)
        assert self.win.save_to(str(path))
        assert profile_json(load_profile(path)) == before
        assert self.win.open_path(str(path), ask=False)
        self.pump()
        assert profile_json(self.win.model.profile) == before
        self.start = before  # an opened file is a fresh document: its undo history starts here

    def load_preset(self, name: str) -> None:
        assert self.win.load_preset(name)
        self.pump()
        self.start = profile_json(self.win.model.profile)
        assert profile_json(profile_from_dict(json.loads(self.start))) == self.start

    def reset_history(self) -> None:
        """Start the undo history afresh from the current profile (after a reported failure)."""
        self.win.undo_stack.clear()
        self.start = profile_json(self.win.model.profile)

    # -- invariants ------------------------------------------------------------------------------------
    def check(self) -> None:
        self.steps += 1
        assert not self.errors, self.errors
        assert not self.win.editor.dragging
        self.check_fields()
        self.check_verdict()
        self.check_undo()

    def check_fields(self) -> None:
        for key, f in self.fields().items():
            value = self.model_value(key)
            if value is not None:
                assert f.spin.value() == value, (key, f.spin.value(), value)

    def check_verdict(self) -> None:
        w = self.win
        w.refresh_visible()  # what the coalesced refresh does at the next turn of the event loop
        h = Headline.from_result(stability(w.model.profile))
        for attr, key in VERDICT_KEYS.items():
            assert getattr(w.verdict, attr).text() == h.text(key, rich=True), (attr, key)

    def check_undo(self) -> None:
        """Undo everything, compare, redo to where we were, compare.  The model's signals are
        blocked for the round trip: it ends on the very profile the views show (asserted), so
        nothing needs to redraw, and the check stays cheap however long the history is."""
        stack, model = self.win.undo_stack, self.win.model
        now, index = profile_json(model.profile), stack.index()
        model.blockSignals(True)
        try:
            stack.setIndex(0)
            assert profile_json(model.profile) == self.start
            stack.setIndex(index)
            assert profile_json(model.profile) == now
        finally:
            model.blockSignals(False)


def machine_class(folder: Path) -> type[RuleBasedStateMachine]:
    """The hypothesis machine over a :class:`GuiDriver` whose files go to ``folder``."""

    class WindowMachine(RuleBasedStateMachine):
        def __init__(self) -> None:
            super().__init__()
            self.driver = GuiDriver(folder)

        def teardown(self) -> None:
            self.driver.close()

        @rule(data=st.data(), kind=st.sampled_from(TYPED), fraction=st.floats(0.0, 1.0))
        def type_value(self, data: st.DataObject, kind: str, fraction: float) -> None:
            self.driver.type_value(data.draw(st.sampled_from(self.driver.field_names())), kind, fraction)

        @rule(data=st.data(), moves=st.lists(st.integers(-40, 40), min_size=1, max_size=6))
        def drag(self, data: st.DataObject, moves: list[int]) -> None:
            self.driver.drag(data.draw(st.sampled_from(self.driver.field_names())), moves)

        @rule()
        def undo(self) -> None:
            self.driver.undo()

        @rule()
        def redo(self) -> None:
            self.driver.redo()

        @rule(name=st.sampled_from(["impedance", "admittance"]))
        def switch_display(self, name: str) -> None:
            self.driver.switch_display(name)

        @rule()
        def add_mass(self) -> None:
            self.driver.add_mass()

        @rule()
        def remove_mass(self) -> None:
            self.driver.remove_mass()

        @rule(which=st.sampled_from(["maximize", "minimize"]))
        def design(self, which: str) -> None:
            self.driver.design(which)

        @rule(index=st.integers(0, 9))
        def switch_tab(self, index: int) -> None:
            self.driver.switch_tab(index)

        @rule()
        def save_and_load(self) -> None:
            self.driver.save_and_load()

        @rule(name=st.sampled_from(PRESETS))
        def load_preset(self, name: str) -> None:
            self.driver.load_preset(name)

        @invariant()
        def views_agree_with_the_model(self) -> None:
            self.driver.check()

    return WindowMachine


def test_random_use_keeps_the_window_consistent(qapp, tmp_path):
    machine = machine_class(tmp_path)
    run_state_machine_as_test(machine, settings=settings(
        max_examples=4, stateful_step_count=50, derandomize=True, deadline=None, database=None,
        suppress_health_check=list(HealthCheck)))


if __name__ == "__main__":  # a quick manual run
    run_state_machine_as_test(machine_class(Path(tempfile.mkdtemp())), settings=settings(
        max_examples=2, stateful_step_count=20, derandomize=True, deadline=None, database=None))
