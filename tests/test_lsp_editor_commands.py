"""The commands that answer what the editor's boxes and views would otherwise compute, over
stdio: a thread designation read, a generator's answers checked, their defaults, the trace
view's text and the controllers; each refusal the command line's message."""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import pytest
from lsprotocol import types
from pytest_lsp import LanguageClient

from cli_runner import run as run_cli
from fanuc_macro.ide.trace_view import view_of_trace
from test_lsp import CAPABILITIES, WAIT, client, open_seed, start

__all__ = ["client"]  # the fixture, shared with test_lsp.py

DESIGNATION = "fanuc-macro.readDesignation"
CHECK = "fanuc-macro.checkParameters"
DEFAULTS = "fanuc-macro.parameterDefaults"
TRACE_VIEW = "fanuc-macro.traceView"
CONTROLLERS = "fanuc-macro.controllers"

ARC_BOXES = [
    ["outer_diameter", "groove_radius", "tool_radius"],
    ["pitch", "length"],
    ["layers"],
    ["cuts_per_layer"],
    ["finishing_diameter", "finishing_cuts"],
]


async def run(client: LanguageClient, command: str, *arguments: Any) -> dict[str, Any]:
    result = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command=command, arguments=list(arguments))
        ),
        WAIT,
    )
    assert isinstance(result, dict)
    return result


def cli_refusal(tmp_path: Path, *args: str) -> str:
    """The one line the command line refuses ``args`` with, without its ``fanuc-macro x:``."""
    done = run_cli(tmp_path, *args)
    assert done.returncode == 2, done.stderr
    return done.stderr.strip().split(": ", 1)[1]


def answers(boxes: list[list[str]], values: list[Any]) -> list[dict[str, Any]]:
    return [{"names": names, "value": value} for names, value in zip(boxes, values, strict=False)]


async def test_the_editor_commands_are_advertised(client: LanguageClient) -> None:
    result = await asyncio.wait_for(
        client.initialize_session(types.InitializeParams(capabilities=CAPABILITIES)), WAIT
    )
    provider = result.capabilities.execute_command_provider
    assert provider is not None
    assert {DESIGNATION, CHECK, DEFAULTS, TRACE_VIEW, CONTROLLERS, "fanuc-macro.variableAt"} <= set(
        provider.commands
    )


async def test_a_designation_is_read_with_its_kind_pitch_and_diameters(
    client: LanguageClient,
) -> None:
    await start(client, None)
    bolt = await run(client, DESIGNATION, " M50x3-5g6g ")
    assert bolt == {
        "text": "M50x3-5g6g",
        "canonical": "M50x3-5g6g",
        "side": "external",
        "nominalDiameter": 50.0,
        "pitch": 3.0,
        "lead": 3.0,
        "starts": 1,
        "leftHand": False,
        "tolerance": "5g6g",
        "pitchDiameter": 48.051,
        "minorDiameter": 46.752,
    }
    nut = await run(client, DESIGNATION, "M20x1.5LH-6H")
    assert nut["side"] == "internal" and nut["leftHand"] is True and "question" not in nut
    two = await run(client, DESIGNATION, "M24xPh4P2-6g-LH")
    assert (two["starts"], two["lead"], two["pitch"], two["leftHand"]) == (2, 4.0, 2.0, True)
    # The case is lost and both kinds have the class: asked, never guessed.
    capitals = await run(client, DESIGNATION, "M50X3-5G6G")
    assert capitals["side"] == "undecided" and capitals["tolerance"] == "5G6G"
    assert capitals["readings"] == {"external": "M50x3-5g6g", "internal": "M50x3-5G6G"}
    assert capitals["question"] == (
        "M50X3-5G6G: the class 5G6G fits an external (5g6g) or an internal (5G6G) thread: "
        "which is it?"
    )
    # A class only one kind has says that kind; no class at all is asked.
    assert (await run(client, DESIGNATION, "M50X3-4H5H"))["side"] == "internal"
    plain = await run(client, DESIGNATION, "M10")
    assert plain["side"] == "undecided" and plain["tolerance"] is None
    assert plain["readings"] == {"external": "M10-6g", "internal": "M10-6H"}


@pytest.mark.parametrize(
    "designation", ["Tr40x7", "M50x3-5g6H", "M50x3-3H", "M10x", "M50x3--6g", "M50-6g", "M5x6"]
)
async def test_a_designation_is_refused_as_the_command_line_refuses_it(
    client: LanguageClient, tmp_path: Path, designation: str
) -> None:
    await start(client, None)
    refused = await run(client, DESIGNATION, designation)
    expected = cli_refusal(tmp_path, "thread", designation, "--length", "30")
    assert refused == {"error": expected}


async def test_the_forms_open_on_the_generators_defaults(client: LanguageClient) -> None:
    await start(client, None)
    arc = (await run(client, DEFAULTS, "arcThread"))["defaults"]
    boxes = [", ".join(arc[name] for name in names) for names in ARC_BOXES]
    assert boxes == ["93.82, 10, 1.2", "25, 113", "108, 103", "7", "100, 19"]
    drum = (await run(client, DEFAULTS, "drumGroove"))["defaults"]
    assert "pitch" not in drum  # the paper's is lost: no default
    assert drum["points"].startswith("298.91,205; 302.104,173; ") and drum["points"].endswith(
        "303.246,-160"
    )
    assert (drum["layers"], drum["radial_step"], drum["axial_step"]) == ("9", "0.8", "0.5")
    # The thread module's length box opens on one nominal diameter, its taper box empty.
    module = (await run(client, DEFAULTS, "threadModule", "M24x3-6g"))["defaults"]
    assert module == {"length": "24", "infeed": "symmetric", "taper": ""}
    assert "length" not in (await run(client, DEFAULTS, "threadModule"))["defaults"]
    # Enter in each box: the defaults as they are make a module.
    boxes = [["designation"], ["length"], ["internal"], ["infeed"], ["taper"]]
    values = ["M24x3-6g", module["length"], False, module["infeed"], module["taper"]]
    checked = await run(
        client,
        CHECK,
        {"generator": "threadModule", "answers": answers(boxes, values), "complete": True},
    )
    assert checked == {
        "parameters": {
            "designation": "M24x3-6g",
            "length": 24.0,
            "internal": False,
            "infeed": "symmetric",
            "taper": 0.0,
        }
    }
    assert await run(client, DEFAULTS, "gear") == {
        "error": "no generator gear; the generators are threadModule, arcThread, drumGroove"
    }


async def test_the_module_takes_the_numbers_its_document_does_not_have(
    client: LanguageClient,
) -> None:
    await start(client)
    uri = open_seed(client, "o4009_external_m50x3.nc")  # O4009 and O3331
    spec = {"designation": "M50x3-5g6g", "length": 50, "internal": False}
    paper = await run(client, "fanuc-macro.threadModule", spec)
    assert "note" not in paper and "M98 P0013331 " in paper["text"]
    into = await run(client, "fanuc-macro.threadModule", {**spec, "uri": uri})
    text = into["text"]
    assert "\nO4010 (" in text and "M98 P0013332 " in text and "\nO3332 (" in text
    assert "O4009" not in text and "O3331" not in text
    assert into["note"] == (
        "O4009 and O3331 are in the file already: the main program is O4010 and the "
        "sub-program is O3332."
    )
    other = "untitled:other.nc"
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=other, language_id="fanuc-macro", version=1, text="O1000\nM30\n"
            )
        )
    )
    assert "note" not in await run(client, "fanuc-macro.threadModule", {**spec, "uri": other})


async def test_the_answers_are_read_and_checked_by_the_generator(client: LanguageClient) -> None:
    await start(client, None)
    first = await run(
        client, CHECK, {"generator": "arcThread", "answers": answers(ARC_BOXES, ["93.82 10 1.2"])}
    )
    assert first == {
        "parameters": {"outer_diameter": 93.82, "groove_radius": 10.0, "tool_radius": 1.2}
    }
    # What cannot be read is refused; what the generator refuses, the later boxes still at
    # their defaults, is a warning until the form is complete.
    unread = await run(
        client, CHECK, {"generator": "arcThread", "answers": answers(ARC_BOXES, ["93.82, x, 1"])}
    )
    assert unread == {"error": 'groove_radius: "x" is not a number'}
    count = await run(
        client, CHECK, {"generator": "arcThread", "answers": answers(ARC_BOXES, ["93.82, 10"])}
    )
    assert count == {
        "error": "give 3 numbers apart by commas: outer_diameter, groove_radius, tool_radius"
    }
    big_r = await run(
        client, CHECK, {"generator": "arcThread", "answers": answers(ARC_BOXES, ["93.82, 10, 12"])}
    )
    warning = "tool nose radius r = 12 must be smaller than the groove radius R = 10"
    assert big_r["warning"] == warning and "error" not in big_r
    complete = {"generator": "arcThread", "complete": True}
    refused = await run(
        client, CHECK, {**complete, "answers": answers(ARC_BOXES, ["93.82, 10, 12"])}
    )
    assert refused == {"error": warning}
    paper = ["93.82, 10, 1.2", "25, 113", "108, 103", "7", "100, 19"]
    checked = await run(client, CHECK, {**complete, "answers": answers(ARC_BOXES, paper)})
    assert set(checked) == {"parameters"}
    ran = await run(client, "fanuc-macro.arcThread", checked["parameters"])
    assert ran["text"] == (await run(client, "fanuc-macro.arcThread", {}))["text"]


async def test_the_drum_and_the_thread_module_refuse_as_the_command_line(
    client: LanguageClient, tmp_path: Path
) -> None:
    await start(client, None)
    drum = [["points"], ["pitch"], ["layers", "radial_step"], ["cuts_per_layer", "axial_step"]]
    no_pitch = await run(
        client,
        CHECK,
        {"generator": "drumGroove", "complete": True, "answers": answers(drum, ["", "", "9, 0.8"])},
    )
    assert no_pitch["error"].startswith("pitch is missing")
    deep = await run(
        client,
        CHECK,
        {"generator": "drumGroove", "answers": answers(drum, ["", "40", "9, 200"])},
    )
    expected = cli_refusal(tmp_path, "drum-groove", "--pitch", "40", "--radial-step", "200")
    assert deep["warning"] == expected
    module = [["designation"], ["length"], ["internal"], ["infeed"], ["taper"]]
    spec = {"generator": "threadModule", "complete": True}
    ratio = await run(
        client,
        CHECK,
        {**spec, "answers": answers(module, ["M50x3-5g6g", "30", False, "left", "x"])},
    )
    assert ratio["error"] == (
        "the taper is a ratio or a number (e.g. 1:16, or 0.0625 mm of diameter per mm of "
        "length), not x"
    )
    steep = await run(
        client, CHECK, {**spec, "answers": answers(module, ["M50x3-5g6g", "30", False, "", "1:1"])}
    )
    assert steep["error"] == cli_refusal(
        tmp_path, "thread", "M50x3-5g6g", "--length", "30", "--taper", "1:1"
    )
    side = await run(
        client, CHECK, {**spec, "answers": answers(module, ["M50x3-5g6g", "30", True])}
    )
    assert side["error"] == cli_refusal(
        tmp_path, "thread", "M50x3-5g6g", "--length", "30", "--internal"
    ).replace("--internal was given", "an internal thread was asked for")
    # An undecided designation's side is its own box: no warning before it is picked.
    asked = await run(
        client,
        CHECK,
        {"generator": "threadModule", "answers": answers(module, ["M50X3-5G6G", "30"])},
    )
    assert asked == {"parameters": {"designation": "M50X3-5G6G", "length": 30.0}}
    fine = await run(
        client,
        CHECK,
        {**spec, "answers": answers(module, ["M50X3-5G6G", "30", True, "left", "1:16"])},
    )
    assert fine["parameters"] == {
        "designation": "M50X3-5G6G",
        "length": 30.0,
        "internal": True,
        "infeed": "left",
        "taper": 0.0625,
    }
    assert "warning" not in fine


async def test_the_trace_view_is_written_by_the_server(client: LanguageClient) -> None:
    await start(client)
    uri = open_seed(client, "o2_arc_thread_roughing.nc")
    view = await run(client, TRACE_VIEW, uri, "/seeds/o2_arc_thread_roughing.nc")
    lines = view["text"].split("\n")
    # The file's name as the title, its folder under it; no example of a link in the header:
    # only a row's block is one.
    assert lines[:2] == ["Trace of o2_arc_thread_roughing.nc", "in /seeds"]
    assert "line" not in "".join(lines[2:4]) and lines[4] == ""
    assert lines[5].split() == ["block", "code", "words", "to", "S", "F", "time"]
    at = next(i for i, line in enumerate(lines) if line.startswith("O0003 line 34 "))
    # The values the block read under its row; the columns fit beside a program (the cycle
    # time's column, "0:27.9", takes 8 of its 68 characters).
    assert lines[at + 1] == "    #5=108. #4=10. #18=1.2 #16=51.249025"
    assert max(len(line) for line in lines) <= 68
    row = next(r for r in view["rows"] if r["line"] == at)
    assert row == {
        "line": at,
        "sourceLine": 33,
        "link": {"start": 0, "end": 13},
        "label": row["label"],
    }
    assert row["label"] == "O0003 line 34"
    missing = await run(client, TRACE_VIEW, "file:///nowhere/none.nc")
    assert "neither open nor a readable program file" in missing["error"]


async def test_the_controllers_come_from_the_configuration(client: LanguageClient) -> None:
    await start(client, None)
    answer = await run(client, CONTROLLERS)
    assert answer["default"] == "0i-F"
    kinds = {c["id"]: c["kind"] for c in answer["controllers"]}
    assert list(kinds) == ["0i-F", "0i-TF", "0i-MF", "16i-T", "16i-M", "18i-T", "18i-M", "30i"]
    assert (
        kinds["0i-TF"] == "lathe" and kinds["18i-M"] == "mill" and kinds["30i"] == "lathe and mill"
    )
    assert kinds["0i-F"] == "lathe or mill"  # each document as its codes show
    assert answer["controllers"][-1]["series"] == "FANUC Series 30i/31i/32i"


def test_the_trace_view_writes_values_at_the_controls_precision() -> None:
    trace = {
        "motions": [
            {
                "program": 3331,
                "line": 12,
                "code": "G1",
                "words": {"G": 1.0, "X": 49.8164, "Z": -60.0, "F": 3.0},
                "start": {"X": 51.0, "Z": 5.9644},
                "end": {"X": 49.816, "Z": -60.0},
                "values": {"#101": None, "#102": 1 / 3, "#103": "depends on #500"},
            },
            {
                "program": "<THREAD>",
                "line": 20,
                "code": "G71",
                "words": {},
                "start": {},
                "end": {"X": 40.0},
                "cycle": "G71",
                "moves": [
                    {
                        "kind": "arc",
                        "start": {"X": 40.0},
                        "end": {"X": 42.0},
                        "centre": {"X": 41.0},
                        "clockwise": True,
                    }
                ],
                "path": "file:///p/O2.nc",
            },
        ],
        "toolpath": {
            "units": "mm",
            "lost": [{"program": 3331, "line": 14, "axes": ["X"], "reason": "after G28"}],
        },
        "summary": {"blocks_executed": 1, "by_code": {}, "findings": [{"line": 3, "kind": "k"}]},
    }
    view = view_of_trace(trace, "O1.nc")
    lines = view.text.split("\n")
    assert lines[1] == "2 motion blocks, 1 block executed, positions in mm"
    assert lines[5].split("  ")[0] == "O3331 line 12"
    # The F in force is a column of its own, the S one too (not known here), and the cycle
    # time when the block begins (none in this trace).
    assert lines[5].split() == [
        *("O3331", "line", "12", "G1", "G1", "X49.816", "Z-60."),
        *("X49.816", "Z-60.", "-", "3.", "-"),
    ]
    assert lines[6] == "    #101=<vacant> #102=0.33333333 #103=(depends on #500)"
    assert lines[7].split()[-4:] == ["X40.", "-", "-", "-"]
    assert lines[8:10] == ["    1 move (G71):", "      arc    X40. -> X42.  centre X41. CW"]
    assert [(r.line, r.source_line, r.path, r.link) for r in view.rows] == [
        (5, 11, None, (0, 13)),
        (6, 11, None, None),
        (7, 19, "file:///p/O2.nc", (0, 16)),
        (8, 19, "file:///p/O2.nc", None),
        (9, 19, "file:///p/O2.nc", None),
        (12, 13, None, (2, 15)),
    ]
    assert lines[12] == "  O3331 line 14: X after G28"
    assert lines[14:] == [
        "Summary",
        "  blocks_executed: 1",
        "  by_code: (none)",
        "  findings:",
        "    - line: 3",
        "      kind: k",
        "",
    ]


async def test_the_variable_under_the_hover_keeps_its_hash(client: LanguageClient) -> None:
    await start(client, None)
    line = "#1=#[#2+1]*#101 (RADIUS #5)"

    async def under(column: int) -> str | None:
        found = await run(client, "fanuc-macro.variableAt", line, column)
        return None if not found else line[found["start"] : found["end"]]

    assert [await under(c) for c in (0, 5, 7, 12, 2, 24)] == [
        "#1",
        "#2",
        "#[#2+1]",
        "#101",
        None,  # the =
        None,  # in the comment
    ]
    assert await run(client, "fanuc-macro.variableAt", "#_UI[2]=1", 1) == {"start": 0, "end": 7}
    refused = await run(client, "fanuc-macro.variableAt", line)
    assert refused == {"error": "fanuc-macro.variableAt takes a line's text and a column"}


def test_the_trace_gives_the_spindle_speed_and_feed_in_force() -> None:
    from fanuc_macro.ide.trace import trace
    from fanuc_macro.program.index import build_index
    from fanuc_macro.syntax.parser import default_parser, parse_text

    text = "O1\nT0101\nG97 S400 M3\nG00 X50. Z2.\nG01 Z-10. F0.2\nG96 S150\nG01 X60.\nM30\n"
    doc = parse_text(text, "t.nc", default_parser())
    traced = trace("t.nc", doc, build_index(doc))
    speeds = [(m["line"], m.get("speed"), m.get("surface_speed")) for m in traced["motions"]]
    assert speeds == [(4, 400.0, None), (5, 400.0, None), (7, None, 150.0)]
    rows = view_of_trace(traced, "t.nc").text.split("\n")[5:8]
    assert [row.split("  ")[0] for row in rows] == ["O0001 line 4", "O0001 line 5", "O0001 line 7"]
    assert [row.split()[-3:-1] for row in rows] == [["400", "-"], ["400", "0.2"], ["G96", "0.2"]]
    assert rows[2].split()[-4:-1] == ["150", "G96", "0.2"]
    # The cycle time when each begins: after T0101's 2 s; the G01 Z-10. from Z2. at F0.2 x
    # S400 = 80 mm/min takes 12 / 80 min = 9 s.
    assert [row.split()[-1] for row in rows] == ["0:02.0", "0:02.0", "0:11.0"]
