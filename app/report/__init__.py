"""Design reports: PDF and HTML built from the analysis core and the app's own plot views.

* :mod:`.model` is what a report is made of (rows, sections, figures, the parts each section
  returns) and how it prints a number; every other module imports it, it imports none of them;
* :mod:`.content` gathers every number (Qt-free), with :mod:`.identify_section` and
  :mod:`.zwidth_section` (Qt-free too);
* :mod:`.figures` draws them with the app's :class:`~app.views.base.PlotView` classes, offscreen,
  with :mod:`.plots`, :mod:`.identify_figures` and :mod:`.zwidth_figures`;
* :mod:`.pdf` and :mod:`.html` lay them out; :func:`build_report` picks by file extension;
* :mod:`.action` is File → Export Report… in the app.
"""

from __future__ import annotations

from analysis.progress import Cancelled, Progress, check_cancelled, report_progress

__all__ = ["build_report", "REPORT_FORMATS", "report_format", "report_stages"]

REPORT_FORMATS = {"pdf": "PDF document (*.pdf)", "html": "HTML page (*.html *.htm)"}


def report_format(path) -> str | None:
    """``"pdf"``, ``"html"`` or ``None`` from the file name's extension."""
    suffix = str(path).rsplit(".", 1)[-1].lower() if "." in str(path) else ""
    return {"pdf": "pdf", "html": "html", "htm": "html"}.get(suffix)


def report_stages(fmt: str) -> tuple[str, ...]:
    """What :func:`build_report` does next after ``progress(done, total)``: the text of stage ``done``
    (``total = len(stages) - 1``; the last is ``"Done"``) for a report of format ``fmt``."""
    return ("Analysing the profile", "Drawing the figures", f"Writing the {fmt.upper()}", "Done")


def build_report(profile, path, *, page_size: str = "a4", source: str | None = None,
                 progress: Progress | None = None, cancelled: Cancelled | None = None,
                 sampled: bool = True) -> dict:
    """Write the report of ``profile`` to ``path`` (format by extension); returns build info.

    The hooks of :mod:`analysis.progress`: ``progress(done, total)`` is called before each stage
    (:func:`report_stages` names them) and once written; ``cancelled()`` is polled before each
    stage, and once it is true the build stops and raises
    :class:`~analysis.progress.OperationCancelled` (``ReportCancelled``) with nothing written.
    Needs a ``QApplication`` (see :func:`.figures.ensure_app`).
    The file is written atomically (:func:`analysis.profiles.atomic_write`); a target that cannot
    be written (a folder, a missing folder) raises its ``WriteError`` (an ``OSError``) before any work.
    """
    import time

    from analysis.profiles import WriteError
    from analysis.profiles.files import unwritable_reason
    from app.report.content import gather
    from app.report.figures import build_figures

    fmt = report_format(path)
    if fmt is None:
        raise ValueError(f"{path}: the report format comes from the extension: .pdf or .html")
    reason = unwritable_reason(path)
    if reason is not None:  # say so before a minute of analysis, not after (a folder, a missing folder)
        raise WriteError(path, reason)
    t0 = time.perf_counter()
    total = len(report_stages(fmt)) - 1

    def step(done: int) -> None:
        report_progress(progress, done, total)
        check_cancelled(cancelled, "the report was cancelled")

    step(0)
    content = gather(profile, source=source, sampled=sampled)
    step(1)
    figures = build_figures(content)
    step(2)
    if fmt == "pdf":
        from app.report.pdf import write_pdf

        pages = write_pdf(content, figures, path, page_size=page_size)
    else:
        from app.report.html import write_html

        write_html(content, figures, path)
        pages = None
    report_progress(progress, total, total)  # written: too late to cancel
    for fig in figures:
        fig.view.deleteLater()
    return {"format": fmt, "pages": pages, "seconds": time.perf_counter() - t0, "figures": len(figures)}
