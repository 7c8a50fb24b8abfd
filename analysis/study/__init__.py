"""What zwidth computes for a profile: one definition shared by the GUI, the CLI and the report.
"""

from __future__ import annotations

from .summary import (  # noqa: F401
    summarize,
    format_summary,
    design_summary,
    format_design,
    SUMMARY_VERSION,
)

__all__ = [
    "summarize",
    "format_summary",
    "design_summary",
    "format_design",
    "SUMMARY_VERSION",
]
