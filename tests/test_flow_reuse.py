"""The flow rules' verdicts kept from one analysis to the next (MB701, MB702, MB709): after
random edits, a document analysed as the language server analyses it (the evaluation resumed,
the verdicts of unchanged lines kept) gives the diagnostics of a fresh analysis, and a
one-line edit looks again at the few conditions and stretches it can change (counted, not
timed)."""

from __future__ import annotations

import dataclasses
import random

from fanuc_macro import database
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.rules import flow
from fanuc_macro.workspace import Workspace

URI = "file:///flow.nc"
CONFIG = dataclasses.replace(Config(), max_blocks=10**6, max_file_size=10**8, step_budget=60_000)


def _chunk(rng: random.Random, label: int) -> list[str]:
    """A loop with a GOTO out of it and one back before it (bench.py's macro-dense program),
    now and then a jump over dead blocks, a restart point after it and a comment."""
    v = rng.randint(1, 8)
    start = f"#{v}+" if rng.random() < 0.5 else ""  # a loop skipped or run a few times
    out = [
        f"N{label} #{v}={start}{rng.randint(0, 2)}",
        f"WHILE[#{v}LT{rng.randint(1, 12)}]DO1",
        f"#{100 + v}=#{v}*{rng.randint(0, 5)}",
        f"IF[#{100 + v}GT{rng.randint(3, 14)}]GOTO{label + 1}",
        f"#{v}=#{v}+1.",
        "END1",
        f"IF[#{v}LT0]GOTO{label}",
        f"N{label + 1} #{rng.randint(1, 8)}=#{v}",
    ]
    if rng.random() < 0.2:
        # A condition reached only after the jump back from the variable's first write: not
        # the program's own until a write before it (an edit at the top) makes it so.
        w = rng.randint(141, 144)
        out += [
            f"GOTO{10000 + label}",
            f"N{20000 + label} IF[#{w}GT0]GOTO{30000 + label}",
            f"N{10000 + label} #{w}={rng.randint(1, 3)}",
            f"GOTO{20000 + label}",
            f"N{30000 + label} #{w}=#{w}+1",
        ]
    if rng.random() < 0.25:
        out += [f"GOTO{label + 2}", "#20=1", "(SKIPPED)", "#21=2"]
        if rng.random() < 0.5:
            out += [f"N{5000 + label} #22=3", "#23=4"]
    return out


def _program(rng: random.Random, blocks: int) -> list[str]:
    lines = ["%", "O2000 (FLOW REUSE)", *(f"#{v}=0" for v in range(1, 9))]
    label = 1
    while len(lines) < blocks:
        lines += _chunk(rng, label)
        label += 2
    return [*lines, f"N{label} M30", "%"]


# Lines an edit puts in: the end of the program, an unconditional jump, a label, a loop's
# ends, an assignment, a comment, another program.
EXTRA = [
    "M30",
    "GOTO{label}",
    "N{label} #3=5",
    "IF[#2GT1]GOTO{label}",
    "WHILE[#1LT2]DO1",
    "END1",
    "#5=#5+1",
    "(NOTE)",
    "",
    "N{restart}",
    "O3000 (SECOND)",
    "M99",
]


def _edit(rng: random.Random, lines: list[str]) -> None:
    """One random edit: a number changed (a loop's bound, a value, a jump's target, a
    label), a line put in, replaced or removed, or the program's end moved."""
    at = rng.randrange(2, len(lines) - 1)
    kinds = ["number", "number", "number", "replace", "insert", "delete", "end", "top", "note"]
    kind = rng.choice([*kinds, "drop"])
    label = rng.randint(1, 250)
    extra = rng.choice(EXTRA).format(label=label, restart=6000 + label)
    if kind == "number":
        line = lines[at]
        digits = [i for i, c in enumerate(line) if c.isdigit()]
        if digits:
            i = rng.choice(digits)
            lines[at] = line[:i] + str(rng.randint(0, 9)) + line[i + 1 :]
    elif kind == "replace":
        lines[at] = extra
    elif kind == "insert":
        lines[at:at] = [extra] * rng.randint(1, 2)
    elif kind == "delete":
        del lines[at : at + rng.randint(1, 3)]
    elif kind == "top":  # a first write moved, before the conditions that read it
        lines.insert(rng.randint(2, 6), f"#{rng.randint(141, 144)}={rng.randint(1, 3)}")
    elif kind == "note":  # the lines after it move, and what the program does stays
        lines.insert(at, rng.choice(["(NOTE)", ""]))
    elif kind == "drop":  # an assignment or a comment removed, which moves no label or loop
        plain = [i for i in range(at, min(at + 40, len(lines) - 1)) if lines[i][:1] in "#("]
        if plain:
            del lines[plain[0]]
    else:  # the program's end: the last M30 removed or put back, or one put before it
        end = max(i for i, line in enumerate(lines) if "%" not in line)
        if "M30" in lines[end]:
            lines[end] = lines[end].replace("M30", "#9=1")
        elif rng.random() < 0.5:
            lines.insert(end + 1, "M30")
        else:
            lines.insert(at, "M30")


def work_done(kind: str, workspace: Workspace) -> int:
    """The flow rules' work of ``kind`` in the workspace's database and in the default one
    (a fresh analysis outside any workspace): together, all they did."""
    databases = {id(db): db for db in (getattr(workspace, "db", None), database.default()) if db}
    return sum(flow.work_done(kind, db) for db in databases.values())


def _diagnostics(text: str, uri: str) -> list[object]:
    return list(analyse(text, uri, CONFIG).diagnostics)


def test_verdicts_kept_after_random_edits_equal_a_fresh_analysis() -> None:
    rng = random.Random(11)
    workspace = Workspace(CONFIG)
    resumed = [0, 0]  # conditions looked at when the run was kept or resumed: kept, fresh
    for trial in range(3):
        lines = _program(rng, 2500)
        uri = f"file:///flow{trial}.nc"
        workspace.add_text(uri, "\n".join(lines))
        previous = workspace.analyse(uri).facts
        codes: set[str] = set()
        for edit in range(25):
            _edit(rng, lines)
            text = "\n".join(lines)
            workspace.add_text(uri, text)
            before = work_done("conditions", workspace)
            analysis = workspace.analyse(uri)
            kept = work_done("conditions", workspace) - before
            before = work_done("conditions", workspace)
            fresh = _diagnostics(text, f"file:///fresh{trial}-{edit}.nc")
            assert analysis.diagnostics == fresh, (trial, edit)
            codes.update(d.code for d in fresh)
            assert analysis.facts is not None and analysis.facts.record is not None
            facts = analysis.facts
            if facts is previous or facts.record.executed < facts.steps:
                resumed[0] += kept
                resumed[1] += work_done("conditions", workspace) - before
            previous = facts
        assert {"MB701", "MB702", "MB709"} <= codes
    # Where the evaluation kept its run or ran a part of it again, the flow rules looked at
    # fewer conditions than a fresh analysis does.
    assert resumed[0] < resumed[1] / 2


def test_a_one_number_edit_builds_few_verdicts_again() -> None:
    """A factor typed in one assignment of a long program of loops (bench.py's keystroke),
    then a line put in: the conditions and dead stretches looked at again are those of the
    stretches of the run the evaluation ran again (a few thousand blocks), not the program's;
    those after a line put in are moved, not looked at."""
    rng = random.Random(5)
    lines = _program(rng, 20_000)
    workspace = Workspace(CONFIG)
    workspace.add_text(URI, "\n".join(lines))
    first = workspace.analyse(URI).diagnostics
    conditions = sum(d.code == "MB701" for d in first)
    dead = sum(d.code in ("MB702", "MB709") for d in first)
    assert conditions > 2000 and dead > 2000
    at = next(i for i in range(len(lines) // 2, len(lines)) if "*" in lines[i])
    original = lines[at]
    for edited in (original.replace("*", "*1", 1), original, None):
        if edited is None:
            lines.insert(at, "(NOTE)")
        else:
            lines[at] = edited
        text = "\n".join(lines)
        workspace.add_text(URI, text)
        before = work_done("conditions", workspace), work_done("stretches", workspace)
        diagnostics = workspace.analyse(URI).diagnostics
        assert work_done("conditions", workspace) - before[0] < conditions / 3
        assert work_done("stretches", workspace) - before[1] < dead / 5
        assert diagnostics == _diagnostics(text, "file:///fresh.nc")


def _chunks(rng: random.Random, count: int, label: int) -> list[str]:
    """``count`` chunks from N``label`` on: the one after them is N``label + 2 * count``."""
    lines: list[str] = []
    for _ in range(count):
        lines += _chunk(rng, label)
        label += 2
    return lines


def test_a_first_write_put_before_a_condition_decides_it_far_from_the_edit() -> None:
    """A condition the run reaches last, by a jump back, reads #141, first set at the end of
    the text: not the program's own value. An equal assignment put in at the top makes it
    so; the evaluation meets its earlier run soon after, long before it reaches the
    condition, whose verdict changes though nothing around it does."""
    rng = random.Random(3)
    lines = [
        "%",
        "O2000 (FIRST WRITE)",
        *(f"#{v}=0" for v in range(1, 9)),
        "GOTO9000",
        "N9100 IF[#141GT0]GOTO9200",
        "N9200 M30",
        "N9000 #141=2",
        *_chunks(rng, 300, 1),
        "N601 #30=0",
        "WHILE[#30LT400]DO1",
        "#31=#30*2",
        "#30=#30+1",
        "END1",
        "GOTO9100",
        "%",
    ]
    condition = lines.index("N9100 IF[#141GT0]GOTO9200")
    workspace = Workspace(CONFIG)
    workspace.add_text(URI, "\n".join(lines))
    first = workspace.analyse(URI).diagnostics
    assert not any(d.code == "MB701" and d.line == condition for d in first)
    lines.insert(2, "#141=2")
    text = "\n".join(lines)
    workspace.add_text(URI, text)
    analysis = workspace.analyse(URI)
    assert analysis.facts is not None and analysis.facts.record is not None
    assert analysis.facts.record.converged_at is not None  # the run was not all made again
    assert any(d.code == "MB701" and d.line == condition + 1 for d in analysis.diagnostics)
    assert analysis.diagnostics == _diagnostics(text, "file:///fresh.nc")


def test_edits_inside_a_dead_stretch_give_its_new_extent() -> None:
    """A comment or a block removed from, or put into, blocks no run reaches: what the run
    does is the same, the stretch's lines and count are not."""
    rng = random.Random(4)
    dead = ["GOTO8000", "#20=1", "(SKIPPED)", "#21=2", "#22=3", "N8000 #23=4"]
    lines = ["%", "O2000 (DEAD)", *(f"#{v}=0" for v in range(1, 9))]
    lines += [*_chunks(rng, 150, 1), *dead, *_chunks(rng, 150, 301), "N601 M30", "%"]
    at = lines.index("GOTO8000") + 2
    workspace = Workspace(CONFIG)
    workspace.add_text(URI, "\n".join(lines))
    workspace.analyse(URI)
    edits = [
        lambda: lines.pop(at),  # the comment
        lambda: lines.pop(at),  # a dead block
        lambda: lines.insert(at, "#24=5"),
        lambda: lines.insert(at - 1, "(NOTE)"),
        lambda: lines.__setitem__(at + 1, "#22=33"),
        lambda: lines.pop(at - 2),  # the jump: the blocks run
    ]
    for edit in edits:
        edit()
        text = "\n".join(lines)
        workspace.add_text(URI, text)
        diagnostics = workspace.analyse(URI).diagnostics
        assert diagnostics == _diagnostics(text, "file:///fresh.nc")
        assert sum(d.code == "MB702" for d in diagnostics) > 10
