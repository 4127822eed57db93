"""MB2xx: WHILE/DO/END structure: pairs, loop numbers, nesting, crossed ranges."""

from __future__ import annotations

import re
from collections.abc import Iterator

from ..diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register
from .context import RuleContext

FAMILY = "loops"
register(
    RuleInfo("MB201", "do-without-end", Severity.ERROR,
             "A DO m with no END m after it in the program (alarm PS0124).", FAMILY),
    RuleInfo("MB202", "end-without-do", Severity.ERROR,
             "An END m with no open DO m before it (alarm PS0126).", FAMILY),
    RuleInfo("MB203", "loop-number", Severity.ERROR,
             "A DO/END identification number other than 1, 2 or 3 (alarm PS0126).", FAMILY),
    RuleInfo("MB204", "loop-too-deep", Severity.ERROR,
             "WHILE loops nested more than three deep.", FAMILY),
    RuleInfo("MB205", "loops-crossed", Severity.ERROR,
             "Loop ranges that cross (DO1 ... DO2 ... END1 ... END2).", FAMILY),
)  # fmt: skip


def _rejected_do_lines(ctx: RuleContext, start: int, end: int) -> dict[float, list[int]]:
    """Lines from ``start`` to ``end`` that FANUC rejects (MB001/MB002) and that hold 'DOm':
    the loop they open is not seen, and its END is no second mistake."""
    found: dict[float, list[int]] = {}
    for block in ctx.doc.blocks[start:end]:
        parsed = block.parsed
        if parsed.problem is None:
            continue
        for m in _DO_WORD.finditer(parsed.text):
            found.setdefault(float(m.group(1)), []).append(block.line)
    return found


_DO_WORD = re.compile(r"\bDO\s*(\d)\b", re.I)


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    unread = ctx.doc.unread_from
    for program in ctx.index.programs:
        name = program.display_name
        rejected_dos: dict[float, list[int]] | None = None
        # A program that goes on past the part of the file the analysis reads (MB013) may
        # have its END there.
        cut = unread is not None and program.end_line >= unread
        for p in program.loop_problems:
            if cut and p.kind == "no-end":
                continue
            if p.kind == "no-do":
                if rejected_dos is None:
                    rejected_dos = _rejected_do_lines(ctx, program.first_line, program.end_line)
                if any(line < p.line for line in rejected_dos.get(p.loop_id, ())):
                    continue  # its DO is in a block already reported as rejected
            n = f"{p.loop_id:g}"
            if p.kind == "no-end":
                yield make(
                    "MB201",
                    f"DO{n} has no END{n} in {name} (alarm PS0124)",
                    p.line,
                    p.span.start,
                    p.span.end,
                    data={"loop_id": n},
                )
            elif p.kind == "no-do":
                yield make(
                    "MB202",
                    f"END{n} closes no open DO{n} in {name} (alarm PS0126)",
                    p.line,
                    p.span.start,
                    p.span.end,
                )
            elif p.kind == "bad-id":
                yield make(
                    "MB203",
                    f"loop number {n} is outside 1-3 (alarm PS0126)",
                    p.line,
                    p.span.start,
                    p.span.end,
                )
            elif p.kind == "too-deep":
                related = (
                    []
                    if p.other_line is None
                    else [Related(p.other_line, 0, 0, "outermost loop starts here")]
                )
                yield make(
                    "MB204",
                    f"DO{n} is a fourth nested loop; FANUC nests at most three",
                    p.line,
                    p.span.start,
                    p.span.end,
                    related=related,
                )
            elif p.kind == "crossed":
                related = (
                    []
                    if p.other_line is None
                    else [Related(p.other_line, 0, 0, "inner loop opened here is still open")]
                )
                yield make(
                    "MB205",
                    f"END{n} closes DO{n} while a loop opened inside it (line "
                    f"{(p.other_line or 0) + 1}) is still open: loop ranges cross",
                    p.line,
                    p.span.start,
                    p.span.end,
                    related=related,
                )
