"""Malformed trials files (issue 22), shared by the reader tests and the command-line tests.

Each case is ``(name, write, line, column, words)``: ``write(path)`` makes the file (or a folder, or
nothing), ``line``/``column`` are where :func:`analysis.sampled.load_trials` must place the fault
(``None``: the file as a whole) and ``words`` must appear in the message.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple


class BadFile(NamedTuple):
    name: str
    write: Callable[[Path], None]
    line: int | None
    column: str | None
    words: str


def _text(text: str) -> Callable[[Path], None]:
    return lambda p: p.write_text(text, encoding="utf-8")


def _bytes(data: bytes) -> Callable[[Path], None]:
    return lambda p: p.write_bytes(data)


GOOD = "b,k,stable\n1,5000,1\n10,8000,0\n"

BAD_TRIALS = [
    BadFile("missing-stable-column", _text("b,k\n1,5000\n"), 1, "stable", "column is missing"),
    BadFile("missing-b-column", _text("# bench\nk,stable\n1,1\n"), 2, "b", "column is missing"),
    BadFile("stable-yes", _text("b,k,stable\n1,5000,1\n1,6000,yes\n"), 3, "stable", "'yes' is not"),
    BadFile("stable-true", _text("b,k,stable\n1,5000,true\n"), 2, "stable", "'true' is not"),
    BadFile("stable-2", _text("b,k,stable\n1,5000,2\n"), 2, "stable", "'2' is not"),
    BadFile("stable-empty", _text("b,k,stable\n1,5000,\n"), 2, "stable", "empty"),
    BadFile("text-in-k", _text("b,k,stable\n1,5000,1\n\n1,abc,0\n"), 4, "k", "'abc' is not a number"),
    BadFile("inf-in-k", _text("b,k,stable\n1,inf,1\n"), 2, "k", "not finite"),
    BadFile("nan-in-b", _text("b,k,stable\n1,5,1\nnan,5,1\n"), 3, "b", "not finite"),
    BadFile("negative-b", _text("b,k,stable\n-1,5000,1\n"), 2, "b", "negative"),
    BadFile("ragged-short", _text("b,k,stable\n1,5000,1\n1,5000\n"), 3, None, "2 values, the header has 3"),
    BadFile("ragged-long", _text("b,k,stable\n1,5000,1,extra\n"), 2, None, "4 values, the header has 3"),
    BadFile("duplicate-k", _text("b,k,k,stable\n1,2,3,1\n"), 1, "k", "duplicate column"),
    BadFile("header-only", _text("# bench\nb,k,stable\n"), 2, None, "at least one trial row"),
    BadFile("empty-file", _text(""), None, None, "empty file"),
    BadFile("comments-only", _text("# nothing yet\n\n"), None, None, "empty file"),
    BadFile("nonexistent", lambda p: None, None, None, "no such file"),
    BadFile("directory", lambda p: p.mkdir(), None, None, "folder"),
    BadFile("utf16-bom", lambda p: p.write_text(GOOD, encoding="utf-16"), None, None, "UTF-16"),
    BadFile("utf16-no-bom", _bytes(GOOD.encode("utf-16-le")), 1, None, "NUL"),
    BadFile("latin1-byte", _bytes(b"b,k,stable,note\n1,5000,1,ok\n1,6000,0,caf\xe9\n"), 3, None, "not UTF-8"),
]
