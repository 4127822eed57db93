"""The executed motion blocks of a program, with computed addresses (``fanuc-macro trace``)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from typing import Any

from ..config import Config
from ..evaluator import evaluate
from ..evaluator.values import fmt_address
from ..program.index import ProgramIndex
from ..syntax.tree import Document


def trace(
    uri: str,
    doc: Document,
    index: ProgramIndex,
    others: Sequence[tuple[str, Document, ProgramIndex]] = (),
    config: Config | None = None,
    entry: int | None = None,
) -> dict[str, Any]:
    """``{"motions": [{program, line, code, words}], "summary": {...}}``; lines are 1-based."""
    facts = evaluate(
        [(uri, doc, index), *others], config, only_uri=None if entry else uri, entry=entry
    )
    motions = [
        {"program": m.program, "line": m.line + 1, "code": m.code, "words": m.words}
        | ({"path": m.uri} if m.uri != uri else {})
        for m in facts.motions
    ]
    codes = Counter(m.code for m in facts.motions)
    findings = [
        {"line": f.line + 1, "kind": f.kind, "message": f.message}
        for df in facts.by_uri.values()
        for f in df.findings
    ]
    return {
        "motions": motions,
        "summary": {
            "motions": len(motions),
            "by_code": dict(sorted(codes.items())),
            "blocks_executed": facts.steps,
            "stopped": facts.stopped,
            "stop_message": facts.stop_message(),
            "findings": findings,
        },
    }


def motion_text(motion: dict[str, Any]) -> str:
    """One motion of a trace as the command line prints it: program, line, code, its words at
    the control's precision."""
    words = " ".join(f"{k}{fmt_address(v)}" for k, v in motion["words"].items())
    return f"{motion['program']:<6} line {motion['line']:<5} {motion['code']:<4} {words}"
