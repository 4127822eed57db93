"""The arc-thread and drum-groove commands of the language server, over stdio: the seed papers'
programs with the defaults, an override, and what is refused with the parameter's name."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest
from lsprotocol import types
from pytest_lsp import LanguageClient

from fanuc_macro.analysis import analyse
from fanuc_macro.generators.generator_requests import arc_thread_request, drum_groove_request
from test_lsp import CAPABILITIES, WAIT, client, start

__all__ = ["client"]  # the fixture, shared with test_lsp.py

ARC = "fanuc-macro.arcThread"
DRUM = "fanuc-macro.drumGroove"


async def run(client: LanguageClient, command: str, *arguments: Any) -> dict[str, Any]:
    result = await asyncio.wait_for(
        client.workspace_execute_command_async(
            types.ExecuteCommandParams(command=command, arguments=list(arguments))
        ),
        WAIT,
    )
    assert isinstance(result, dict)
    return result


def g32_cuts(text: str) -> int:
    """The G32 blocks the evaluator runs in the program, read apart from the generator."""
    facts = analyse(text, "generated:check.nc").facts
    assert facts is not None
    return sum(1 for m in facts.motions if m.code == "G32")


async def test_the_commands_are_advertised_and_give_the_papers_programs(
    client: LanguageClient,
) -> None:
    result = await asyncio.wait_for(
        client.initialize_session(types.InitializeParams(capabilities=CAPABILITIES)), WAIT
    )
    provider = result.capabilities.execute_command_provider
    assert provider is not None and {ARC, DRUM} <= set(provider.commands)

    arc = await run(client, ARC, {})
    assert arc["text"].startswith("%\nO0002") and "G65 P0003" in arc["text"]
    assert arc["summary"]["layer_cuts"] == [7, 7] and arc["summary"]["finishing_cuts"] == 19
    assert arc["summary"]["g32_cuts"] == 33 == g32_cuts(arc["text"])

    drum = await run(client, DRUM, {"pitch": 40})
    assert drum["summary"] == {"passes": 9, "segments_per_pass": 11, "g32_cuts": 108}
    assert g32_cuts(drum["text"]) == 108
    # No argument at all is the arc thread's defaults too.
    assert (await run(client, ARC))["text"] == arc["text"]


async def test_an_override_changes_the_program(client: LanguageClient) -> None:
    await start(client, None)
    arc = await run(client, ARC, {"layers": "108,104,101", "cuts_per_layer": 5})
    assert arc["summary"]["layer_cuts"] == [5, 5, 5]
    assert arc["summary"]["g32_cuts"] == 34 == g32_cuts(arc["text"])
    drum = await run(client, DRUM, {"pitch": "40", "layers": 3, "points": "300,10;310,0;300,-10"})
    assert drum["summary"] == {"passes": 3, "segments_per_pass": 2, "g32_cuts": 9}
    assert g32_cuts(drum["text"]) == 9


async def test_what_cannot_be_cut_is_refused_naming_the_parameter(client: LanguageClient) -> None:
    await start(client, None)
    tool = await run(client, ARC, {"tool_radius": 10})
    assert set(tool) == {"error"}
    assert "tool nose radius r = 10" in tool["error"] and "groove radius R = 10" in tool["error"]
    pitch = await run(client, DRUM, {"layers": 9})
    assert set(pitch) == {"error"} and pitch["error"].startswith("pitch is missing")
    unknown = await run(client, DRUM, {"pitch": 40, "depth": 2})
    assert set(unknown) == {"error"} and 'unknown drum groove parameter "depth"' in unknown["error"]
    text = await run(client, ARC, {"layers": "108,x"})
    assert text == {"error": 'layers[2]: "x" is not a number'}
    two = await run(client, ARC, {}, {})
    assert "one argument" in two["error"]


@pytest.mark.parametrize(
    ("parameters", "message"),
    [
        ({"cuts_per_layer": 7.5}, "cuts_per_layer: 7.5 is not a whole number"),
        ({"pitch": True}, "pitch: true is not a number"),
        ({"layers": {"a": 1}}, 'layers: {"a": 1} is not a list of diameters'),
        ({"outer_diameter": "inf"}, 'outer_diameter: "inf" is not a finite number'),
        ({"finishing_diameter": 130}, "ASIN argument"),
    ],
)
def test_arc_thread_request_refusals(parameters: dict[str, Any], message: str) -> None:
    assert message in arc_thread_request(parameters)["error"]


def test_drum_groove_points_as_lists_or_text() -> None:
    listed = drum_groove_request({"pitch": 40, "points": [[300, 10], [310, 0], [300, -10]]})
    typed = drum_groove_request({"pitch": 40, "points": "300,10\n310,0\n300,-10"})
    assert listed == typed and listed["summary"]["segments_per_pass"] == 2
    # An empty text or null is the paper's profile.
    assert drum_groove_request({"pitch": 40, "points": ""}) == drum_groove_request({"pitch": 40})
    bad = drum_groove_request({"pitch": 40, "points": "300,10;310"})
    assert bad == {"error": 'points point 2: "310" is not a point X,Z'}


def test_a_program_takes_the_numbers_its_file_does_not_have() -> None:
    arc = arc_thread_request({}, {2, 3})
    assert "error" not in arc and arc["note"] == (
        "O0002 and O0003 are in the file already: the main program is O0004 and the roughing "
        "macro is O0006."
    )
    text = arc["text"]
    assert "\nO0004 (" in text and "G65 P0006 " in text and "\nO0006 (" in text
    assert "G65 P0005 " in text and "O0002" not in text and "O0003" not in text
    assert "note" not in arc_thread_request({}, {1000}) and "note" not in arc_thread_request({})
    # A number given is the user's: refused when the file has it.
    assert arc_thread_request({"main_number": 3}, {3}) == {"error": "the file has O0003 already"}
    drum = drum_groove_request({"pitch": 40}, {10, 1})
    assert "error" not in drum and "\nO0011 (" in drum["text"] and "G65 P0002 " in drum["text"]
    assert drum["note"] == (
        "O0010 and O0001 are in the file already: the main program is O0011 and the macro is O0002."
    )


async def test_the_commands_take_the_numbers_the_document_does_not_have(
    client: LanguageClient,
) -> None:
    await start(client, None)
    uri = "untitled:part.nc"
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=uri, language_id="fanuc-macro", version=1, text="O0002\nM30\n%\nO0005\nM99\n"
            )
        )
    )
    arc = await run(client, ARC, {"uri": uri})
    assert arc["note"] == (
        "O0002 and O0005 are in the file already: the main program is O0004 and the finishing "
        "macro is O0006."
    )
    assert "\nO0004 (" in arc["text"] and "G65 P0006 " in arc["text"]
    assert "note" not in await run(client, ARC, {"uri": "untitled:not-open.nc"})
