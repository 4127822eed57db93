"""The compiled form of a block of number words, built in one pass (``_compile_plain_nc``),
equals the one the general path builds for the same block."""

from __future__ import annotations

import pytest

from fanuc_macro.config import Config
from fanuc_macro.evaluator import compile_lines, evaluate
from fanuc_macro.evaluator.compile_lines import (
    CompiledLine,
    _compile_nc,
    _compile_plain_nc,
    _direct_reads,
    _ends_program,
)
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.syntax.tree import NcStatement, PlainNc
from test_parser import program_lines, random_nc_lines


def _general(nc: NcStatement, text: str) -> CompiledLine:
    compiled = _compile_nc(nc, text)
    compiled.reads = _direct_reads(nc)
    compiled.ends_program = _ends_program(nc)
    return compiled


EXTRA = [
    "G01 X1.23456 Y-0.0004 Z1.0005",
    "G1.5 X1",
    "G00.04 M3 S-100",
    "M2",
    "m30",
    "P1.5 L-2 F-1 T2.5",
    "H1 D2. F0.1 P10",
    "X1 X2 Y3.14159 Y2",
    "G4 P-1.",
    "Q0.4 R.5",
    "S20000 M3",
    "M98.5 P1",
    "T-1",
    # Words written together, E among them: a token of two words is not one number.
    "X1E2 Y3",
    "G01X1.5Y2.",
    "x1e2y3",
    "G01 X1. E2.",
    "E5 X1",
    "G01 X1.23456Y2",
]


def _compare(lines: list[str]) -> int:
    parser = BlockParser()
    seen = 0
    for text in [*lines, *EXTRA]:
        parsed = parser.parse_line(text)
        nc = parsed.statement
        if type(nc) is PlainNc:
            # Compiled from its code, without its nodes: as the nodes compile.
            built = nc.built()  # a line seen before has its nodes from that comparison
            plain = compile_lines.compile_statement(nc, text)
            assert nc.built() == built, text
            nodes = NcStatement(nc.words, nc.span)
            from_nodes = _compile_plain_nc(nodes)
            assert from_nodes is not None, text
            assert from_nodes == plain, text
            nc = nodes
        elif type(nc) is NcStatement:
            found = _compile_plain_nc(nc)
            if found is None:
                continue
            plain = found
        else:
            continue
        seen += 1
        general = _general(nc, text)
        assert general.constant is not None, text
        assert plain.constant is not None, text
        assert plain.constant.order == general.constant.order, text
        # The plain path reads the values from the Num nodes (``constants`` None), and works
        # out ``quiet``, which the general path leaves False.
        assert general.constant.constants == tuple(v for _, v, _ in plain.constant.order)
        general.constant.constants = None
        general.constant.quiet = plain.constant.quiet
        assert plain == general, text
        assert list(plain.constant.motion_words.items()) == list(
            general.constant.motion_words.items()
        ), text
    return seen


def test_plain_blocks_compile_as_the_general_path_compiles_them() -> None:
    assert _compare(program_lines()) > 1000


def test_random_plain_blocks_compile_as_the_general_path_compiles_them() -> None:
    assert _compare(random_nc_lines(4000, seed=4321)) > 400


def _findings(lines: list[str], quiet: bool, monkeypatch: pytest.MonkeyPatch) -> list[object]:
    compile_plain = compile_lines._compile_plain_nc

    def compile_loud(nc: NcStatement) -> CompiledLine | None:
        compiled = compile_plain(nc)
        if compiled is not None and compiled.constant is not None:
            compiled.constant.quiet = False
        return compiled

    if not quiet:
        monkeypatch.setattr(compile_lines, "_compile_plain_nc", compile_loud)
    # The calls go nowhere and M02/M30/M99 would end the run: each line is a program.
    text = "".join(
        f"O{n + 1}\n{line}\nM30\n" for n, line in enumerate(lines) if "M" not in line.upper()
    )
    text += "".join(f"O{n + 5000}\n{line}\n" for n, line in enumerate(lines) if "M" in line.upper())
    doc = parse_text(text, "file:///plain.nc", BlockParser())
    facts = evaluate([("file:///plain.nc", doc, build_index(doc))], Config(max_spindle_speed=8000))
    monkeypatch.undo()
    return sorted(
        (f.line, f.kind, f.column, f.message) for d in facts.by_uri.values() for f in d.findings
    )


def test_a_quiet_block_has_no_address_finding(monkeypatch: pytest.MonkeyPatch) -> None:
    lines = [*random_nc_lines(1500, seed=77), *EXTRA]
    found = _findings(lines, True, monkeypatch)
    assert found == _findings(lines, False, monkeypatch)
    assert any(kind.startswith("address-") for _, kind, _, _ in found)
