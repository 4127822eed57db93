"""MB1xx: GOTO targets: missing labels, duplicated labels, jumps into loops."""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic, Related, RuleInfo, Severity, make, register
from .context import RuleContext

FAMILY = "jumps"
register(
    RuleInfo("MB101", "goto-missing-label", Severity.ERROR,
             "GOTO to a sequence number that is not in the program.", FAMILY),
    RuleInfo("MB102", "duplicate-label", Severity.WARNING,
             "A sequence number that a GOTO uses stands more than once in the program.", FAMILY),
    RuleInfo("MB103", "goto-into-loop", Severity.ERROR,
             "GOTO from outside a WHILE loop to a block inside it.", FAMILY),
    RuleInfo("MB104", "goto-bad-target", Severity.ERROR,
             "GOTO target that is not a whole number from 1 to 99999.", FAMILY),
)  # fmt: skip


def check(ctx: RuleContext) -> Iterator[Diagnostic]:
    for program in ctx.index.programs:
        name = program.display_name
        for jump in program.jumps:
            ts = jump.target_span
            if jump.target is None:
                if jump.constant is not None:
                    yield make(
                        "MB104",
                        f"GOTO target {jump.constant:g} is not a whole number (alarm PS0128)",
                        jump.line,
                        ts.start,
                        ts.end,
                    )
                continue
            if not 1 <= jump.target <= 99999:
                yield make(
                    "MB104",
                    f"GOTO target {jump.target} is outside 1-99999 (alarm PS0128)",
                    jump.line,
                    ts.start,
                    ts.end,
                )
                continue
            lines = program.labels.get(jump.target)
            if not lines:
                yield make(
                    "MB101",
                    f"GOTO {jump.target}: no N{jump.target} in {name} (alarm "
                    "PS0128 when the jump is taken)",
                    jump.line,
                    ts.start,
                    ts.end,
                )
                continue
            if len(lines) > 1:
                related = [Related(ln, 0, 0, f"N{jump.target} also here") for ln in lines]
                yield make(
                    "MB102",
                    f"GOTO {jump.target}: N{jump.target} stands {len(lines)} times"
                    f" in {name} (lines {', '.join(str(ln + 1) for ln in lines)}); the "
                    "control searches forward from the GOTO and takes the first it meets",
                    jump.line,
                    ts.start,
                    ts.end,
                    related=related,
                )
            target_line = program.label_line(jump.target, jump.line)
            assert target_line is not None
            target_loops = program.enclosing_loops(target_line)
            source_loops = program.enclosing_loops(jump.line)
            for loop in target_loops:
                if loop not in source_loops:
                    yield make(
                        "MB103",
                        f"GOTO {jump.target} jumps into the DO{loop.loop_id:g} "
                        f"loop of line {loop.do_line + 1} from outside it; FANUC forbids "
                        "branching into a loop",
                        jump.line,
                        ts.start,
                        ts.end,
                        related=[Related(loop.do_line, 0, 0, "the loop starts here")],
                    )
                    break
