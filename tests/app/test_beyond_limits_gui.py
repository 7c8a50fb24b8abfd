"""Designs beyond the physical range in the GUI (issue 22): the Eom profile's admittance display
has its smallest m_c at b_c ≈ 1.3·10¹² N·s/m (the loader allows 10⁸).  Design → Minimize m_c does
not apply it: the status bar says "beyond the physical range" and which limit, the action is
disabled with a tooltip saying why, and it is offered again once an input of the design changes.
The robust design's Apply is checked the same way."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from analysis.study import BEYOND, RobustDesigns

from app.window.robust_actions import robust_beyond


def test_minimize_mc_beyond_limit_is_refused_and_disabled(eom_win, qtbot):
    win = eom_win
    win.editor.edit("display", "admittance")
    assert win.act_minimize.isEnabled()
    before = win.model.profile
    edits = win.undo_stack.count()
    win.act_minimize.trigger()
    qtbot.waitUntil(lambda: not win.design.pending_min_mass, timeout=20000)
    design = win.graph.result("min_mass")
    assert design.bc > 1e8  # the design itself: its number is what the analysis found
    # not applied: the profile and the undo stack are unchanged
    assert win.model.profile.mc == before.mc and win.model.profile.bc_adm == before.bc_adm
    assert win.undo_stack.count() == edits
    message = win.statusBar().currentMessage()
    assert BEYOND in message and "b_c ≤ 1e+08 N·s/m" in message
    assert not win.act_minimize.isEnabled()
    assert BEYOND in win.act_minimize.toolTip() and "b_c ≤ 1e+08" in win.act_minimize.toolTip()
    # an input of the design changes: the design is stale, the action is offered again
    win.editor.edit("kp", 2 * before.kp)
    qtbot.waitUntil(win.act_minimize.isEnabled, timeout=5000)
    assert BEYOND not in win.act_minimize.toolTip()


def test_minimize_mc_inside_limits_still_applies(win, qtbot):
    """The HBFD's smallest m_c (16 kg, 2.4 kN·s/m) is inside: applied as before, the action stays enabled."""
    win.editor.edit("display", "admittance")
    win.act_minimize.trigger()
    qtbot.waitUntil(lambda: not win.design.pending_min_mass, timeout=20000)
    qtbot.waitUntil(lambda: win.model.profile.mc > 10.0, timeout=5000)
    assert win.model.profile.bc_adm == pytest.approx(win.graph.result("min_mass").bc, rel=1e-12)
    assert win.act_minimize.isEnabled() and BEYOND not in win.act_minimize.toolTip()


def test_robust_apply_checks_the_limit():
    def designs(kc: float) -> RobustDesigns:
        return RobustDesigns(impedance=True, intervals={"masses[0]": (0.9, 1.1)}, coupling=1e3, holds=True,
                             stiffness=SimpleNamespace(kc=kc, nominal_kc=kc, bc=1.0, binding={}), damping=None)

    beyond = robust_beyond(designs(5e9))
    assert beyond is not None and beyond.field == "kc" and BEYOND in beyond.text()
    assert robust_beyond(designs(5e5)) is None
    low_only = RobustDesigns(impedance=False, intervals={"masses[0]": (0.9, 1.1)}, coupling=10.0, holds=False,
                             stiffness=None, damping=SimpleNamespace(mc=1.0, low=6e7, high=float("inf")))
    assert robust_beyond(low_only) is not None  # the applied b_c (2 × the lower edge) is 1.2e8 > 1e8
