"""The answers sent to the editor as JSON have the shape their TypedDicts say: every required
key, no key the type lacks, each value of its declared type (ide/trace.py, ide/toolpath_view.py,
generators/generator_requests.py, lsp/commands.py)."""

from __future__ import annotations

import asyncio
import types
import typing
from pathlib import Path
from typing import Any, Literal, Union, get_args, get_origin, get_type_hints

import pytest

from fanuc_macro.config import Config
from fanuc_macro.generators.generator_requests import (
    ArcThreadAnswer,
    DrumGrooveAnswer,
    GeneratorRefusal,
    arc_thread_request,
    drum_groove_request,
)
from fanuc_macro.ide.toolpath_view import NoToolpathView, ToolpathViewData, toolpath_view
from fanuc_macro.ide.trace import Trace, trace
from fanuc_macro.lsp import commands
from fanuc_macro.workspace import Workspace

SEEDS = Path(__file__).resolve().parents[2] / "shared" / "seeds"
SEED_FILES = sorted(SEEDS.glob("*.txt")) if SEEDS.is_dir() else []

LATHE = """O1234
G21 G18 G40 G80 G99
T0101
G97 S500 M03
G00 X60. Z5.
#1 = 2.5
G01 X[50. - #1] Z0. F0.2
G02 X50. Z-10. R10.
G76 P020060 Q50 R0.05
G76 X46.75 Z-30. P1624 Q300 F3.
G00 X100. Z100.
M30
"""


def _is_typed_dict(kind: object) -> bool:
    return isinstance(kind, type) and typing.is_typeddict(kind)


def conforms(value: object, kind: Any, where: str = "answer") -> list[str]:
    """What in ``value`` does not fit ``kind`` (empty: it fits)."""
    if kind is Any or kind is object:
        return []
    if _is_typed_dict(kind):
        if not isinstance(value, dict):
            return [f"{where}: {type(value).__name__}, not {kind.__name__}"]
        hints = get_type_hints(kind)
        wrong = [f"{where}: no key {key!r}" for key in kind.__required_keys__ if key not in value]
        wrong += [
            f"{where}: key {key!r} not in {kind.__name__}" for key in value if key not in hints
        ]
        for key, item in value.items():
            if key in hints:
                wrong += conforms(item, hints[key], f"{where}.{key}")
        return wrong
    origin = get_origin(kind)
    if origin in (Union, types.UnionType):
        options = get_args(kind)
        if any(not conforms(value, option, where) for option in options):
            return []
        return [f"{where}: {value!r:.80} fits none of {kind}"]
    if origin is Literal:
        return [] if value in get_args(kind) else [f"{where}: {value!r} not in {kind}"]
    if origin is list:
        if not isinstance(value, list):
            return [f"{where}: {type(value).__name__}, not a list"]
        (item_kind,) = get_args(kind)
        return [
            w for i, item in enumerate(value) for w in conforms(item, item_kind, f"{where}[{i}]")
        ]
    if origin is dict:
        if not isinstance(value, dict):
            return [f"{where}: {type(value).__name__}, not a dict"]
        key_kind, item_kind = get_args(kind)
        return [
            w
            for key, item in value.items()
            for w in conforms(key, key_kind, f"{where} key")
            + conforms(item, item_kind, f"{where}[{key!r}]")
        ]
    if kind is type(None):
        return [] if value is None else [f"{where}: {value!r:.80} is not null"]
    if kind is float:  # JSON has numbers: an int is a float's value too (PEP 484)
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        return [] if ok else [f"{where}: {value!r:.80} is not a number"]
    if kind is int:
        ok = isinstance(value, int) and not isinstance(value, bool)
        return [] if ok else [f"{where}: {value!r:.80} is not an int"]
    return [] if isinstance(value, kind) else [f"{where}: {value!r:.80} is not a {kind.__name__}"]


def _documents(text: str, name: str = "t.nc") -> tuple[str, Any, Any]:
    workspace = Workspace()
    doc = workspace.add_text(name, text)
    return name, doc, workspace.index(name)


def test_the_checker_refuses_a_key_the_type_lacks_and_a_missing_one() -> None:
    assert conforms({"error": "x"}, GeneratorRefusal) == []
    assert conforms({"error": "x", "undecided": True}, GeneratorRefusal)
    assert conforms({}, GeneratorRefusal)
    assert conforms({"error": 3}, GeneratorRefusal)


def test_a_trace_fits_its_type() -> None:
    answer = trace(*_documents(LATHE), config=Config())
    assert answer["motions"], "the program makes motions"
    assert any("moves" in m for m in answer["motions"]), "a cycle's moves are checked too"
    assert any("values" in m for m in answer["motions"])
    assert conforms(answer, Trace) == []


@pytest.mark.parametrize("path", SEED_FILES, ids=[p.name for p in SEED_FILES])
def test_a_seed_paper_s_trace_and_view_fit_their_types(path: Path) -> None:
    uri, doc, index = _documents(path.read_text("utf-8"), path.as_uri())
    assert conforms(trace(uri, doc, index, config=Config()), Trace) == []
    view = toolpath_view(uri, doc, index, config=Config())  # a paper's text may make no move
    assert conforms(view, ToolpathViewData | NoToolpathView) == []


def test_the_toolpath_view_fits_its_type_or_says_why_not() -> None:
    assert conforms(toolpath_view(*_documents(LATHE), config=Config()), ToolpathViewData) == []
    nothing = toolpath_view(*_documents("O1\n#1 = 2\nM30\n"), config=Config())
    assert "error" in nothing
    assert conforms(nothing, NoToolpathView) == []


def test_the_generators_answers_fit_their_types() -> None:
    assert conforms(arc_thread_request({}), ArcThreadAnswer) == []
    assert conforms(drum_groove_request({"pitch": 40}), DrumGrooveAnswer) == []
    assert conforms(arc_thread_request({"nope": 1}), GeneratorRefusal) == []
    assert conforms(drum_groove_request({}), GeneratorRefusal) == []


def _run(command: Any, *args: Any) -> Any:
    return asyncio.run(command(None, args))


def test_the_editor_commands_answers_fit_their_types() -> None:
    answers = [
        _run(commands.run_read_designation, "M50x3-6g"),
        _run(commands.run_read_designation, "M50X3"),  # undecided: the question and readings
        _run(commands.run_read_designation, "Q1"),
        _run(
            commands.run_check_parameters,
            {"generator": "arcThread", "answers": [{"names": ["length"], "value": "5"}]},
        ),
        _run(commands.run_parameter_defaults, "drumGroove"),
        _run(commands.run_controllers),
        _run(commands.run_variable_at, "#100 = 1", 1),
        _run(commands.run_variable_at, "G00 X1.", 0),
        _run(commands.run_variable_at, "no column"),
    ]
    assert "question" in answers[1]
    for answer in answers:
        assert conforms(answer, commands.EditorAnswer) == [], answer
