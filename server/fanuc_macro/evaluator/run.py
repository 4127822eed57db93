"""Evaluating a set of documents: choose the entry programs, run each, collect the facts."""

from __future__ import annotations

import time
from collections.abc import Sequence

from ..cancel import COMPILING, SLICE, CancelToken
from ..config import Config
from ..index import ProgramIndex
from ..syntax import Document
from .facts import Facts
from .machine import Machine, ProgramContext, build_contexts, compiled


def entry_programs(every: Sequence[ProgramContext], only_uri: str | None) -> list[ProgramContext]:
    """Programs nothing calls (by a constant P), in file order; a file's first if all are called."""
    called: set[int] = set()
    for ctx in every:
        for call in ctx.program.calls:
            if call.program is not None:
                called.add(call.program)
    entries = [
        ctx
        for ctx in every
        if (only_uri is None or ctx.uri == only_uri)
        and (ctx.program.number is None or ctx.program.number not in called)
    ]
    if not entries:
        firsts: dict[str, ProgramContext] = {}
        for ctx in every:
            if only_uri is None or ctx.uri == only_uri:
                firsts.setdefault(ctx.uri, ctx)
        entries = list(firsts.values())
    return entries


def evaluate(
    docs: Sequence[tuple[str, Document, ProgramIndex]],
    config: Config | None = None,
    only_uri: str | None = None,
    entry: int | None = None,
    cancel: CancelToken | None = None,
) -> Facts:
    """Run every entry program (or O``entry``) of ``docs`` within the configured budgets;
    ``cancel`` may stop it (see :mod:`fanuc_macro.cancel`)."""
    config = config or Config()
    facts = Facts()
    if cancel is not None:
        _compile_lines(docs, cancel)
    programs, every = build_contexts(list(docs), facts)
    if entry is not None:
        chosen = programs.get(entry)
        entries = [chosen] if chosen is not None else []
    else:
        entries = entry_programs(every, only_uri)
    # One wall-clock limit for the whole analysis, a safety net only: the step budget, per
    # entry, is what ends a run that goes on (see Config).
    deadline = time.monotonic() + config.time_limit
    machine = Machine(programs, config, facts, cancel)
    reasons: list[str] = []
    for ctx in entries:
        machine.steps = 0
        reasons.append(machine.run(ctx, deadline))
        facts.steps += machine.steps
    # Programs nothing ran (a subprogram whose caller is elsewhere): analyse them alone.
    for ctx in every if entry is None else ():
        if only_uri is not None and ctx.uri != only_uri:
            continue
        if ctx.program.first_line in ctx.facts.analysed_programs:
            continue
        machine.steps = 0
        reasons.append(machine.run(ctx, deadline))
        facts.steps += machine.steps
    if "time" in reasons:
        facts.stopped = "time"
        facts.time_limit = config.time_limit
    elif "budget" in reasons:
        facts.stopped = "budget"
    return facts


def _compile_lines(docs: Sequence[tuple[str, Document, ProgramIndex]], cancel: CancelToken) -> None:
    """Compile the documents' lines a slice at a time, looking at ``cancel`` between slices:
    :func:`build_contexts` then finds them in the per-line cache (a cold 200,000-block file
    takes seconds to compile, too long to wait for a newer edit)."""
    total = sum(len(doc.blocks) for _, doc, _ in docs)
    done = 0
    for _, doc, _ in docs:
        blocks = doc.blocks
        for start in range(0, len(blocks), SLICE):
            if done >= SLICE:
                cancel.reached(COMPILING, done, total)
            for block in blocks[start : start + SLICE]:
                compiled(block.parsed)
            done += min(SLICE, len(blocks) - start)
