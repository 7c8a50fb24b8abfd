"""The plots show what matters (issue 13): legends off the data, the range plot's default view, the
stability reserve view, and empty charts that say so.  Geometry is checked in scene coordinates."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from PySide6.QtWidgets import QApplication

from analysis.profiles.io import bundled_profiles, load_profile
from analysis.study import design_chart, display_kind, exact_chart, headline
from app.views.design_chart import DesignChart
from app.views.exact_limit_chart import ExactLimitChart
from app.views.placement import densify, scene_points
from app.views.range_plot import RangePlot
from app.views.stability_plot import StabilityPlot, bound_ratio

SIZES = [(900, 520), (560, 330)]


def preset(name: str, display: str = "impedance"):
    return dataclasses.replace(load_profile(bundled_profiles()[name]), display=display)


def shown(view, size):
    view.resize(*size)
    view.show()
    for _ in range(4):
        QApplication.processEvents()
    view.place_legend()
    QApplication.processEvents()
    return view


def covered(view, item_or_xy) -> int:
    """How many (densified) points of a curve or marker lie inside the legend's scene rectangle."""
    vb = view.plot.getViewBox()
    x, y = item_or_xy.getData() if hasattr(item_or_xy, "getData") else item_or_xy
    pts = scene_points(vb, np.asarray(x, float), np.asarray(y, float))
    if len(pts) > 1:
        pts = densify(pts)
    box = vb.sceneBoundingRect()  # a point outside the data area is not drawn, so not covered
    pts = pts[(pts[:, 0] >= box.left()) & (pts[:, 0] <= box.right())
              & (pts[:, 1] >= box.top()) & (pts[:, 1] <= box.bottom())]
    r = view.legend.sceneBoundingRect()
    return int(np.count_nonzero((pts[:, 0] >= r.left()) & (pts[:, 0] <= r.right())
                                & (pts[:, 1] >= r.top()) & (pts[:, 1] <= r.bottom())))


@pytest.fixture(scope="module")
def charts():
    return {(n, d): design_chart(preset(n, d)) for n in ("hbfd", "eom") for d in ("impedance", "admittance")}


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("display", ["impedance", "admittance"])
def test_design_chart_legend_leaves_the_curve_and_the_gains_free(qtbot, charts, display, size):
    p = preset("hbfd", display)
    view = DesignChart()
    qtbot.addWidget(view)
    view.update_chart(charts[("hbfd", display)])
    view.update_point(*display_kind(p).chart_point(p), True)
    shown(view, size)
    assert covered(view, view.upper) == 0 and covered(view, view.point) == 0
    if display == "impedance":  # the best design: the k_c peak near b_c ≈ 1200
        x, y = view.upper.getData()
        j = int(np.argmax(y))
        assert 800 < 10 ** x[j] < 2000
        assert covered(view, ([x[j]], [y[j]])) == 0
    else:
        assert covered(view, view.lower) == 0
    if size == SIZES[0]:
        assert view.legend_placer.covered() == 0  # nor the shaded feasible region


@pytest.mark.parametrize("size", SIZES)
def test_admittance_exact_limit_legend_leaves_the_lower_edge_and_the_gains_free(qtbot, charts, size):
    p = preset("hbfd", "admittance")
    view = ExactLimitChart()
    qtbot.addWidget(view)
    kind = display_kind(p)
    view.update_bound(charts[("hbfd", "admittance")])
    view.update_exact(exact_chart(p, points=12), kind)
    view.update_point(*kind.chart_point(p), False)
    shown(view, size)
    for item in (view.bound, view.bound_low, view.exact, view.point):
        assert covered(view, item) == 0, item


@pytest.mark.parametrize("mode", ["values", "ratio", "log"])
def test_eom_stability_legend_and_binding_label(qtbot, mode):
    p = preset("eom")
    res = display_kind(p).evaluate(p)
    view = StabilityPlot()
    qtbot.addWidget(view)
    view.update_result(res, mode=mode)
    shown(view, (900, 420))
    label = view.worst_line.label.sceneBoundingRect()
    assert label.width() > 20 and "binds at" in view.worst_line.label.format
    assert not view.legend.sceneBoundingRect().intersects(label)
    main = view.ratio_curve if mode == "ratio" else view.coupling_curve
    assert covered(view, main) == 0
    # the label (no opaque box) sits where it hides no point of the coupling curve (or the ratio)
    x, y = main.getData()
    pts = densify(scene_points(view.plot.getViewBox(), x, y))
    inside = ((pts[:, 0] >= label.left()) & (pts[:, 0] <= label.right()) & (pts[:, 1] >= label.top())
              & (pts[:, 1] <= label.bottom()))
    assert not np.any(inside)
    assert view.worst_line.label.fill.style().name == "NoBrush"


@pytest.mark.parametrize("name", ["hbfd", "eom", "rigid"])
def test_ratio_view_peaks_at_one_minus_the_reserve(qtbot, name):
    p = preset(name)
    h = headline(p, with_designs=False)
    res = display_kind(p).evaluate(p)
    view = StabilityPlot()
    qtbot.addWidget(view)
    view.update_result(res, mode="ratio")
    x, y = view.ratio_curve.getOriginalDataset()
    np.testing.assert_allclose(y, bound_ratio(res), rtol=1e-15)
    # the marker: exactly 1 - reserve at the binding frequency of the study's headline
    assert view.worst_xy == (h.binding_frequency, 1.0 - h.stability_reserve)
    # the sampled curve's peak is that point, up to the grid (the headline is refined between points)
    j = int(np.argmax(y))
    assert y[j] == pytest.approx(1.0 - h.stability_reserve, rel=2e-3, abs=2e-4)
    assert x[j] == pytest.approx(h.binding_frequency, rel=0.03)
    assert (y.max() <= 1.0) == h.stable
    if name == "hbfd":  # 76 % reserve at ~80 rad/s: visible on a linear axis with the limit 1
        assert h.stability_reserve == pytest.approx(0.7624, abs=1e-4)
        assert 79 < h.binding_frequency < 82


def test_log_view_keeps_the_sign_of_the_bound(qtbot):
    p = preset("hbfd")
    res = display_kind(p).evaluate(p)
    view = StabilityPlot()
    qtbot.addWidget(view)
    view.update_result(res, mode="log")
    _, pos = view.bound_curve.getData()
    _, neg = view.bound_negative.getData()
    b = np.asarray(res.bound)
    assert pos.size == np.count_nonzero(b > 0) and neg.size == np.count_nonzero(b < 0) > 0
    assert "negative" in view.warning.text()


def y_range(view) -> tuple[float, float]:
    lo, hi = view.plot.getViewBox().viewRange()[1]
    return 10.0 ** lo, 10.0 ** hi


@pytest.mark.parametrize("display", ["impedance", "admittance"])
def test_range_plot_default_view_shows_the_data_of_interest(qtbot, display):
    p = preset("hbfd", display)
    res = display_kind(p).evaluate(p)
    view = RangePlot()
    qtbot.addWidget(view)
    view.update_result(res)
    shown(view, (900, 420))
    lo, hi = y_range(view)
    assert math.log10(hi / lo) <= 5.2  # was 12 (impedance) and 18 (admittance) decades
    band = res.w <= 0.98 * res.w[-1]
    for z in (res.zmin, res.zmax):
        assert lo <= np.abs(z[band]).min() and np.abs(z[band]).max() <= hi
    assert lo <= res.k_max <= hi
    assert lo <= res.k_max / res.w[-1]  # the k_max/ω asymptote over the whole band
    assert np.abs(res.zmin).max() > 1e11 > hi  # the rise below Nyquist is off-scale ...
    assert "off-scale" in view.off_scale.textItem.toPlainText()  # ... and the plot says so
    assert view.off_scale.isVisible() and view.off_scale.textItem.toPlainText().count("×10¹¹")
    if display == "impedance":
        assert lo <= res.b_min <= hi
        assert not view.below_scale.textItem.toPlainText()
    else:
        assert res.b_min < 1e-6 < lo
        assert "below the axis" in view.below_scale.textItem.toPlainText()
    # the export keeps every point, the off-scale ones too
    zmin = next(s for s in view.export_series() if s.name == "|Z_min|")
    assert zmin.y.max() == np.abs(res.zmin).max() and zmin.y.size == res.w.size
    for curve in (view.zmin_curve, view.zmax_curve, view.kmax_curve, view.bmin_curve):
        assert covered(view, curve) == 0  # no curve point under the legend


def test_range_plot_without_a_blow_up_keeps_the_whole_band(qtbot):
    p = preset("hbfd")
    res = display_kind(p).evaluate(p)
    res = dataclasses.replace(res, zmin=res.zmin[:-20], zmax=res.zmax[:-20], w=res.w[:-20])
    view = RangePlot()
    qtbot.addWidget(view)
    view.update_result(res)
    shown(view, (900, 420))
    lo, hi = y_range(view)
    assert lo <= np.abs(res.zmin).min() and np.abs(res.zmax).max() <= hi
    assert not view.off_scale.textItem.toPlainText()


@pytest.mark.parametrize("size", SIZES)
def test_empty_design_chart_says_so_in_the_plot(qtbot, charts, size):
    p = preset("eom")
    view = DesignChart()
    qtbot.addWidget(view)
    view.update_chart(charts[("eom", "impedance")])
    view.update_point(*display_kind(p).chart_point(p), False)
    shown(view, size)
    assert not view.export_series()[0].x.size  # nothing feasible, nothing drawn
    msg = view.message.item
    assert msg.isVisible() and "Nothing is feasible" in msg.toPlainText()
    vb = view.plot.getViewBox().sceneBoundingRect()
    r = msg.sceneBoundingRect()
    assert abs(r.center().x() - vb.center().x()) < 3 and abs(r.center().y() - vb.center().y()) < 3
    assert vb.contains(r)
    bc = charts[("eom", "impedance")].chart.bc
    x0, x1 = view.plot.getViewBox().viewRange()[0]
    assert 10 ** x0 <= bc.min() * 1.001 and bc.max() <= 10 ** x1 * 1.001  # the requested b_c range, not 0.3–3
    assert view.export_notes() == [view.empty_message]
    view.update_chart(charts[("hbfd", "impedance")])
    assert not msg.isVisible() and view.export_notes() == []
