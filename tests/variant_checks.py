"""What the variant tests read of a fixture program: its analysis, alone, as the CLI makes
it of one file, and its errors and warnings by (1-based line, code)."""

from __future__ import annotations

from functools import cache
from pathlib import Path

from fanuc_macro.analysis import Analysis, analyse
from fanuc_macro.diagnostics import Severity


@cache
def analysed(path: Path) -> Analysis:
    return analyse(path.read_text("utf-8"), path.as_uri())


def errors_and_warnings(path: Path) -> set[tuple[int, str]]:
    return {
        (d.line + 1, d.code)
        for d in analysed(path).diagnostics
        if d.severity in (Severity.ERROR, Severity.WARNING)
    }
