"""Cancelling an analysis: it stops at a block boundary, keeps nothing, and the next analysis
of the same text gives what an analysis never cancelled gives."""

from __future__ import annotations

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.cancel import (
    CHECKING,
    COMPILING,
    READING,
    RULE_CHECKS,
    RUNNING,
    SLICE,
    Cancelled,
    CancelToken,
    Stage,
)
from fanuc_macro.config import Config
from fanuc_macro.evaluator import evaluate
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.workspace import Workspace

URI = "file:///cancel/o1000.nc"
CONFIG = Config()


def program(motions: int = 3 * SLICE) -> str:
    """A loop the evaluator runs a few thousand blocks through, motion blocks enough for
    several slices of every stage, and a few findings for the rules."""
    rows = [f"G01 X{i % 97}.{i % 7} Z-{i % 89}.{i % 3} F0.2 (pass {i})" for i in range(motions)]
    return "\n".join(
        [
            "%",
            "O1000 (cancel test)",
            "#1=0",
            "WHILE[#1LT1500]DO1",
            "#1=#1+1",
            "#2=#1*2.",
            "END1",
            *rows,
            "#3=SQRT[-1.]",
            "GOTO 9999",
            "M30",
            "%",
        ]
    )


def cancel_at(stage: Stage) -> CancelToken:
    """A token that cancels itself at the second checkpoint of ``stage`` (as another thread
    would while the analysis is there)."""
    seen: list[int] = []

    def observe(reached: Stage, done: int, total: int) -> None:
        if reached is stage:
            seen.append(done)
            if len(seen) == 2:
                token.cancel()

    token = CancelToken(observe)
    return token


def test_a_token_already_set_stops_the_analysis_before_it_reads_anything() -> None:
    parser = BlockParser()
    token = CancelToken()
    token.cancel()
    with pytest.raises(Cancelled) as raised:
        analyse(program(), URI, CONFIG, parser=parser, cancel=token)
    assert raised.value.stage is None and raised.value.where() == "before it began"
    assert not parser._cache  # not one line parsed
    ws = Workspace(CONFIG, parser)
    with pytest.raises(Cancelled):
        ws.add_text(URI, program(), token)
    assert ws.document(URI) is None and not parser._cache


@pytest.mark.parametrize(
    "stage", [READING, COMPILING, RUNNING, CHECKING, RULE_CHECKS], ids=lambda s: s.name
)
def test_an_analysis_cancelled_at_any_stage_then_run_again_is_the_same(stage: Stage) -> None:
    text = program()
    reference = Workspace(CONFIG, BlockParser())
    reference.add_text(URI, text)
    expected = reference.analyse(URI)
    assert expected.facts is not None and expected.facts.steps > 4 * 512
    assert {"MB101"} <= {d.code for d in expected.diagnostics}

    ws = Workspace(CONFIG, BlockParser())
    old = ws.add_text(URI, "O1000\nG01 X1. Z1.\nM30\n")
    old_analysis = ws.analyse(URI)
    token = cancel_at(stage)
    with pytest.raises(Cancelled) as raised:
        ws.add_text(URI, text, token)
        ws.analyse(URI, cancel=token)
    cancelled = raised.value
    assert cancelled.stage is stage and 0 < cancelled.done < cancelled.total
    assert stage.name in cancelled.where()
    if stage is READING:
        assert ws.document(URI) is old  # the workspace keeps the text it had
        assert ws.analyse(URI).diagnostics == old_analysis.diagnostics
        ws.add_text(URI, text)
    again = ws.analyse(URI)
    assert again.diagnostics == expected.diagnostics
    assert again.facts is not None and again.facts.steps == expected.facts.steps
    assert again.facts.stopped == expected.facts.stopped


def test_the_parse_and_the_evaluator_give_the_same_with_a_token() -> None:
    text = program()
    plain = parse_text(text, URI, BlockParser())
    with_token = parse_text(text, URI, BlockParser(), cancel=CancelToken())
    assert [b.parsed for b in plain.blocks] == [b.parsed for b in with_token.blocks]
    seen: list[tuple[str, int]] = []
    token = CancelToken(lambda stage, done, total: seen.append((stage.name, done)))
    index = build_index(plain)
    facts = evaluate([(URI, plain, index)], CONFIG, only_uri=URI, cancel=token)
    alone = evaluate([(URI, plain, index)], CONFIG, only_uri=URI)
    assert facts.steps == alone.steps and facts.stopped == alone.stopped
    # The run looks at the token every 1,024 blocks, before the 1,024th runs.
    assert ("running the program", 1023) in seen
    assert ("compiling blocks", SLICE) in seen


def test_a_short_document_reaches_no_checkpoint_of_its_blocks() -> None:
    """What the language server's progress relies on: a document of fewer blocks than a slice
    (and a short run) reports no block count, so its analysis never shows progress."""
    seen: list[Stage] = []
    analyse(
        "O1000\n#1=1\nG01 X#1 Z1. F0.2\nM30\n",
        URI,
        CONFIG,
        parser=BlockParser(),
        cancel=CancelToken(lambda stage, done, total: seen.append(stage)),
    )
    assert seen and all(not stage.counts_blocks for stage in seen)
