"""The PDF report: QPdfWriter + QPainter, vector plots, selectable text, page numbers.

The writer works at 96 dpi so that one device unit is one CSS pixel: the plot views, laid out
in pixels, are rendered at their native scale (slightly reduced to the text width) and their
fonts keep their point sizes.  Everything is vector (paths and text); only the stability map's
colour field is an embedded image.  Text is laid out by ``QTextDocument`` and drawn as text,
so it can be selected and searched.
"""

from __future__ import annotations

import html
import os

from app import qt_compat  # noqa: F401 - before any Qt call

from PySide6.QtCore import QMarginsF, QRectF, QSizeF, Qt
from PySide6.QtGui import QColor, QFont, QPageLayout, QPageSize, QPainter, QPdfWriter, QPen, QTextDocument

from analysis.profiles import atomic_write
from analysis.profiles.files import unwritable_reason

from app.report.model import Figure, ReportContent

__all__ = ["write_pdf", "PAGE_SIZES"]

PAGE_SIZES = {"a4": QPageSize.PageSizeId.A4, "letter": QPageSize.PageSizeId.Letter}
DPI = 96
MARGIN_X = 68
MARGIN_TOP = 78
MARGIN_BOTTOM = 70
GAP = 14

CSS = """
body { font-size: 9.5pt; color: #222; }
h1 { font-size: 17pt; color: #12355b; margin: 0; }
h2 { font-size: 12pt; color: #12355b; margin-top: 4px; margin-bottom: 4px; }
p { margin-top: 2px; margin-bottom: 4px; }
.meta { color: #555; }
.cap { font-size: 8.5pt; color: #333; }
.fig { font-size: 10pt; font-weight: bold; color: #12355b; }
th { background-color: #e6ecf3; color: #12355b; text-align: left; font-weight: bold; }
td.v { text-align: right; font-family: 'DejaVu Sans Mono', monospace; }
.ok { color: #2b8a3e; }
.bad { color: #c92a2a; }
"""


def table_html(rows, head=("Quantity", "Symbol", "Value", "Unit")) -> str:
    out = ['<table width="100%" cellspacing="0" cellpadding="3" border="0" style="border-collapse: collapse">',
           "<tr>" + "".join(f"<th width='{w}'{a}>{h}</th>" for h, w, a in
                            zip(head, ("42%", "13%", "20%", "25%"), ("", "", " align='right'", ""))) + "</tr>"]
    for i, r in enumerate(rows):
        bg = ' bgcolor="#f6f8fa"' if i % 2 else ""
        out.append(f"<tr{bg}><td>{r.label}</td><td>{r.symbol}</td><td class='v'>{r.value}</td>"
                   f"<td>{r.unit}</td></tr>")
    out.append("</table>")
    return "".join(out)


def section_html(sec) -> str:
    parts = [f"<h2>{sec.title}</h2>"]
    parts += [f"<p>{p}</p>" for p in sec.paragraphs]
    if sec.rows:
        parts.append(table_html(sec.rows))
    parts += [f"<p>{p}</p>" for p in sec.after]
    return "".join(parts)


def title_html(c: ReportContent) -> str:
    p = c.profile
    meta = [("Profile", html.escape(p.name)), ("Date", c.date), ("zwidth version", html.escape(c.version)),
            ("Display type", p.display)]
    if c.source:
        meta.insert(1, ("File", html.escape(os.path.basename(c.source))))
    rows = "".join(f"<tr><td width='22%'><b>{k}</b></td><td>{v}</td></tr>" for k, v in meta)
    notes = f"<p><b>Notes.</b> {html.escape(p.notes)}</p>" if p.notes.strip() else ""
    return (f"<h1>{c.title}</h1><p class='meta'>Two-port virtual coupling design and Z-width analysis</p>"
            f"<table cellspacing='0' cellpadding='2' class='meta'>{rows}</table>{notes}")


class _Block:
    height = 0.0
    keep = False  # start on a new page rather than split (every block is unsplittable anyway)

    def draw(self, painter: QPainter, x: float, y: float) -> None:
        raise NotImplementedError


class _Text(_Block):
    def __init__(self, text: str, width: float, device) -> None:
        self.doc = QTextDocument()
        self.doc.documentLayout().setPaintDevice(device)
        self.doc.setDefaultStyleSheet(CSS)
        font = QFont()
        font.setPointSizeF(9.5)
        self.doc.setDefaultFont(font)
        self.doc.setDocumentMargin(0)
        self.doc.setHtml(f"<body>{text}</body>")
        self.doc.setTextWidth(width)
        self.height = self.doc.size().height()

    def draw(self, painter: QPainter, x: float, y: float) -> None:
        painter.save()
        painter.translate(x, y)
        self.doc.drawContents(painter)
        painter.restore()


class _Figure(_Block):
    def __init__(self, fig: Figure, number: int, width: float, device) -> None:
        self.fig = fig
        self.head = _Text(f"<p class='fig'>Figure {number}. {fig.title}</p>", width, device)
        self.cap = _Text(f"<p class='cap'>{fig.caption}</p>", width, device)
        src = fig.view.plot_widget.viewport().rect()
        self.plot_w = width
        self.plot_h = width * src.height() / max(src.width(), 1)
        self.height = self.head.height + self.plot_h + 4 + self.cap.height

    def draw(self, painter: QPainter, x: float, y: float) -> None:
        self.head.draw(painter, x, y)
        y += self.head.height
        target = QRectF(x, y, self.plot_w, self.plot_h)
        painter.save()
        painter.setClipRect(target)
        self.fig.view.render_into(painter, target)
        painter.restore()
        painter.setPen(QPen(QColor("#c8d0da"), 0.8))
        painter.drawRect(target)
        self.cap.draw(painter, x, y + self.plot_h + 4)


def _paginate(blocks: list[_Block], avail: float) -> list[list[_Block]]:
    pages: list[list[_Block]] = [[]]
    used = 0.0
    for b in blocks:
        need = b.height + (GAP if pages[-1] else 0)
        if pages[-1] and (used + need > avail or b.keep):
            pages.append([])
            used = 0.0
            need = b.height
        pages[-1].append(b)
        used += need
    return pages


def _blocks(content: ReportContent, figures: list[Figure], width: float, writer: QPdfWriter) -> list[_Block]:
    """The report as unsplittable blocks, the "Figures" heading kept with the first figure."""
    blocks: list[_Block] = [_Text(title_html(content), width, writer)]
    for sec in content.sections:
        blocks.append(_Text(section_html(sec), width, writer))
    first_fig = _Text("<h2>Figures</h2>", width, writer)
    first_fig.keep = True
    blocks.append(first_fig)
    for i, fig in enumerate(figures, 1):
        blocks.append(_Figure(fig, i, width, writer))
    blocks.append(_Text("<h2>Methods</h2>" + "".join(f"<p>{p}</p>" for p in content.methods), width, writer))
    merged: list[_Block] = []
    for b in blocks:
        if merged and merged[-1] is first_fig and isinstance(b, _Figure):
            b.keep = True
            b.head = _Text(f"<h2>Figures</h2><p class='fig'>Figure 1. {b.fig.title}</p>", width, writer)
            b.height = b.head.height + b.plot_h + 4 + b.cap.height
            merged[-1] = b
            continue
        merged.append(b)
    return merged


def _frame(painter: QPainter, content: ReportContent, page: QSizeF, width: float, n: int, total: int) -> None:
    """Running header (profile, date) and footer (version, page n of total)."""
    small = QFont()
    small.setPointSizeF(8)
    painter.setFont(small)
    painter.setPen(QColor("#6b7785"))
    top = QRectF(MARGIN_X, MARGIN_TOP - 40, width, 20)
    painter.drawText(top, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter,
                     f"zwidth design report — {content.profile.name}")
    painter.drawText(top, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter, content.date)
    painter.setPen(QPen(QColor("#c8d0da"), 0.8))
    painter.drawLine(int(MARGIN_X), int(MARGIN_TOP - 16), int(MARGIN_X + width), int(MARGIN_TOP - 16))
    bottom = QRectF(MARGIN_X, page.height() - MARGIN_BOTTOM + 24, width, 20)
    painter.drawLine(int(MARGIN_X), int(bottom.top() - 6), int(MARGIN_X + width), int(bottom.top() - 6))
    painter.setPen(QColor("#6b7785"))
    painter.drawText(bottom, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter, f"zwidth {content.version}")
    painter.drawText(bottom, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter, f"Page {n} of {total}")


def write_pdf(content: ReportContent, figures: list[Figure], path: str | os.PathLike,
              page_size: str = "a4") -> int:
    """Write the PDF report with :func:`analysis.profiles.atomic_write` (Qt's writer renders to its
    temporary file); returns the page count.  Raises its ``WriteError`` when the file cannot be written."""
    if page_size not in PAGE_SIZES:
        raise ValueError(f"page size must be one of {', '.join(PAGE_SIZES)}, got {page_size!r}")
    pages: list[int] = []
    atomic_write(path, lambda tmp: pages.append(_render(content, figures, tmp, page_size)))
    return pages[0]


def _render(content: ReportContent, figures: list[Figure], path: str, page_size: str) -> int:
    """Draw the report into a new PDF file at ``path``; returns the page count."""
    writer = QPdfWriter(path)
    writer.setResolution(DPI)
    writer.setPageLayout(QPageLayout(QPageSize(PAGE_SIZES[page_size]), QPageLayout.Orientation.Portrait,
                                     QMarginsF(0, 0, 0, 0)))
    writer.setTitle(f"zwidth report: {content.profile.name}")
    writer.setCreator(f"zwidth {content.version}")
    page = QSizeF(writer.width(), writer.height())
    width = page.width() - 2 * MARGIN_X
    pages = _paginate(_blocks(content, figures, width, writer), page.height() - MARGIN_TOP - MARGIN_BOTTOM)
    painter = QPainter()
    if not painter.begin(writer):  # Qt gives no reason: "QPainter::begin(): Returned false"
        raise OSError(unwritable_reason(path) or "the PDF writer cannot open the file")
    try:
        for n, blist in enumerate(pages, 1):
            if n > 1:
                writer.newPage()
            _frame(painter, content, page, width, n, len(pages))
            y = float(MARGIN_TOP)
            for i, b in enumerate(blist):
                if i:
                    y += GAP
                b.draw(painter, MARGIN_X, y)
                y += b.height
    finally:
        painter.end()
    del writer  # the file is complete once the writer is gone
    return len(pages)
