"""Plots and exports tell the truth (issue 22): axes at the data's scale in every SVG, shading only
where a range exists and down to the axis, one quantity per legend entry and unit."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from PySide6.QtCore import QPointF
from PySide6.QtGui import QFont, QFontMetricsF

from analysis.study import design_chart, display_kind
from app.report.figures import prepare_view
from app.views.design_chart import DesignChart
from app.views.export import export_svg, svg_bytes
from app.views.range_plot import RangePlot, band_segments

SVG = "{http://www.w3.org/2000/svg}"
MATRIX = re.compile(r"matrix\(([^)]*)\)")


def _texts(root: ET.Element) -> list[tuple[str, float, float, float]]:
    """(text, absolute x of its start, absolute y, font pixel size) of every <text> in the drawing."""
    out = []
    for g in root.iter(f"{SVG}g"):
        m = MATRIX.search(g.get("transform", "")) if g.get("transform") else None
        a, b, c, d, e, f = (float(v) for v in m.group(1).split(",")) if m else (1, 0, 0, 1, 0, 0)
        for t in g.findall(f"{SVG}text"):
            x, y = float(t.get("x", 0)), float(t.get("y", 0))
            out.append(((t.text or "").strip(), a * x + c * y + e, b * x + d * y + f,
                        float(t.get("font-size", 12)) * np.hypot(a, b)))
    return out


def _centre(text: str, x: float, size: float) -> float:
    font = QFont("Sans Serif")
    font.setPixelSize(round(size))
    font.setHintingPreference(QFont.HintingPreference.PreferNoHinting)
    return x + QFontMetricsF(font).horizontalAdvance(text) / 2


@pytest.fixture
def chart(qapp, hbfd_profile):
    view = DesignChart()
    view.update_chart(design_chart(hbfd_profile))
    ux, uy = view.upper.getData()
    view.update_point(100.0, float(10 ** np.interp(2.0, ux, uy)) / 3, True)  # a data point at b_c = 100
    prepare_view(view)
    yield view
    view.close()
    view.deleteLater()


def _data_x(view: DesignChart, bc: float) -> float:
    """Where b_c = ``bc`` is drawn, in the exported drawing's coordinates (the viewport's)."""
    vb = view.plot.getViewBox()
    scene = vb.mapViewToScene(QPointF(np.log10(bc), vb.viewRange()[1][0]))
    return float(view.plot_widget.mapFromScene(scene).x())


@pytest.mark.parametrize("write", ["export_svg", "report_svg"])
def test_svg_tick_labels_sit_on_their_data(chart, tmp_path, write):
    """The "100" tick label of the b_c axis is centred on b_c = 100, where the current-gains dot is
    drawn (pyqtgraph's axes are QPictures: a generator at another dpi scaled them to 75 %)."""
    if write == "export_svg":
        path = tmp_path / "chart.svg"
        export_svg(chart, path)
        data = path.read_bytes()
    else:  # the HTML report's figures come from the same writer
        data = svg_bytes(chart, "Design chart", "#ffffff")
    root = ET.fromstring(data)
    x100 = _data_x(chart, 100.0)
    texts = _texts(root)
    bottom = max(y for s, _x, y, _f in texts if s == "100")  # the b_c axis is the lowest "100"
    labels = [(s, x, f) for s, x, y, f in texts if s in ("10", "100", "1000") and abs(y - bottom) < 1]
    assert {s for s, _x, _f in labels} == {"10", "100", "1000"}
    for s, x, size in labels:
        assert abs(size - 12) < 0.01  # 9 pt at 96 dpi, not scaled
        assert _centre(s, x, size) == pytest.approx(_data_x(chart, float(s)), abs=1.0)
    # the dot: a marker translated to its centre at b_c = 100
    moves = [[float(v) for v in m.group(1).split(",")] for g in root.iter(f"{SVG}g")
             if (m := MATRIX.search(g.get("transform", "")))]
    assert any(abs(m[4] - x100) < 1.0 and m[0] > 1 for m in moves)
    assert not any(0 < abs(m[0]) < 1 for m in moves), "a group is drawn scaled down"


def test_range_band_is_shaded_only_where_the_range_exists(qtbot, hbfd_profile):
    """|Z_min| > |Z_max| (about 60-180 rad/s on the HBFD) is an empty range: nothing shaded there."""
    res = display_kind(hbfd_profile).evaluate(hbfd_profile)
    view = RangePlot()
    qtbot.addWidget(view)
    view.update_result(res)
    lo, hi = np.log10(np.abs(res.zmin)), np.log10(np.abs(res.zmax))
    w = np.log10(res.w)
    empty = lo > hi
    assert 10 < empty.sum() < w.size - 10  # the HBFD has an empty stretch and a band
    assert empty[np.argmin(np.abs(res.w - 100.0))] and not empty[np.argmin(np.abs(res.w - 20.0))]
    path = view.fill.path()
    hits = np.array([path.contains(QPointF(x, (a + b) / 2)) for x, a, b in zip(w, lo, hi)])
    clear = np.abs(hi - lo) > 1e-3  # a crossing lies between samples: only test off the crossings
    inner = clear & (np.arange(w.size) > 0) & (np.arange(w.size) < w.size - 1)
    assert not np.any(hits[inner & empty])
    assert np.all(hits[inner & ~empty])
    # no polygon reaches into the empty stretch: each lies where lo <= hi
    for poly in path.toSubpathPolygons():
        xs = np.array([poly.at(i).x() for i in range(poly.size())])
        inside = (w > xs.min() + 1e-9) & (w < xs.max() - 1e-9)
        assert not np.any(inside & empty)
    assert len(path.toSubpathPolygons()) >= 2


def test_band_segments_end_at_the_crossings():
    x = np.linspace(0.0, 10.0, 11)
    segs = band_segments(x, np.zeros(11), x, np.sin(x))
    assert len(segs) == 2
    (xa, la, ha), (xb, lb, hb) = segs
    assert xa[0] == 0.0 and xa[-1] == pytest.approx(3.157, abs=1e-3) and ha[-1] == la[-1]
    assert xb[0] == pytest.approx(6.298, abs=1e-3) and xb[-1] == pytest.approx(9.431, abs=1e-3)
    assert np.all(ha >= la) and np.all(hb >= lb)
    assert band_segments(x, np.ones(11), x, np.zeros(11)) == []


def _fill_bottom(view) -> float:
    """The lowest y (view coordinates: log10) the shading reaches."""
    return float(view.fill.path().boundingRect().top())  # y grows upward in view coordinates


def test_design_chart_shades_the_feasible_gains_down_to_the_axis(chart, tmp_path):
    """Every k_c below the largest is feasible: the shading reaches the axis's lower edge (it stopped
    at a decade below the curve's minimum, about 4.6 kN/m on the HBFD), also after zooming out, and
    never past it (an SVG has no clipping: it would cover the axis)."""
    vb = chart.plot.getViewBox()
    assert _fill_bottom(chart) == pytest.approx(vb.viewRange()[1][0], abs=1e-9)
    vb.setYRange(vb.viewRange()[1][0] - 6, vb.viewRange()[1][1], padding=0)  # zoomed out 6 decades below
    assert _fill_bottom(chart) == pytest.approx(vb.viewRange()[1][0], abs=1e-9)
    # the shading is no part of the auto-range: the axis still fits the data
    _ux, uy = chart.upper.getData()
    vb.enableAutoRange()
    vb.updateAutoRange()
    assert vb.viewRange()[1][0] > float(np.min(uy)) - 1.0
    assert _fill_bottom(chart) == pytest.approx(vb.viewRange()[1][0], abs=1e-9)
    # zoomed in above part of the curve: no shading below the view there either
    vb.setYRange(float(np.max(uy)) - 0.2, float(np.max(uy)) + 0.1, padding=0)
    bottom, path = vb.viewRange()[1][0], chart.fill.path()
    ux, _uy = chart.upper.getData()
    xs = np.linspace(ux[0], ux[-1], 200)[1:-1]
    assert not any(path.contains(QPointF(x, bottom - 0.01)) for x in xs)
    assert any(path.contains(QPointF(x, bottom + 0.01)) for x in xs)


def test_zwidth_region_shades_the_stable_walls_down_to_the_axis(qtbot):
    from app.views.zwidth_region_view import ZWidthRegionView

    view = ZWidthRegionView()
    qtbot.addWidget(view)
    view.update_region(_synthetic_region())
    view.resize(700, 420)
    view.show()
    qtbot.waitExposed(view)
    vb = view.plot.getViewBox()
    assert vb.viewRange()[1][0] < np.log10(5e3)  # the passive curve is in view
    assert _fill_bottom(view) == pytest.approx(vb.viewRange()[1][0], abs=1e-9)
    vb.setYRange(-2, 8, padding=0)
    assert _fill_bottom(view) == pytest.approx(-2, abs=1e-9)
    top = view.fill.path().boundingRect().bottom()
    assert top == pytest.approx(np.log10(1e4 * 101), abs=1e-6)  # up to the exact curve, no further


def _legend_texts(view) -> list[str]:
    return [label.text for _sample, label in view.legend.items]


def test_identify_magnitude_names_each_quantity_with_its_unit(qtbot, hbfd_profile):
    """Actuator (m/N) and gauge (N/N) responses: each its own colour and legend entries, and an
    axis label that gives no unit wrong (it said "|H| [m/N]" for both)."""
    from analysis.identify import device_response, make_measurement
    from app.views.bode_view import BodeView

    dev = hbfd_profile.device
    w = np.logspace(0, 3, 60)
    pairs = []
    for q in ("actuator", "gauge"):
        h = device_response(dev, w, q, "free", None, 0)
        pairs.append((make_measurement(w, h, q, "free"), h * 1.01))
    view = BodeView()
    qtbot.addWidget(view)
    view.show_pairs(pairs)
    mag = view.magnitude
    texts = _legend_texts(mag)
    assert texts == ["actuator x/F [m/N] measured", "actuator x/F [m/N] fitted",
                     "gauge F<sub>g</sub>/F [N/N] measured", "gauge F<sub>g</sub>/F [N/N] fitted"]
    label = mag.plot.getAxis("left").labelText
    assert "m/N" in label and "N/N" in label and "|H|" not in label
    assert "|x/F|" in label and "|F<sub>g</sub>/F|" in label
    colours = {k: mag.items[k].opts["pen"].color().getRgb()[:3] for k in mag.items}
    assert colours["measured"] == colours["fitted"] != colours["measured gauge"] == colours["fitted gauge"]
    # each curve holds its own quantity's numbers
    np.testing.assert_allclose(mag.data("measured gauge")[1], np.abs(pairs[1][0].response))
    np.testing.assert_allclose(mag.data("fitted")[1], np.abs(pairs[0][1]))
    names = [s.name for s in mag.export_series()]
    assert "|F_g/F| gauge measured" in names and "|x/F| actuator fitted" in names
    # one quantity again: its unit alone, and no gauge entries left over
    view.show_pairs(pairs[1:])
    assert _legend_texts(mag) == ["gauge F<sub>g</sub>/F [N/N] measured", "gauge F<sub>g</sub>/F [N/N] fitted"]
    label = mag.plot.getAxis("left").labelText
    assert "N/N" in label and "m/N" not in label
    assert mag.data("measured")[0].size == 0


def _synthetic_region(area_linear: float = 1.234e7, area_log: float = 3.2e6):
    from analysis.sampled import VelocityFilter, ZWidthRegion

    b = np.geomspace(0.1, 100.0, 60)
    return ZWidthRegion(b=b, k_max=1e4 * (1 + b), k_passive=5e3 * np.ones_like(b),
                        k_twoport=4e4 * np.ones_like(b), area_linear=area_linear, area_log=area_log,
                        delay_samples=0, velocity_filter=VelocityFilter("backward"), k_floor=1.0, k_ceiling=1e9)


def test_zwidth_title_exponents_are_glyphs_not_clipped_sup(qtbot):
    """The one-line title clipped a <sup> at its top (×10⁷ read ×10'): the exponents are Unicode
    superscripts, which sit inside the line."""
    from app.views.zwidth_region_view import ZWidthRegionView

    view = ZWidthRegionView()
    qtbot.addWidget(view)
    view.update_region(_synthetic_region())
    text = view.header.text()
    assert "1.234×10⁷" in text and "3.2×10⁶" in text
    assert "<sup>" not in text
    view.set_busy(True)
    assert "10⁷" in view.header.text() and "updating" in view.header.text()


def _sample_colour(legend, index: int) -> tuple[int, int, int]:
    """The centre pixel of a legend sample painted on white."""
    from PySide6.QtGui import QColor, QImage, QPainter

    sample = legend.items[index][0]
    image = QImage(24, 24, QImage.Format.Format_ARGB32)
    image.fill(QColor("white"))
    painter = QPainter(image)
    sample.paint(painter, None, None)
    painter.end()
    c = QColor(image.pixel(10, 10))
    return c.red(), c.green(), c.blue()


def test_shading_swatches_have_the_shadings_colours(qtbot, chart):
    """The "feasible" and "margin < 0" swatches were pyqtgraph's slate squares."""
    from app.views.stability_plot import StabilityPlot

    texts = _legend_texts(chart)
    r, g, b = _sample_colour(chart.legend, texts.index("feasible (unconditionally stable)"))
    assert g > r + 8 and g > b + 8  # green, like the shading
    view = StabilityPlot()
    qtbot.addWidget(view)
    for dark in (False, True):
        view.apply_theme(dark)
        r, g, b = _sample_colour(view.legend, _legend_texts(view).index("margin &lt; 0"))
        assert r > g + 8 and r > b + 8  # pink, like the shading


def test_time_plot_lists_only_the_curves_it_draws(qtbot):
    """Without the passivity observer there is no PO curve: no legend entry (it showed pyqtgraph's
    crossed-eye "hidden" icon), and it comes back with the observer."""
    from app.views.time_response import TimeResponse

    view = TimeResponse()
    qtbot.addWidget(view)
    energy = view.energy
    t = np.linspace(0.0, 1.0, 50)
    base = {"absorbed by controller": t, "observed (encoder)": t, "work of the human": t}
    energy.set_series(t, {**base, "PO (environment port)": None})
    assert all(sample.item.isVisible() for sample, _label in energy.legend.items)
    assert not any("PO" in text for text in _legend_texts(energy)) and len(energy.legend.items) == 3
    energy.set_series(t, {**base, "PO (environment port)": -t})
    assert _legend_texts(energy)[-1] == "PO" and len(energy.legend.items) == 4
    assert all(sample.item.isVisible() for sample, _label in energy.legend.items)


def test_zwidth_legend_lists_trials_only_when_loaded(qtbot):
    from analysis.sampled import MeasuredTrials
    from app.views.zwidth_region_view import ZWidthRegionView

    view = ZWidthRegionView()
    qtbot.addWidget(view)
    view.update_region(_synthetic_region())
    texts = _legend_texts(view)
    assert not any("trial" in t for t in texts) and texts[-1].startswith("current wall")
    assert len(texts) == 4
    trials = MeasuredTrials(path="t.csv", b=np.array([1.0, 10.0]), k=np.array([1e3, 1e7]),
                            stable=np.array([True, False]), lines=np.array([2, 3]))
    view.update_region(_synthetic_region(), trials)
    texts = _legend_texts(view)
    assert "trial: stable" in texts and "trial: unstable" in texts and texts[-1].startswith("current wall")
    view.update_region(_synthetic_region())
    assert not any("trial" in t for t in _legend_texts(view))


def test_group_titles_show_an_ampersand_not_a_mnemonic(qtbot):
    """"Hannaford & Ryu" showed as "Hannaford _Ryu": Qt took the & for a shortcut mark."""
    from PySide6.QtGui import QKeySequence
    from PySide6.QtWidgets import QGroupBox, QLineEdit

    from app.panels.simulation_panel import PassivityControls

    box = PassivityControls(lambda *a, **k: None, QLineEdit())
    qtbot.addWidget(box)
    assert "Hannaford && Ryu" in box.title()
    assert QKeySequence.mnemonic(box.title()).isEmpty()  # no shortcut: the & is drawn
    assert isinstance(box, QGroupBox)
