"""An evaluation resumed from the checkpoints of an earlier one equals a full run, always.

Random edits (a number changed, a line replaced by another of the file, a line emptied, two
lines swapped, a variable renumbered) of the seed programs, the rule fixtures and generated
long programs; after each, the facts of the resumed evaluation are compared, field by field
and value by value, with those of a fresh one; edits are chained, each resuming from the one
before. Other tests check that the resumption really saves work.
"""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.evaluator import (
    Facts,
    Motion,
    ValueSummary,
    canned_cycles,
    evaluate,
    machine,
    motion,
)
from fanuc_macro.evaluator.facts import same_value
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.workspace import Workspace

FIXTURES = Path(__file__).parent / "fixtures"
PROGRAMS = sorted(
    [
        *(FIXTURES / "seeds").glob("*.nc"),
        *(FIXTURES / "thread_variants").glob("*.nc"),
        *(FIXTURES / "rules").glob("*.nc"),
    ]
)
URI = "file:///edit.nc"


FIELDS = (
    "runs",
    "reads",
    "writes",
    "jumps",
    "findings",
    "analysed",
    "incomplete",
    "roundings",
    "ends",
    "assumed",
    "feedless",
)


def digest(facts: Facts) -> dict[str, object]:
    """Everything the rules and the editor read of the facts, as plain values, by name."""

    def summary(s: ValueSummary) -> tuple[object, ...]:
        return (s.count, s.first, s.last, s.minimum, s.maximum, s.vacant, s.unknown)

    out: dict[str, object] = {}
    for uri, d in facts.by_uri.items():
        parts: tuple[object, ...] = (
            dict(d.runs),
            {k: summary(v) for k, v in d.reads.items()},
            {k: (n, summary(v)) for k, (n, v) in d.writes.items()},
            {k: (j.taken, j.not_taken, j.undecided, j.guessed) for k, j in d.jumps.items()},
            [vars(f) for f in d.findings],
            sorted(d.analysed_programs),
            sorted(d.incomplete_programs),
            {k: (r.function, r.argument, r.result, r.count) for k, r in d.roundings.items()},
            dict(d.program_ends),
            list(d.assumed_arguments.items()),
            {k: (p.message, p.count, p.lines) for k, p in d.feedless().items()},
        )
        for name, part in zip(FIELDS, parts, strict=True):
            out[f"{uri} {name}"] = part
    out["motions"] = [tuple(getattr(m, n) for n in Motion.__slots__) for m in facts.motions]
    out["run values"] = [(k, v.locals, v.globals) for k, v in facts.run_values.items()]
    out["steps"] = facts.steps
    out["stopped"] = facts.stopped
    return out


def assert_same(resumed: Facts, full: Facts) -> None:
    a, b = digest(resumed), digest(full)
    assert a.keys() == b.keys()
    for name, value in a.items():
        assert same_value(value, b[name]), f"{name}: {value!r:.600} != {b[name]!r:.600}"


def evaluate_text(
    text: str, parser: BlockParser, config: Config, previous: Facts | None = None
) -> Facts:
    doc = parse_text(text, URI, parser)
    return evaluate([(URI, doc, build_index(doc))], config, only_uri=URI, previous=previous)


NUMBER = re.compile(r"(?<![#A-Z])\d+\.?\d*|(?<=#)\d+")


def mutate(lines: list[str], rng: random.Random, shift: bool = False) -> list[str]:
    """One edit as a user makes while typing; with ``shift``, one in three adds or removes
    lines (a new line, a line deleted, a block of lines pasted or cut)."""
    out = list(lines)
    i = rng.randrange(len(out))
    if shift and rng.randrange(3) == 0:
        pick = rng.randrange(4)
        if pick == 0:  # Enter: an empty line
            out.insert(i, "")
        elif pick == 1 and len(out) > 2:  # a line deleted
            del out[i]
        elif pick == 2:  # lines of the file pasted
            j = rng.randrange(len(out))
            out[i:i] = out[j : j + rng.randrange(1, 6)]
        elif len(out) > 8:  # lines cut
            del out[i : i + rng.randrange(2, 6)]
        return out
    kind = rng.randrange(6)
    if kind == 5:  # a bracket typed or removed: the block no longer reads (nor moves)
        j = out[i].find("]")
        out[i] = out[i][:j] + out[i][j + 1 :] if j >= 0 else out[i] + " X1["
    elif kind == 0 or kind == 4:  # a number (or a variable's number) changed
        found = list(NUMBER.finditer(out[i]))
        if found:
            m = rng.choice(found)
            digits = str(rng.choice([0, 1, 2, 3, 5, 9, 10, 25, 100, 101, 0.5]))
            out[i] = out[i][: m.start()] + digits + out[i][m.end() :]
    elif kind == 1:  # a line replaced by another line of the file
        out[i] = out[rng.randrange(len(out))]
    elif kind == 2:  # a line emptied
        out[i] = ""
    else:  # two lines swapped
        j = rng.randrange(len(out))
        out[i], out[j] = out[j], out[i]
    return out


def resume_through_random_edits(
    lines: list[str],
    rng: random.Random,
    parser: BlockParser,
    config: Config,
    previous: Facts,
    edits: int,
) -> None:
    """Edit ``lines`` at random ``edits`` times; after each, the run resumed from the one
    before equals a full run with a parser of its own."""
    for _ in range(edits):
        lines = mutate(lines, rng, shift=True)
        text = "\n".join(lines)
        resumed = evaluate_text(text, parser, config, previous)
        full = evaluate_text(text, BlockParser(), config)
        assert_same(resumed, full)
        previous = resumed


def long_program(blocks: int, seed: int) -> str:
    """A long main program with loops, calls of a subprogram and thread passes."""
    rng = random.Random(seed)
    lines = ["%", "O1000 (LONG)", "#100=50.", "#101=3.", "#102=40."]
    i = 0
    while len(lines) < blocks:
        i += 1
        pick = rng.randrange(6)
        if pick == 0:
            lines += [
                f"#{1 + i % 30}=#101*{i % 7 + 1}.+SQRT[{i % 11 + 1}.]",
                f"G00 X[#100+{i % 5 + 1}.] Z{i % 9 + 2}.",
            ]
        elif pick == 1:
            lines += [f"G92 X[#100-0.{i % 9 + 1}] W-[#102+#101] F#101", f"G01 W[{i % 3}.*0.1]"]
        elif pick == 2:
            lines += [
                "#20=0",
                f"WHILE[#20LT{rng.randrange(2, 40)}]DO1",
                "#20=#20+1",
                f"#{110 + i % 5}=#{110 + i % 5}+#20*0.{i % 9 + 1}",
                "END1",
            ]
        elif pick == 3:
            lines += ["M98 P2000", f"#{1 + i % 30}=#130+{i % 4}."]
        elif pick == 4:
            lines += [f"IF[#{1 + i % 30}GT{i % 13}.]GOTO{9000 + i}", "#31=#31+1", f"N{9000 + i}"]
        else:
            lines += [f"G01 X{rng.uniform(10, 90):.3f} Z{-rng.uniform(0, 80):.3f} F0.2"]
    lines += [
        "M30",
        "O2000 (SUB)",
        "#130=#130+1.",
        "#21=0",
        "WHILE[#21LT3]DO1",
        "#21=#21+1",
        "END1",
        "M99",
        "%",
    ]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.name)
def test_resumed_equals_full_after_random_edits(path: Path) -> None:
    rng = random.Random(path.name)
    # A small step budget: an edit that makes a loop endless ends soon, and the runs that
    # end at the budget (whose verdicts read the whole run) are resumed too.
    config = Config(step_budget=20_000)
    parser = BlockParser()
    lines = path.read_text("utf-8", errors="replace").splitlines()
    if not lines:
        return
    previous = evaluate_text("\n".join(lines), parser, config)
    resume_through_random_edits(lines, rng, parser, config, previous, 12)


@pytest.mark.parametrize("seed", range(4))
def test_long_programs_resume_and_equal_full(seed: int) -> None:
    rng = random.Random(seed)
    config = Config()
    parser = BlockParser()
    lines = long_program(12_000, seed).splitlines()
    previous = evaluate_text("\n".join(lines), parser, config)
    saved = 0
    for _ in range(6):
        lines = mutate(lines, rng, shift=True)
        text = "\n".join(lines)
        resumed = evaluate_text(text, parser, config, previous)
        full = evaluate_text(text, parser, config)
        assert_same(resumed, full)
        if resumed is not previous and resumed.record is not None and full.record is not None:
            saved += full.record.executed - resumed.record.executed
        previous = resumed
    assert saved > 0


def test_an_edit_late_in_a_long_program_runs_few_blocks() -> None:
    config = Config()
    parser = BlockParser()
    text = long_program(40_000, 11)
    lines = text.splitlines()
    first = evaluate_text(text, parser, config)
    assert first.record is not None and first.stopped is None
    total = first.record.executed
    # A number of an assignment three quarters down the program.
    line = next(
        i for i in range(len(lines) * 3 // 4, len(lines)) if re.match(r"#\d+=#101\*", lines[i])
    )
    lines[line] = lines[line].replace("#101*", "#101*2.*", 1)
    edited = "\n".join(lines)
    resumed = evaluate_text(edited, parser, config, first)
    assert resumed.record is not None
    assert resumed.record.resumed_at is not None
    assert resumed.record.converged_at is not None
    assert resumed.record.executed < total // 4
    assert_same(resumed, evaluate_text(edited, BlockParser(), config))


def test_a_bracket_being_typed_runs_few_blocks() -> None:
    # While "X[#100+2.]" is typed, the block does not read and does not move: the resumed run
    # meets the earlier one with one motion fewer, a few checkpoints later.
    config = Config()
    parser = BlockParser()
    text = long_program(20_000, 3)
    lines = text.splitlines()
    previous = evaluate_text(text, parser, config)
    line = next(i for i in range(len(lines) // 2, len(lines)) if lines[i].startswith("G00 X["))
    for typed in (lines[line].replace("]", "", 1), lines[line]):
        lines[line] = typed
        edited = "\n".join(lines)
        resumed = evaluate_text(edited, parser, config, previous)
        assert resumed.record is not None and resumed.record.converged_at is not None
        assert resumed.record.executed <= 4 * machine.CHECKPOINT_EVERY
        assert_same(resumed, evaluate_text(edited, BlockParser(), config))
        previous = resumed


def test_an_edit_in_a_comment_reuses_the_run() -> None:
    config = Config()
    parser = BlockParser()
    text = long_program(20_000, 3)
    first = evaluate_text(text, parser, config)
    edited = text.replace("#101=3.\n", "#101=3. (PITCH)\n", 1)
    again = evaluate_text(edited, parser, config, first)
    # The line ran once, at the start: the run resumes there and meets the earlier one at
    # its next checkpoint.
    assert again.record is not None and first.record is not None
    assert again.record.converged_at is not None
    assert again.record.executed <= 4096 < first.record.executed
    assert_same(again, evaluate_text(edited, BlockParser(), config))


def test_other_settings_run_in_full() -> None:
    parser = BlockParser()
    text = long_program(3_000, 5)
    first = evaluate_text(text, parser, Config())
    other = Config(step_budget=10_000)
    again = evaluate_text(text, parser, other, first)
    assert again.record is not None and again.record.resumed_at is None
    assert_same(again, evaluate_text(text, BlockParser(), other))


def test_analyse_with_previous_facts_gives_the_same_diagnostics() -> None:
    rng = random.Random(7)
    parser = BlockParser()
    lines = (FIXTURES / "seeds" / "o4009_external_m50x3.nc").read_text("utf-8").splitlines()
    previous = analyse("\n".join(lines), URI, parser=parser).facts
    for _ in range(20):
        lines = mutate(lines, rng)
        text = "\n".join(lines)
        resumed = analyse(text, URI, parser=parser, previous_facts=previous)
        full = analyse(text, URI, parser=BlockParser())
        assert resumed.diagnostics == full.diagnostics
        previous = resumed.facts


def test_a_new_line_late_in_a_long_program_runs_few_blocks() -> None:
    config = Config()
    parser = BlockParser()
    text = long_program(40_000, 11)
    lines = text.splitlines()
    first = evaluate_text(text, parser, config)
    assert first.record is not None
    total = first.record.executed
    line = next(
        i for i in range(len(lines) * 3 // 4, len(lines)) if re.match(r"#\d+=#101\*", lines[i])
    )
    for edited in (
        [*lines[:line], "(ADDED)", *lines[line:]],  # a line added
        [*lines[:line], *lines[line + 1 :]],  # a line removed
    ):
        source = "\n".join(edited)
        resumed = evaluate_text(source, parser, config, first)
        assert resumed.record is not None and resumed.record.resumed_at is not None
        assert resumed.record.converged_at is not None
        assert resumed.record.executed < total // 4
        assert_same(resumed, evaluate_text(source, BlockParser(), config))


def test_a_line_removed_from_a_program_of_few_distinct_lines_meets_the_earlier_run() -> None:
    """Most lines alike (a posted pattern repeated): boundary lines are dense, and a resumed
    run whose count of blocks the edit moved still meets the earlier run soon after it."""
    config = Config()
    parser = BlockParser()
    pattern = [
        "G00 X[#100+{a}.] Z{b}.",
        "G92 X[#100-0.{b}] W-[#102+#101] F#101",
        "G01 W[{c}.*0.1]",
        "#{v}=#101*{a}.+SQRT[{b}.] (STEP {k})",
    ]
    body = [
        line.format(a=k % 5 + 1, b=k % 9 + 1, c=k % 3, v=k % 30 + 1, k=k)
        for k in range(3000)
        for line in pattern
    ]
    lines = ["O1000", "#100=40.", "#101=2.", "#102=30.", *body, "M30"]
    first = evaluate_text("\n".join(lines), parser, config)
    assert first.record is not None
    removed = next(i for i in range(len(lines) // 2, len(lines)) if "SQRT" in lines[i])
    edited = "\n".join([*lines[:removed], *lines[removed + 1 :]])
    resumed = evaluate_text(edited, parser, config, first)
    assert resumed.record is not None and resumed.record.converged_at is not None
    assert resumed.record.executed <= 4 * machine.CHECKPOINT_EVERY
    assert_same(resumed, evaluate_text(edited, BlockParser(), config))


def cam_with_calls(blocks: int, seed: int) -> str:
    """CAM output without F, cut by a main program, a loop and a subprogram called more than
    once: the cuts without F repeat across stretches of the run, between other findings."""
    rng = random.Random(seed)
    lines = ["%", "O1000 (CAM)", "#1=0", "#9=2.5"]
    i = 0
    while len(lines) < blocks:
        i += 1
        pick = rng.randrange(12)
        if pick == 0:
            lines.append("M98 P2000")
        elif pick == 1:
            lines += ["#1=0", "WHILE[#1LT3]DO1", f"G01 X{i}. Z-{i % 7}.", "#1=#1+1", "END1"]
        elif pick == 2:
            lines.append("M#9")  # M2.5: another finding between the cuts
        elif pick == 3:
            lines.append(f"G0{rng.randrange(4)} X{i}.")
        else:
            lines.append(f"G01 X{i / 10:.1f} Z-{i % 13}.")
    lines += ["M30", "O2000 (SUB)"]
    lines += [f"G01 X{n}. Z-{n}." for n in range(40)]
    lines += ["M99", "%"]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("seed", range(3))
def test_cam_programs_resume_and_equal_full(seed: int) -> None:
    rng = random.Random(seed)
    config = Config()
    parser = BlockParser()
    lines = cam_with_calls(6_000, seed).splitlines()
    previous = evaluate_text("\n".join(lines), parser, config)
    assert previous.document(URI).feedless()
    resume_through_random_edits(lines, rng, parser, config, previous, 8)


@pytest.mark.parametrize("below", [40, 1, 0, -1])
def test_edits_that_add_or_remove_motions_near_the_records_kept(
    below: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A resumed run that meets the earlier one with more or fewer motions splices the earlier
    # records after its own; a full run keeps the first MAX_MOTIONS. Near that bound the two
    # must still agree: the resumed run does not meet the earlier one when either reaches it.
    rng = random.Random(below)
    config = Config()
    parser = BlockParser()
    lines = long_program(3_000, 7).splitlines()
    total = len(evaluate_text("\n".join(lines), BlockParser(), config).motions)
    for module in (machine, motion, canned_cycles):  # each part that records motions
        monkeypatch.setattr(module, "MAX_MOTIONS", total - below)
    previous = evaluate_text("\n".join(lines), parser, config)
    movers = [i for i, line in enumerate(lines) if line.startswith(("G00 X[", "G01"))]
    for _ in range(8):
        at = rng.choice(movers)
        j = lines[at].find("]")
        lines[at] = (
            lines[at][:j] + lines[at][j + 1 :] if j >= 0 else rng.choice(["", "G00 X[#100+1.]"])
        )
        text = "\n".join(lines)
        resumed = evaluate_text(text, parser, config, previous)
        full = evaluate_text(text, BlockParser(), config)
        assert_same(resumed, full)
        previous = resumed


def lathe_cycles_program(turns: int) -> str:
    """A loop of G71 roughing and G70 finishing of one profile."""
    return "\n".join(
        [
            "%",
            "O1000 (CYCLES)",
            "#1=0",
            f"WHILE[#1LT{turns}]DO1",
            "G00 X[60.+#1] Z2.",
            "G71 U2. R0.5",
            "G71 P10 Q20 U0.4 W0.1 F0.25",
            "N10 G00 X[20.+#1]",
            "G01 Z-10.",
            "X40.",
            "N20 Z-30.",
            "G70 P10 Q20",
            "#1=#1+1",
            "END1",
            "M30",
            "%",
        ]
    )


@pytest.mark.parametrize("turns", [3, 400])
def test_lathe_cycles_resume_and_equal_full(turns: int) -> None:
    # 400 turns: the profiles' blocks (8 a turn) pass the step budget before the blocks do.
    rng = random.Random(turns)
    config = Config(step_budget=3000)
    parser = BlockParser()
    lines = lathe_cycles_program(turns).splitlines()
    previous = evaluate_text("\n".join(lines), parser, config)
    assert previous.stopped == ("budget" if turns == 400 else None)
    resume_through_random_edits(lines, rng, parser, config, previous, 12)


def feed_modes_program(turns: int) -> str:
    """Cuts in G98 (per minute) and G99 (per revolution) by turns: the motions of G98 record
    their feed mode (a lathe's power-on mode is G99), which the cycle time reads."""
    return "\n".join(
        [
            "%",
            "O1000 (FEED MODES)",
            "G97 S800 M03",
            "#1=0",
            f"WHILE[#1LT{turns}]DO1",
            "G00 X[40.+#1] Z2.",
            "G98 G01 Z-20. F150.",
            "G99 G01 Z-40. F0.2",
            "G04 P[100*#1]",
            "#1=#1+1",
            "END1",
            "M30",
            "%",
        ]
    )


def test_feed_modes_resume_and_equal_full() -> None:
    rng = random.Random(33)
    config = Config(step_budget=3000)
    parser = BlockParser()
    lines = feed_modes_program(40).splitlines()
    previous = evaluate_text("\n".join(lines), parser, config)
    assert {m.feed_mode for m in previous.motions} == {None, 98.0}
    resume_through_random_edits(lines, rng, parser, config, previous, 12)


# A document with no program (empty, or bytes that are not a text) leaves no compiled lines in
# the record: the next version, its first keystroke, is analysed as from scratch.
NO_PROGRAM_EDITS = [("", "G"), ("", "1"), ("", "%"), ("", "X\n"), ("X", ""), ("G", "")]
NOT_TEXT = bytes(range(32)) * 4


@pytest.mark.parametrize(("before", "after"), NO_PROGRAM_EDITS, ids=repr)
def test_an_edit_from_or_to_a_document_without_program_equals_a_fresh_analysis(
    before: str, after: str
) -> None:
    fresh = analyse(after, URI, parser=BlockParser()).diagnostics
    assert "MB000" not in {d.code for d in fresh}
    parser = BlockParser()
    previous = analyse(before, URI, parser=parser).facts
    assert analyse(after, URI, parser=parser, previous_facts=previous).diagnostics == fresh
    assert_same(
        evaluate_text(after, parser, Config(), evaluate_text(before, parser, Config())),
        evaluate_text(after, BlockParser(), Config()),
    )
    ws = Workspace()
    ws.add_text(URI, before)
    ws.analyse(URI)
    ws.add_text(URI, after)
    assert ws.analyse(URI).diagnostics == fresh


@pytest.mark.parametrize("after", ["G", "G01 X1.\nM30\n"])
def test_a_document_not_text_then_typed_in_equals_a_fresh_analysis(after: str) -> None:
    ws = Workspace()
    ws.add_bytes(URI, NOT_TEXT)
    assert "MB007" in {d.code for d in ws.analyse(URI).diagnostics}
    ws.add_text(URI, after)
    assert ws.analyse(URI).diagnostics == analyse(after, URI, parser=BlockParser()).diagnostics
