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
