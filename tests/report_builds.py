"""The reports of the bundled profiles, built once per test process for the modules that read them.

``test_report`` and ``test_report_faults`` check the same reports (every bundled profile, PDF and
HTML, the default page size and the profile file as the source): a report costs seconds, so they
share one build (issue 21). The result is immutable: the frozen content, the build info, and the
files' bytes and text (a test that wants a file writes its own copy).
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterator, Mapping
from types import MappingProxyType
from typing import Any, NamedTuple
from unittest import mock

import pypdf

from analysis.profiles.io import bundled_profiles, load_profile


class BuiltReport(NamedTuple):
    """One bundled profile's report, as :func:`app.report.build_report` wrote it."""

    content: Any  #: the ReportContent the PDF was built from (frozen)
    pdf: bytes
    info: Mapping[str, Any]  #: build_report's info of the PDF
    html: str
    pdf_pages: int
    pdf_text: str  #: the text of every page, joined by newlines


def _build(name: str, path: str, folder: str) -> BuiltReport:
    import io
    import tempfile

    import app.report.content as content_module
    from app.report import build_report

    profile = load_profile(path)
    seen: list[Any] = []
    calls: list[tuple[Any, Any]] = []
    gather = content_module.gather

    def recorded(*args: Any, **kwargs: Any) -> Any:  # the content the report is made of, not a third gather
        calls.append((args, kwargs))
        seen.append(gather(*args, **kwargs))
        return seen[-1]

    def again(*args: Any, **kwargs: Any) -> Any:  # the HTML's gather: the same call, so the same content
        assert (args, kwargs) == calls[0], "the HTML report gathers other content than the PDF"
        return seen[0]

    with tempfile.TemporaryDirectory(dir=folder) as tmp:
        pdf, page = f"{tmp}/{name}.pdf", f"{tmp}/{name}.html"
        with mock.patch.object(content_module, "gather", recorded):
            info = build_report(profile, pdf, source=str(path))
        assert len(seen) == 1, "build_report no longer gathers through app.report.content.gather"
        with mock.patch.object(content_module, "gather", again):  # gather is a pure function of its call
            html_info = build_report(profile, page, source=str(path))
        assert html_info["format"] == "html"
        with open(pdf, "rb") as f:
            data = f.read()
        with open(page, encoding="utf-8") as f:
            html = f.read()
    reader = pypdf.PdfReader(io.BytesIO(data))
    text = "\n".join(p.extract_text() for p in reader.pages)
    return BuiltReport(seen[0], data, MappingProxyType(dict(info)), html, len(reader.pages), text)


@functools.lru_cache(maxsize=None)
def bundled_report(folder: str, name: str) -> BuiltReport:
    """The report of the bundled profile ``name``, written under ``folder`` (a session's temporary
    folder) and removed again. Needs a ``QApplication`` (:func:`app.report.figures.ensure_app`)."""
    return _build(name, str(bundled_profiles()[name]), folder)


class LazyReports(Mapping[str, BuiltReport]):
    """{name: BuiltReport}, each report built when first read (:func:`bundled_report`): a test that
    reads one profile's report does not build the others (under xdist, the tests of one profile may
    run on another worker than those of the next)."""

    def __init__(self, folder: str, names: tuple[str, ...]) -> None:
        self._folder, self._names = folder, names

    def __getitem__(self, name: str) -> BuiltReport:
        if name not in self._names:
            raise KeyError(name)
        return bundled_report(self._folder, name)

    def __iter__(self) -> Iterator[str]:
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)


def bundled_reports(folder: str, names: tuple[str, ...] | None = None) -> Mapping[str, BuiltReport]:
    """{name: BuiltReport} for the bundled profiles ``names`` (all of them by default), built lazily."""
    return LazyReports(folder, tuple(names or sorted(bundled_profiles())))


def flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)
