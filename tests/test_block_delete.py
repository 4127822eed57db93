"""Blocks that begin with '/' (block delete): the evaluator runs the programs with the
operator's block-delete switch off and, when a run reaches such a block, on. A block is never
executed (MB702) only when neither run reaches it; a finding of one run says which."""

from __future__ import annotations

import asyncio
import json
import random
from collections.abc import AsyncIterator
from pathlib import Path

import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

from cli_runner import run
from fanuc_macro.config import Config
from fanuc_macro.evaluator import evaluate
from fanuc_macro.evaluator.facts import SWITCH_OFF, SWITCH_ON, Facts
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.workspace import Workspace
from test_incremental import assert_same
from test_lsp import ENV, SERVER, WAIT, codes, edited_as_fresh, replace, start

ROOT = Path(__file__).resolve().parents[1]
RULES = ROOT / "tests" / "fixtures" / "rules"
URI = "file:///O1000.nc"

# The jump the switch decides: off, GOTO4 passes over lines 4-5; on, they run.
OPTIONAL_PASS = "O1000\n#1=1.\n/GOTO4\nG00 X10. Z5.\nG01 X0. F0.2\nN4 G00 X100. Z100.\nM30\n"


def evaluate_text(text: str, config: Config | None = None, previous: Facts | None = None) -> Facts:
    doc = parse_text(text, URI, BlockParser())
    return evaluate([(URI, doc, build_index(doc))], config, only_uri=URI, previous=previous)


def test_the_cli_reports_no_block_that_the_switch_on_runs() -> None:
    fixture = RULES / "MB702_never-executed_block-delete.nc"
    done = run(ROOT, "check", "--format", "json", str(fixture))
    found = [(d["code"], d["line"]) for d in json.loads(done.stdout)]
    # Lines 6-7 run when the switch is on; line 16 runs neither way.
    assert found == [("MB702", 16)], done.stdout


def test_the_cli_says_which_position_of_the_switch_an_alarm_needs() -> None:
    fixture = RULES / "MB502_zero-divide_block-delete.nc"
    done = run(ROOT, "check", "--format", "json", str(fixture))
    found = {d["line"]: d["message"] for d in json.loads(done.stdout) if d["code"] == "MB502"}
    assert sorted(found) == [5, 11, 17], done.stdout
    assert found[5].endswith(SWITCH_OFF)
    assert found[11].endswith(SWITCH_ON)
    assert "block-delete" not in found[17]  # the alarm of both runs, once, as it was


def test_a_program_without_a_reached_block_delete_runs_once() -> None:
    plain = evaluate_text(OPTIONAL_PASS.replace("/GOTO4", "GOTO4"))
    assert plain.ways is None
    # The '/' block after the jump: no run reaches it, so the switch changes nothing.
    unreached = evaluate_text(OPTIONAL_PASS.replace("/GOTO4", "GOTO4").replace("G01", "/G01"))
    assert unreached.ways is None
    both = evaluate_text(OPTIONAL_PASS)
    assert both.ways is not None
    off, on = both.ways
    assert 3 not in off.by_uri[URI].runs and 3 in on.by_uri[URI].runs
    assert both.by_uri[URI].runs.keys() == on.by_uri[URI].runs.keys()
    assert both.steps == off.steps + on.steps


def test_each_position_of_the_switch_has_the_step_budget() -> None:
    endless = "O1000\n/GOTO9\n#1=0\nWHILE[1EQ1]DO1\n#1=#1+1\nEND1\nN9 M30\n"
    config = Config(step_budget=5_000)
    facts = evaluate_text(endless, config)
    assert facts.ways is not None
    off, on = facts.ways
    assert off.stopped is None and on.stopped == "budget"
    assert on.steps <= 5_001
    messages = [f.message for f in facts.by_uri[URI].findings]
    assert messages and all(m.endswith(SWITCH_ON) for m in messages), messages


def test_the_runs_are_the_same_on_every_evaluation() -> None:
    text = (RULES / "MB502_zero-divide_block-delete.nc").read_text("utf-8")
    assert_same(evaluate_text(text), evaluate_text(text))


def _long_program_with_block_delete(blocks: int) -> list[str]:
    rng = random.Random(5)
    lines = ["O1000", "#1=0", "/#1=1.", "#2=0"]
    for i in range(blocks):
        if i % 50 == 0:
            lines.append(f"IF[#1EQ1]GOTO{i + 1}")
        lines.append(f"G01 X{rng.randrange(10, 90)}. Z-{i % 40}. F0.{rng.randrange(1, 9)}")
        if i % 50 == 0:
            lines.append(f"N{i + 1} G00 X100.")
        lines.append(f"#2=#2+{rng.randrange(1, 9)}")  # run with the switch off and on
    return [*lines, "G00 X100. Z100.", "M30"]


def test_both_runs_resume_after_an_edit_and_equal_a_fresh_run() -> None:
    lines = _long_program_with_block_delete(3_000)
    first = evaluate_text("\n".join(lines))
    assert first.ways is not None
    late = next(i for i in range(len(lines) * 3 // 4, len(lines)) if lines[i].startswith("#2="))
    lines[late] = "#2=#2+7"
    edited = "\n".join(lines)
    resumed = evaluate_text(edited, previous=first)
    assert resumed.ways is not None
    for way, before in zip(resumed.ways, first.ways, strict=True):
        assert way.record is not None and before.record is not None
        assert way.record.resumed_at is not None
        assert way.record.executed < before.record.executed // 2
    assert_same(resumed, evaluate_text(edited))


def test_typing_and_removing_a_block_delete_equals_a_fresh_analysis() -> None:
    text = (RULES / "MB502_zero-divide_block-delete.nc").read_text("utf-8")
    versions = [
        OPTIONAL_PASS,
        OPTIONAL_PASS.replace("/GOTO4", "GOTO4"),  # the '/' removed: one run
        OPTIONAL_PASS.replace("/GOTO4", "/GOTO4\n/#1=0").replace("F0.2", "F#1"),
        OPTIONAL_PASS,
        text,
        text.replace("/#1=4.", "#1=4."),
        text.replace("#1=4.\n/#1=0", "#1=4.\n\n/#1=0"),  # lines moved
        text,
    ]
    ws = Workspace()
    for version in versions:
        ws.add_text(URI, version)
        edited = ws.analyse(URI)
        fresh = Workspace()
        fresh.add_text(URI, version)
        assert edited.diagnostics == fresh.analyse(URI).diagnostics, version


# ---- the language server ---------------------------------------------------------------------


@pytest_lsp.fixture(config=ClientServerConfig(server_command=SERVER, server_env=ENV))
async def client(lsp_client: LanguageClient) -> AsyncIterator[None]:
    yield
    if lsp_client.capabilities is not None:
        await asyncio.wait_for(lsp_client.shutdown_session(), WAIT)


async def test_typing_a_block_delete_before_a_goto_runs_what_it_passes_over(
    client: LanguageClient,
) -> None:
    await start(client, None)
    # A block after the M30 stays never executed (MB702, line 7): the fresh analysis of the
    # edited text has a diagnostic to wait for.
    text = OPTIONAL_PASS.replace("/GOTO4", "GOTO4") + "G00 X1.\n"
    edited = OPTIONAL_PASS + "G00 X1.\n"
    found = await edited_as_fresh(
        client,
        "block-delete",
        text,
        replace(2, 0, 0, "/"),
        edited,
        lambda d: [x.range.start.line for x in d] == [7],
    )
    assert [(d.code, d.range.start.line) for d in found] == [("MB702", 7)]


async def test_an_alarm_only_the_switch_on_reaches_says_so(client: LanguageClient) -> None:
    await start(client, None)
    text = "O1000\n#1=0\n#1=4.\n#9=800./#1\nG01 X10. F#9\nM30\n"
    edited = text.replace("#1=4.", "/#1=4.")
    found = await edited_as_fresh(
        client,
        "block-delete-alarm",
        text,
        replace(2, 0, 0, "/"),
        edited,
        lambda d: "MB502" in codes(d),
    )
    alarm = next(d for d in found if d.code == "MB502")
    assert alarm.message.endswith(SWITCH_ON), alarm.message
    assert alarm.range.start == types.Position(line=3, character=3)
