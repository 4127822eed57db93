"""The threading rules after an edit: the work done again is that of what changed (counted,
not timed), and the findings are those of an analysis from scratch."""

from __future__ import annotations

import importlib.util
import random
import sys
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from types import ModuleType

import pytest

from fanuc_macro.analysis import Analysis, analyse
from fanuc_macro.config import Config
from fanuc_macro.evaluator import Motion
from fanuc_macro.line_maps import Kept
from fanuc_macro.program import meanings
from fanuc_macro.syntax.parser import BlockParser
from fanuc_macro.threads import identify, jobs

FIXTURES = Path(__file__).parent / "fixtures"
URI = "file:///reuse.nc"


def _bench_programs() -> ModuleType:
    path = Path(__file__).resolve().parents[1] / "bench" / "bench_lsp.py"
    spec = importlib.util.spec_from_file_location("bench_lsp_reuse", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


# A main program in the style of the seeds: one G92 thread of a pass every four blocks.
program: Callable[[int], str] = _bench_programs().program
CONFIG = replace(Config(), max_blocks=10**7, max_file_size=10**9)


def _edit_number(lines: list[str], at: int) -> list[str]:
    """A digit typed into the assignment at or after line ``at``: no thread pass changes."""
    out = list(lines)
    while not out[at].startswith("#"):
        at += 1
    out[at] = out[at].replace("*", "*1", 1)
    return out


def _fresh(text: str) -> Analysis:
    """An analysis from scratch, without the jobs kept of the document (restored after)."""
    kept = jobs._kept
    jobs._kept = Kept()
    try:
        return analyse(text, URI, CONFIG, parser=BlockParser())
    finally:
        jobs._kept = kept


def _same_as_fresh(text: str, previous: object) -> object:
    resumed = analyse(text, URI, CONFIG, parser=PARSER, previous_facts=previous)  # type: ignore[arg-type]
    fresh = _fresh(text)
    assert resumed.diagnostics == fresh.diagnostics
    assert [identify.describe(t) for t in resumed.threads] == [
        identify.describe(t) for t in fresh.threads
    ]
    assert [t.job.passes for t in resumed.threads] == [t.job.passes for t in fresh.threads]
    return resumed.facts


PARSER = BlockParser()


def test_an_edit_that_cuts_the_same_passes_keeps_the_jobs_and_looks_at_one_line() -> None:
    lines = program(4000).split("\n")
    first = analyse("\n".join(lines), URI, CONFIG, parser=PARSER)
    assert first.threads and len(first.threads[0].job.passes) > 900
    before = first.threads[0].job
    lines = _edit_number(lines, len(lines) // 2)
    grouped, looked, roles = (
        jobs.work_done("grouped"),
        identify._thread_lines.looked,
        meanings._role_lines.looked,
    )
    again = analyse("\n".join(lines), URI, CONFIG, parser=PARSER, previous_facts=first.facts)
    # The run resumed and made new records of the passes after the edit, of the same values:
    # the job is the earlier one, not grouped again, and only the edited line is read again.
    assert again.facts is not None and again.facts.motions is not first.facts.motions
    assert again.threads[0].job is before
    assert jobs.work_done("grouped") == grouped
    assert identify._thread_lines.looked - looked <= 1
    assert meanings._role_lines.looked - roles <= 1
    fresh = _fresh("\n".join(lines))
    assert again.diagnostics == fresh.diagnostics


def test_an_edit_of_a_pass_groups_again_and_equals_a_fresh_analysis() -> None:
    lines = program(2000).split("\n")
    previous = analyse("\n".join(lines), URI, CONFIG, parser=PARSER).facts
    at = next(i for i in range(len(lines) // 2, len(lines)) if lines[i].startswith("G92"))
    lines[at] = lines[at].replace("#100-0.", "#100+0.", 1)  # a pass shallower than the one before
    grouped = jobs.work_done("grouped")
    previous = _same_as_fresh("\n".join(lines), previous)
    assert jobs.work_done("grouped") > grouped


def test_an_edit_of_a_pass_over_the_same_z_replaces_that_pass_only() -> None:
    # The pass's X changes, its stretch of Z does not: it joins the same job and the passes
    # after it group as before, so only it is taken again, not all the 500 passes.
    lines = program(2000).split("\n")
    first = analyse("\n".join(lines), URI, CONFIG, parser=PARSER)
    at = next(i for i in range(len(lines) // 2, len(lines)) if lines[i].startswith("G00 X["))
    lines[at] = lines[at].replace("X[#100+", "X[#100+1", 1)  # where the next G92 starts
    grouped = jobs.work_done("grouped")
    again = analyse("\n".join(lines), URI, CONFIG, parser=PARSER, previous_facts=first.facts)
    assert 1 <= jobs.work_done("grouped") - grouped <= 2
    assert len(first.threads[0].job.passes) > 400
    assert again.threads[0].job is not first.threads[0].job
    fresh = _fresh("\n".join(lines))
    assert again.diagnostics == fresh.diagnostics
    assert again.threads[0].job.passes == fresh.threads[0].job.passes


def test_an_edit_of_a_pass_over_another_z_groups_all_again() -> None:
    lines = program(2000).split("\n")
    previous = analyse("\n".join(lines), URI, CONFIG, parser=PARSER).facts
    at = next(i for i in range(len(lines) // 2, len(lines)) if lines[i].startswith("G92"))
    lines[at] = lines[at].replace("W-[", "W-2*[", 1)  # a pass twice as long
    grouped = jobs.work_done("grouped")
    analyse("\n".join(lines), URI, CONFIG, parser=PARSER, previous_facts=previous)
    assert jobs.work_done("grouped") - grouped > 400
    _same_as_fresh("\n".join(lines), previous)


@pytest.mark.parametrize("seed", range(3))
def test_random_edits_of_a_seed_equal_a_fresh_analysis(seed: int) -> None:
    rng = random.Random(seed)
    names = sorted(p.name for p in (FIXTURES / "seeds").glob("*.nc"))
    lines = (FIXTURES / "seeds" / rng.choice(names)).read_text("utf-8").splitlines()
    previous = analyse("\n".join(lines), URI, CONFIG, parser=PARSER).facts
    for _ in range(12):
        lines = list(lines)
        at = rng.randrange(len(lines))
        what = rng.random()
        if what < 0.4:  # a digit changed
            digits = [i for i, ch in enumerate(lines[at]) if ch.isdigit()]
            if digits:
                i = rng.choice(digits)
                lines[at] = lines[at][:i] + str(rng.randrange(10)) + lines[at][i + 1 :]
        elif what < 0.6:
            lines.insert(at, "G04 X0.1 (PAUSE)")
        elif what < 0.8 and len(lines) > 5:
            del lines[at]
        else:
            lines[at] = lines[at] + " (M20X1.5-6G)"
        previous = _same_as_fresh("\n".join(lines), previous)


def test_added_and_removed_lines_move_what_was_found() -> None:
    lines = program(1200).split("\n")
    previous = analyse("\n".join(lines), URI, CONFIG, parser=PARSER).facts
    lines.insert(300, "(M50X3-6G EXTERNAL)")
    previous = _same_as_fresh("\n".join(lines), previous)
    del lines[10]
    previous = _same_as_fresh("\n".join(lines), previous)
    lines.insert(len(lines) - 20, "#3=0.4 (NOSE RADIUS)")
    _same_as_fresh("\n".join(lines), previous)


def test_a_zero_of_the_other_sign_is_not_the_same_motion() -> None:
    a = Motion("O1", 3, "G92", {"X": 0.0}, URI, x=0.0)
    b = replace(a, words={"X": -0.0}, x=-0.0)
    assert a == b  # as Python compares them
    assert not jobs.same_motion(a, b)
    assert jobs.same_motion(a, replace(a, words={"X": 0.0}))


@pytest.mark.parametrize("seed", range(4))
def test_random_edits_of_passes_equal_a_fresh_analysis(seed: int) -> None:
    # Edits of the passes' words (X, start point, F, spindle speed, start angle), chained:
    # most keep the grouping, so each job is a copy of the last with a pass replaced, and
    # what the rules worked out of the last is taken where the pass agrees on what it read.
    rng = random.Random(seed)
    lines = program(600).split("\n")
    previous = analyse("\n".join(lines), URI, CONFIG, parser=PARSER).facts
    passes = [i for i, line in enumerate(lines) if line.startswith(("G00 X[", "G92"))]
    for _ in range(10):
        at = rng.choice(passes)
        line = lines[at]
        pick = rng.randrange(5)
        if pick == 0:
            line = line.replace("X[#100", f"X[{rng.choice(['#100+', '#100-', ''])}#100", 1)
        elif pick == 1 and "F" in line:
            line = line.replace("F#101", f"F{rng.choice(['2.', '3.', '3.5'])}", 1)
        elif pick == 2:
            line = line + f" Q{rng.choice([0, 90000, 180000])}" if "G92" in line else line
        elif pick == 3:
            line = f"G97 S{rng.choice([400, 1500, 4000])} M03"
        else:
            line = line.replace("0.", "0.0", 1)
        lines[at] = line
        previous = _same_as_fresh("\n".join(lines), previous)


def test_a_copy_of_a_job_takes_what_was_found_where_its_new_pass_agrees() -> None:
    old_pass = Motion("O1", 3, "G92", {"X": 20.0, "F": 2.0}, URI, x=20.0, start_x=24.0)
    other = Motion("O1", 4, "G92", {"X": 19.0, "F": 2.0}, URI, x=19.0, start_x=24.0)
    job = jobs.ThreadJob(URI, 0, "O1", 0, [old_pass, other])
    assert job.remember("first", lambda: job.passes[0], ("x",)) is old_pass
    new_pass = replace(old_pass, start_x=30.0)  # another start point, the same X
    copy = jobs.ThreadJob(URI, 0, "O1", 0, [new_pass, other], basis=(job, (0,)))
    # Decided by X alone: the earlier result, with the new pass in place of the old one.
    assert copy.remember("first", lambda: pytest.fail("worked out again"), ("x",)) is new_pass
    # Decided by the start point, which differs: worked out again.
    job.remember("start", lambda: old_pass.start_x, ("start_x",))
    assert copy.remember("start", lambda: new_pass.start_x, ("start_x",)) == 30.0
    # What names no fields is worked out again.
    job.remember("unnamed", lambda: 1)
    assert copy.remember("unnamed", lambda: 2) == 2


def test_a_pass_from_another_start_within_its_job_replaces_that_pass_only() -> None:
    # The G00 before a G92 made unreadable (a bracket being typed): the pass starts from
    # where the tool was, another stretch of Z, but within the stretch of the job's passes
    # before it; it joins the same job, and the passes after it group as before.
    lines = program(2000).split("\n")
    first = analyse("\n".join(lines), URI, CONFIG, parser=PARSER)
    at = next(i for i in range(len(lines) // 2, len(lines)) if lines[i].startswith("G00 X["))
    lines[at] = lines[at].replace("]", "", 1)
    grouped = jobs.work_done("grouped")
    again = analyse("\n".join(lines), URI, CONFIG, parser=PARSER, previous_facts=first.facts)
    assert 1 <= jobs.work_done("grouped") - grouped <= 2
    fresh = _fresh("\n".join(lines))
    assert again.diagnostics == fresh.diagnostics
    assert again.threads[0].job.passes == fresh.threads[0].job.passes


def test_a_chain_of_one_pass_jobs_is_matched_again_job_by_job() -> None:
    # A chained G32, as the drum groove's taper segments: each segment is a job of one pass,
    # all of one program and run. An edit that adds a cut groups again; each new job is then
    # compared with the old jobs of its first pass only, not with all of them.
    segments = 300
    lines = [
        "%",
        "O0001",
        "G00 X40. Z2.",
        "#1=0",
        f"WHILE[#1LT{segments}]DO1",
        "G32 X[40.-#1*0.001] Z[-2.-#1*2.] F2.",
        "#1=#1+1",
        "END1",
        "G00 X60.",
        "M30",
        "%",
    ]
    first = analyse("\n".join(lines), URI, CONFIG, parser=PARSER)
    assert len(first.threads) == segments
    old_jobs = {id(t.job) for t in first.threads}
    lines.insert(lines.index("G00 X60."), "G32 Z-700. F2.")
    compared = jobs.work_done("compared")
    _same_as_fresh("\n".join(lines), first.facts)
    assert jobs.work_done("compared") - compared <= segments + 1
    resumed = analyse("\n".join(lines), URI, CONFIG, parser=PARSER, previous_facts=first.facts)
    assert sum(id(t.job) in old_jobs for t in resumed.threads) >= segments - 1
