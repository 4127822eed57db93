"""The evaluator keeps no state of its own between analyses: what compiled lines share is
interned in the current database's tables, and a run's stretches of facts are told apart by
tokens, not by a process-wide counter."""

from __future__ import annotations

import random

from fanuc_macro.config import Config
from fanuc_macro.database import Database
from fanuc_macro.evaluator import evaluate
from fanuc_macro.evaluator.facts import Stretch
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import BlockParser, parse_text

URI = "file:///state.nc"
EVALUATOR_TABLES = (
    "evaluator.codes_compiled",
    "evaluator.code_tuples",
    "evaluator.shared_expressions",
    "evaluator.constants",
    "evaluator.readers",
    "evaluator.compiled_by_statement",
)


def _program(seed: int) -> str:
    """Lines no other test parses, so that each is compiled here."""
    rng = random.Random(seed)
    x = rng.randint(10_000, 99_999)
    return (
        f"O1\n#1={x}.5+#2\nG01 X{x}.25 Z-{x}.5 F0.{x}\nG00 X[#1+{x}.125]\n"
        f"M08\n#{rng.randint(100, 199)}={x}\nM30\n"
    )


def _facts(text: str) -> None:
    doc = parse_text(text, URI, BlockParser())
    evaluate([(URI, doc, build_index(doc))], Config(), only_uri=URI)


def test_compiled_lines_share_what_they_intern_in_the_current_database() -> None:
    db = Database("evaluator test")
    with db.active():
        _facts(_program(1))
    tables = db.tables()
    assert all(tables.get(name, 0) > 0 for name in EVALUATOR_TABLES), tables
    db.forget()
    assert db.tables() == {}


def test_stretches_of_two_evaluations_are_never_taken_for_one_another() -> None:
    text = "O1\n" + "".join("#1=#1+1\nG01 X#1 F1.\n" for _ in range(400)) + "M30\n"
    doc = parse_text(text, URI, BlockParser())
    docs = [(URI, doc, build_index(doc))]
    first = evaluate(docs, Config(), only_uri=URI)
    second = evaluate(docs, Config(), only_uri=URI)
    assert first.record is not None and second.record is not None
    a = [s[URI].stretch for s in first.record.segments]
    b = [s[URI].stretch for s in second.record.segments]
    assert len(a) > 1 and all(isinstance(s, Stretch) for s in a + b)
    assert not any(x == y for x in a for y in b)
    assert len(set(map(id, a))) == len(a)


def test_a_lathes_g50_s_clamps_the_speed_and_leaves_the_surface_speed_in_force() -> None:
    """G50 S2000 after G96 S180 is the clamp on the spindle speed: the cuts after it run at
    180 m/min, clamped at 2000 rpm, not at a surface speed of 2000."""
    text = (
        "O1\nG00 X60. Z2.\nG96 S180 M03\nG50 S2000\nG01 X50. F0.2\nZ-20.\nG97 S800\nG01 X40.\nM30\n"
    )
    doc = parse_text(text, "t.nc")
    facts = evaluate([("t.nc", doc, build_index(doc))], config=Config(controller="0i-TF"))
    by_line = {m.line: m for m in facts.motions}
    for line in (4, 5):
        assert (by_line[line].surface_speed, by_line[line].speed_clamp) == (180.0, 2000.0)
        assert by_line[line].rpm is None
    assert by_line[7].rpm == 800.0 and by_line[7].surface_speed is None
