"""Texts rewritten on every drag step are shown at a reading pace, and always end exact."""

from __future__ import annotations

import time

from app.widgets.text_pacer import TextPacer


def test_outside_a_drag_every_text_shows_at_once(qtbot):
    shown: list[str] = []
    pacer = TextPacer(lambda: False)
    for k in ("a", "b", "c"):
        pacer.show("legend", lambda k=k: shown.append(k))
    assert shown == ["a", "b", "c"] and pacer.pending == [] and pacer.applied == 3


def test_during_a_drag_the_first_text_shows_then_the_newest_per_interval(qtbot):
    shown: list[str] = []
    pacer = TextPacer(lambda: True, interval_ms=200)
    t0 = time.monotonic()
    pacer.show("legend", lambda: shown.append("k=1"))  # the first step: at once
    assert shown == ["k=1"]
    for k in range(2, 12):  # ten more steps inside the interval: held, the newest replaces the older
        pacer.show("legend", lambda k=k: shown.append(f"k={k}"))
        pacer.show("summary", lambda k=k: shown.append(f"s={k}"))
    held_for = time.monotonic() - t0
    if held_for < 0.2:  # (a machine too slow to run ten steps in 0.2 s would show one more)
        assert shown == ["k=1"] and sorted(pacer.pending) == ["legend", "summary"]
    qtbot.waitUntil(lambda: not pacer.pending, timeout=2000)
    assert shown[-2:] == ["k=11", "s=11"]  # the last texts, exact
    assert time.monotonic() - t0 >= 0.19  # not before the interval had passed
    assert pacer.applied == len(shown) <= 5


def test_the_end_of_a_drag_shows_the_last_text_at_once(qtbot):
    shown: list[str] = []
    dragging = [True]
    pacer = TextPacer(lambda: dragging[0], interval_ms=10_000)
    pacer.show("legend", lambda: shown.append("first"))
    pacer.show("legend", lambda: shown.append("held"))
    assert shown == ["first"] and pacer.pending == ["legend"]
    dragging[0] = False  # the release refreshes the tab: its text replaces the held one
    pacer.show("legend", lambda: shown.append("final"))
    assert shown == ["first", "final"] and pacer.pending == []
