"""The debugger through a real DAP client: ``fanuc-macro-dap`` as a subprocess over stdio
(tests/dap_client.py), on the seed thread module O4009/O3331, the corpus' endless loops and the
fixtures of tests/fixtures/debug."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from dap_client import DapClient

HERE = Path(__file__).resolve().parent
SEED = HERE / "fixtures" / "thread_variants" / "o4009_clean.nc"
DEBUG = HERE / "fixtures" / "debug"
SEEDS = HERE / "fixtures" / "seeds"
CORPUS = HERE.parent.parent / "shared" / "corpus"
SAMPLES = "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__"
GOTO_LOOP = CORPUS / (SAMPLES + "sampleNC(GOTO-infinite-loop).ncd")
WHILE_LOOP = CORPUS / (SAMPLES + "sampleNC(WHILE-DO-infinite-loop).ncd")


def line_of(path: Path, text: str, nth: int = 1) -> int:
    """The 1-based line of the ``nth`` line that holds ``text``."""
    found = [i + 1 for i, line in enumerate(path.read_text().splitlines()) if text in line]
    return found[nth - 1]


@pytest.fixture
def dap() -> Iterator[DapClient]:
    client = DapClient()
    yield client
    client.close()


def top(dap: DapClient) -> dict[str, object]:
    frame: dict[str, object] = dap.ok("stackTrace", {"threadId": 1})["stackFrames"][0]
    return frame


def test_initialize_says_what_the_adapter_does(dap: DapClient) -> None:
    caps = dap.ok("initialize", {"adapterID": "fanuc-macro"})
    for capability in (
        "supportsConfigurationDoneRequest",
        "supportsConditionalBreakpoints",
        "supportsHitConditionalBreakpoints",
        "supportsLogPoints",
        "supportsEvaluateForHovers",
        "supportsSetVariable",
        "supportsRestartRequest",
        "supportsExceptionInfoRequest",
    ):
        assert caps[capability] is True, capability
    filters = {f["filter"]: f["default"] for f in caps["exceptionBreakpointFilters"]}
    assert filters == {"alarm": True, "message": True, "programStop": False}


def test_breakpoint_on_the_first_g92_of_o3331(dap: DapClient) -> None:
    g92 = line_of(SEED, "G92")
    dap.start({"program": str(SEED)}, {str(SEED): [{"line": g92}]})
    stop = dap.stopped()
    assert stop["reason"] == "breakpoint"
    frames = dap.ok("stackTrace", {"threadId": 1})["stackFrames"]
    assert [f["name"].split()[0] for f in frames] == ["O3331", "O4009"]
    assert frames[0]["line"] == g92
    assert frames[1]["line"] == line_of(SEED, "M98 P0013331")
    assert frames[0]["source"]["path"] == str(SEED)
    assert dap.evaluate("#9") == "0.092"
    assert dap.evaluate("#4") == "1.907"  # h, at the control's 0.001 mm
    assert float(dap.evaluate("#101")) == 3.0
    assert dap.evaluate("[#100-2*#9]") == "49.816"
    assert dap.evaluate("#9 GT 0.05") == "true"
    # The next turn of the N10 loop: the second pass's depth.
    dap.ok("continue", {"threadId": 1})
    assert dap.stopped()["reason"] == "breakpoint"
    assert float(dap.evaluate("#9")) == 0.13
    assert dap.evaluate("#7") == "2."


def test_scopes_show_locals_commons_and_the_modal_state(dap: DapClient) -> None:
    g92 = line_of(SEED, "G92")
    dap.start({"program": str(SEED)}, {str(SEED): [{"line": g92}]})
    dap.stopped()
    scopes = dap.ok("scopes", {"frameId": 1})["scopes"]
    names = [s["name"] for s in scopes]
    # Short titles: O3331, which M98 called, has the locals of O4009.
    assert names == [
        "Locals #1-#33 of O4009",
        "Common variables",
        "System variables",
        "Modal state",
    ]
    by_name = {s["name"].split(" of ")[0]: s["variablesReference"] for s in scopes}

    def variables(scope: str) -> dict[str, str]:
        found = dap.ok("variables", {"variablesReference": by_name[scope]})["variables"]
        return {v["name"]: v["value"] for v in found}

    locals_ = variables("Locals #1-#33")
    assert len(locals_) == 33
    assert locals_["#9"] == "0.092" and locals_["#12"] == "8." and locals_["#33"] == "<vacant>"
    commons = variables("Common variables")
    assert commons == {"#100": "50.", "#101": "3.", "#102": "50.", "#103": "0.048", "#104": "0.17"}
    modal = variables("Modal state")
    assert modal["G group 01"] == "G01"  # the G01 before N10; the G92 has not run yet
    assert modal["S"] == "400." and modal["T"] == "101." and modal["unit"] == "mm (G21)"
    assert modal["F"] == "0.5"
    assert modal["G group 05"] == "G99"  # feed per revolution
    # The cycle time before the first G92: the tool change T0101 (2 s), the G01 X51. W7. at
    # F0.5 x S400 = 200 mm/min (sqrt(2² + 7²) mm: 2.184 s) and the G01 W-1.036 of the first
    # pass's offset (0.311 s): 4.495 s.
    assert modal["cycle time so far"] == "4.5 s"


def test_step_into_over_and_out_of_the_m98(dap: DapClient) -> None:
    m98 = line_of(SEED, "M98 P0013331")
    dap.start({"program": str(SEED)}, {str(SEED): [{"line": m98}]})
    dap.stopped()
    dap.ok("stepIn", {"threadId": 1})
    assert dap.stopped()["reason"] == "step"
    frames = dap.ok("stackTrace", {"threadId": 1})["stackFrames"]
    assert frames[0]["name"].startswith("O3331") and frames[0]["line"] == line_of(SEED, "O3331")
    dap.ok("next", {"threadId": 1})
    dap.stopped()
    assert top(dap)["line"] == line_of(SEED, "#1=1.*#101")
    dap.ok("stepOut", {"threadId": 1})
    dap.stopped()
    frames = dap.ok("stackTrace", {"threadId": 1})["stackFrames"]
    assert len(frames) == 1 and frames[0]["line"] == line_of(SEED, "G00 X100. Z100.")
    # Step over the call: the whole thread is cut and the run stops after it.
    dap.ok("restart")
    dap.stopped()
    assert top(dap)["line"] == m98
    dap.ok("next", {"threadId": 1})
    dap.stopped()
    assert top(dap)["line"] == line_of(SEED, "G00 X100. Z100.")
    assert dap.evaluate("#12") == "0."  # O3331's finishing passes all ran


def test_stop_on_entry_and_the_end_of_the_run(dap: DapClient) -> None:
    dap.start({"program": str(SEED), "stopOnEntry": True})
    assert dap.stopped()["reason"] == "entry"
    assert top(dap)["line"] == line_of(SEED, "O4009")
    dap.ok("continue", {"threadId": 1})
    assert dap.event("exited")["body"]["exitCode"] == 0
    dap.event("terminated")
    assert "O4009 ended after" in dap.output_text()


def test_conditions_hit_counts_and_logpoints(dap: DapClient) -> None:
    g92 = line_of(SEED, "G92")
    dap.start(
        {"program": str(SEED)},
        {
            str(SEED): [
                {"line": g92, "logMessage": "pass {#7}: X{[#100-2*#9]}"},
                {"line": g92 + 2, "condition": "#7 GT 2", "hitCondition": "2"},
            ]
        },
    )
    stop = dap.stopped()
    assert stop["reason"] == "breakpoint"
    # The second time #7 > 2 at the second G92: the fourth pass.
    assert dap.evaluate("#7") == "4."
    logged = [ln for ln in dap.output_text().splitlines() if ln.startswith("pass ")]
    assert logged == ["pass 1.: X49.816", "pass 2.: X49.74", "pass 3.: X49.681", "pass 4.: X49.632"]


def test_a_bad_condition_is_an_unverified_breakpoint(dap: DapClient) -> None:
    dap.ok("initialize", {"adapterID": "fanuc-macro"})
    dap.ok("launch", {"program": str(SEED)})
    dap.event("initialized")
    found = dap.ok(
        "setBreakpoints",
        {
            "source": {"path": str(SEED)},
            "breakpoints": [
                {"line": line_of(SEED, "G92"), "condition": "#9 >> 1"},
                {"line": 1},
                {"line": line_of(SEED, "G92"), "hitCondition": "often"},
                {"line": line_of(SEED, "%", 2)},
            ],
        },
    )["breakpoints"]
    assert [b["verified"] for b in found] == [False, True, False, False]
    assert "not a Macro B condition" in found[0]["message"]
    assert found[1]["line"] == line_of(SEED, "O4009")  # '%' runs nothing: the next block
    assert "hit count" in found[2]["message"]
    assert found[3]["message"] == "no block runs from here to the end of O4009"


def test_set_a_variable_and_assign_in_the_console(dap: DapClient) -> None:
    g92 = line_of(SEED, "G92")
    dap.start({"program": str(SEED)}, {str(SEED): [{"line": g92}]})
    dap.stopped()
    scopes = dap.ok("scopes", {"frameId": 1})["scopes"]
    locals_ref = scopes[0]["variablesReference"]
    assert dap.ok(
        "setVariable", {"variablesReference": locals_ref, "name": "#9", "value": "0.2"}
    ) == {"value": "0.2"}
    assert dap.evaluate("[#100-2*#9]") == "49.6"
    assert dap.ok("evaluate", {"expression": "#100=40", "context": "repl"})["result"] == "40."
    assert dap.evaluate("#100") == "40."
    refused = dap.request(
        "setVariable",
        {"variablesReference": scopes[2]["variablesReference"], "name": "#5041", "value": "1"},
    )
    assert not refused["success"] and "read-only" in refused["message"]
    wrong = dap.request("evaluate", {"expression": "SQRT[-#101]", "frameId": 1})
    assert not wrong["success"] and "PS0119" in wrong["message"]


def test_an_alarm_stops_with_its_message(dap: DapClient) -> None:
    program = DEBUG / "o5000_alarm.nc"
    dap.start({"program": str(program)})
    stop = dap.stopped()
    assert stop["reason"] == "exception"
    assert "SQRT" in stop["text"] and "PS0119" in stop["text"]
    assert top(dap)["line"] == line_of(program, "SQRT")
    assert dap.evaluate("#1") == "-2."
    info = dap.ok("exceptionInfo", {"threadId": 1})
    assert info["exceptionId"] == "alarm" and "PS0119" in info["description"]
    dap.ok("continue", {"threadId": 1})
    assert dap.event("exited")["body"]["exitCode"] == 1
    assert "stopped on an alarm" in dap.output_text()


def test_a_feed_of_zero_stops_as_the_control_does(dap: DapClient) -> None:
    program = DEBUG / "o5010_feed_zero.nc"
    dap.start({"program": str(program)})
    stop = dap.stopped()
    assert stop["reason"] == "exception"
    assert "G01 runs with the feed F = 0" in stop["text"] and "PS0011" in stop["text"]
    assert top(dap)["line"] == line_of(program, "G01 Z-1. F#4")
    assert dap.evaluate("#4") == "0."
    dap.ok("continue", {"threadId": 1})
    assert dap.event("exited")["body"]["exitCode"] == 1


def test_alarms_can_be_let_through(dap: DapClient) -> None:
    dap.start({"program": str(DEBUG / "o5000_alarm.nc")}, filters=[])
    assert dap.event("exited")["body"]["exitCode"] == 1
    assert "PS0119" in dap.output_text()
    assert not [e for e in dap.events if e["event"] == "stopped"]


def test_dprnt_a_message_and_a_g65_level(dap: DapClient) -> None:
    program = DEBUG / "o5100_messages.nc"
    inner = line_of(program, "#100=#1+#2")
    dap.start({"program": str(program)}, {str(program): [{"line": inner}]})
    stop = dap.stopped()
    assert stop["reason"] == "exception" and stop["text"] == "CHECK THE INSERT"
    assert "X12.500  Y-0.250" in dap.output_text()
    dap.ok("continue", {"threadId": 1})
    assert dap.stopped()["reason"] == "breakpoint"
    frames = dap.ok("stackTrace", {"threadId": 1})["stackFrames"]
    assert frames[0]["name"] == "O5101 (G65 A1. B2.5 F0.3)"
    scopes = dap.ok("scopes", {"frameId": 1})["scopes"]
    found = dap.ok("variables", {"variablesReference": scopes[0]["variablesReference"]})
    values = {v["name"]: v["value"] for v in found["variables"]}
    assert (
        values["#1 (A)"] == "1." and values["#9 (F)"] == "0.3" and values["#24 (X)"] == "<vacant>"
    )
    # The caller's locals are its own (G65 opens a level).
    assert dap.evaluate("#1", frames[1]["id"]) == "<vacant>"


def test_launch_arguments_and_commons(dap: DapClient) -> None:
    program = DEBUG / "o5100_messages.nc"
    dap.start(
        {
            "program": str(program),
            "entry": "O5101",
            "arguments": "A1. B2. F0.8",
            "commons": {"#500": 7},
        }
    )
    stop = dap.stopped()
    assert stop["reason"] == "exception"
    assert "3001" in stop["text"] and "FEED TOO HIGH" in stop["text"]
    assert dap.evaluate("#100") == "3."
    assert dap.evaluate("#500") == "7."


def test_the_endless_loop_can_be_paused(dap: DapClient) -> None:
    if not GOTO_LOOP.exists():
        pytest.skip("the corpus is not beside the repository")
    dap.start({"program": str(GOTO_LOOP), "stepBudget": 10**9})
    dap.ok("pause", {"threadId": 1})
    assert dap.stopped()["reason"] == "pause"
    frame = top(dap)
    before = dap.evaluate("#1")
    dap.ok("next", {"threadId": 1})
    dap.stopped()
    assert top(dap) != frame or dap.evaluate("#1") != before
    dap.ok("terminate")
    dap.event("terminated")


def test_a_chinese_client_is_answered_in_chinese(dap: DapClient) -> None:
    from test_translation_fixtures import ENGLISH

    g92 = line_of(SEED, "G92")
    caps = dap.start({"program": str(SEED)}, {str(SEED): [{"line": g92}]}, locale="zh-CN")
    labels = [f["label"] for f in caps["exceptionBreakpointFilters"]]
    assert labels[0] == "报警（#3000、PS0112 除零等）"
    stop = dap.stopped()
    assert stop["description"] == "断点"
    scopes = dap.ok("scopes", {"frameId": 1})["scopes"]
    names = [s["name"] for s in scopes]
    assert names == ["O4009 的局部变量 #1-#33", "公共变量", "系统变量", "模态状态"]
    modal = {
        v["name"]: v["value"]
        for v in dap.ok("variables", {"variablesReference": scopes[3]["variablesReference"]})[
            "variables"
        ]
    }
    # The same state as in English (test above), its names and units said in Chinese.
    assert modal["G 代码组 01"] == "G01" and modal["单位"] == "公制（G21）"
    assert modal["至此加工时间"] == "4.5 秒"
    assert not [text for text in [*labels, *names, *modal, *modal.values()] if ENGLISH.search(text)]


def test_a_run_past_the_budget_ends_with_a_message(dap: DapClient) -> None:
    if not WHILE_LOOP.exists():
        pytest.skip("the corpus is not beside the repository")
    dap.start({"program": str(WHILE_LOOP), "stepBudget": 5000})
    assert dap.event("exited")["body"]["exitCode"] == 1
    dap.event("terminated")
    text = dap.output_text()
    assert "step budget of 5,000 blocks" in text


def test_the_configuration_file_beside_the_program_is_read(dap: DapClient, tmp_path: Path) -> None:
    if not WHILE_LOOP.exists():
        pytest.skip("the corpus is not beside the repository")
    program = tmp_path / "loop.nc"
    program.write_bytes(WHILE_LOOP.read_bytes())
    config = tmp_path / "fanuc-macro.toml"
    config.write_text("[analysis]\nstep-budget = 4000\n", encoding="utf-8")
    dap.start({"program": str(program)})
    assert dap.event("exited")["body"]["exitCode"] == 1
    dap.event("terminated")
    assert "step budget of 4,000 blocks" in dap.output_text()


def test_the_launch_reads_the_machine_from_the_configuration_file(
    dap: DapClient, tmp_path: Path
) -> None:
    # G99 is the lathe's feed per revolution (group 05) and the mill's return to R (group 10).
    program = tmp_path / "o1000.nc"
    program.write_text("O1000\nG99\nG00 X1.\nM30\n", encoding="utf-8")
    (tmp_path / "fanuc-macro.toml").write_text("[machine]\ncontroller = '0i-MF'\n", "utf-8")
    dap.start({"program": str(program)}, {str(program): [{"line": 3}]})
    dap.stopped()
    scopes = dap.ok("scopes", {"frameId": 1})["scopes"]
    modal = next(s for s in scopes if s["name"].startswith("Modal state"))
    found = dap.ok("variables", {"variablesReference": modal["variablesReference"]})
    shown = {v["name"]: v["value"] for v in found["variables"]}
    assert shown.get("G group 10") == "G99" and "G group 05" not in shown, shown


def test_a_bad_configuration_file_fails_the_launch_with_its_message(
    dap: DapClient, tmp_path: Path
) -> None:
    program = tmp_path / "o1000.nc"
    program.write_text("O1000\nG00 X1.\nM30\n", encoding="utf-8")
    (tmp_path / "fanuc-macro.toml").write_text("[analysis]\nstep-budget = 'x'\n", "utf-8")
    dap.ok("initialize", {"adapterID": "fanuc-macro"})
    answer = dap.request("launch", {"program": str(program)})
    assert not answer["success"]
    assert (
        "fanuc-macro.toml:2: analysis.step-budget: 'x' is not a whole number" in (answer["message"])
    )


def test_bad_requests_get_clear_answers(dap: DapClient) -> None:
    dap.ok("initialize", {"adapterID": "fanuc-macro"})
    missing = dap.request("launch", {"program": str(DEBUG / "nothing.nc")})
    assert not missing["success"] and "is not a file" in missing["message"]
    no_entry = dap.request("launch", {"program": str(SEED), "entry": 77})
    assert not no_entry["success"] and "no O77" in no_entry["message"]
    bad_args = dap.request("launch", {"program": str(SEED), "arguments": "G1."})
    assert not bad_args["success"] and "not a G65 letter" in bad_args["message"]
    # Bytes that are no message, then a body that is no JSON: the adapter goes on.
    dap.send_raw(b"hello\r\n\r\n")
    dap.send_raw(b"Content-Length: 5\r\n\r\n{oops")
    assert not dap.request("stackTrace", {"threadId": 1})["success"]
    assert not dap.request("frobnicate")["success"]
    dap.ok("launch", {"program": str(SEED)})
    dap.event("initialized")
    assert not dap.request("continue", {"threadId": 1})["success"]  # not started, not stopped


def test_the_same_run_gives_the_same_events() -> None:
    def run() -> list[str]:
        client = DapClient()
        try:
            client.start({"program": str(DEBUG / "o5100_messages.nc")}, filters=["alarm"])
            client.event("terminated")
            return [
                json.dumps(e.get("body"), sort_keys=True)
                for e in client.events
                if e["event"] in ("output", "stopped", "exited")
            ]
        finally:
            client.close()

    first = run()
    assert first == run()
    assert any("CHECK THE INSERT" in e for e in first) is False  # the message filter is off


def test_restart_runs_the_program_as_it_is_now(dap: DapClient, tmp_path: Path) -> None:
    program = tmp_path / "o6000.nc"
    program.write_text("%\nO6000\n#1=2.\n#2=#1*3.\nM30\n%\n")
    dap.start({"program": str(program)}, {str(program): [{"line": 4}]})
    dap.stopped()
    assert dap.evaluate("#1") == "2."
    # Edited while stopped: a comment line where the breakpoint was, a new value above it.
    program.write_text("%\nO6000\n#1=5.\n(TRIPLE IT)\n#2=#1*3.\nM30\n%\n")
    dap.ok("restart")
    changed = dap.event("breakpoint")["body"]
    assert changed["reason"] == "changed" and changed["breakpoint"]["line"] == 5
    dap.stopped()
    assert top(dap)["line"] == 5
    assert dap.evaluate("#1") == "5."
    assert "Restarting O6000." in dap.output_text()


def test_an_undecided_condition_is_said(dap: DapClient, tmp_path: Path) -> None:
    program = tmp_path / "o6100.nc"
    program.write_text(
        "%\nO6100 (PROBE)\nG31 X10. F100\nIF[#5061 GT 9.] GOTO10\n#3000=1(NO CONTACT)\nN10 M30\n%\n"
    )
    dap.start({"program": str(program), "controller": "0i-MF"}, filters=[])
    dap.event("terminated")
    text = dap.output_text()
    assert "o6100.nc:4: this condition cannot be decided before the machine runs" in text
    assert "depends on #5061" in text


def test_program_stops_stop_when_asked(dap: DapClient, tmp_path: Path) -> None:
    program = tmp_path / "o6200.nc"
    program.write_text("%\nO6200\nG00 X10.\nM00 (TURN THE PART)\nG00 X20.\nM30\n%\n")
    dap.start({"program": str(program)}, filters=["alarm", "programStop"])
    stop = dap.stopped()
    assert stop["reason"] == "exception" and stop["text"] == "M00 program stop: TURN THE PART"
    assert top(dap)["line"] == 5  # after the M00, as the control
    assert dap.ok("exceptionInfo", {"threadId": 1})["exceptionId"] == "programStop"


def frame(message: dict[str, Any]) -> bytes:
    body = json.dumps(message).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def test_a_message_nested_too_deep_is_refused_and_the_session_goes_on(dap: DapClient) -> None:
    # Python 3.13's json reads 5,000 levels (then it is no object); older ones give up sooner.
    deep = b"[" * 5000 + b"]" * 5000
    dap.send_raw(b"Content-Length: %d\r\n\r\n" % len(deep) + deep)
    said = dap.event("output")["body"]
    assert said["category"] == "stderr"
    assert said["output"].startswith("fanuc-macro-dap: a message could not be read: ")
    assert "nested too deep" in said["output"] or "not a JSON object" in said["output"]
    dap.start({"program": str(SEEDS / "o4009_external_m50x3.nc"), "stopOnEntry": True})
    assert dap.stopped()["reason"] == "entry"
    assert dap.proc.poll() is None


@pytest.mark.parametrize(
    "bad",
    [
        # A length larger than the body: the next messages would be read as its body.
        b'Content-Length: 9999\r\n\r\n{"seq": 1, "type": "request"',
        b"Content-Length: 9999\r\n\r\n{}",
        # A length that is no number, with no line end: glued to the next header.
        b"Content-Length: abc",
        b"Content-Length: 99999999999\r\n\r\n{}",
        b"\x00\xff garbage Content-Length: 12",
    ],
)
def test_the_reader_finds_the_next_message_after_a_bad_one(dap: DapClient, bad: bytes) -> None:
    dap.send_raw(bad)
    seqs = [dap.send("threads") for _ in range(5)]
    for seq in seqs:
        response = dap._next(lambda m, seq=seq: m.get("request_seq") == seq)
        assert response["success"] and response["command"] == "threads"
    assert "could not be read" in dap.output_text()


def test_a_length_that_swallows_the_next_message_is_found_out(dap: DapClient) -> None:
    # The wrong length ends inside the next message: the body is no JSON but holds a header.
    following = frame({"seq": 1, "type": "request", "command": "threads"})
    short = b'{"seq": 7}'
    dap._seq = 1
    dap.send_raw(b"Content-Length: %d\r\n\r\n" % (len(short) + 30) + short + following)
    response = dap._next(lambda m: m.get("request_seq") == 1)
    assert response["success"] and response["command"] == "threads"
    dap.ok("threads")


@pytest.mark.parametrize(
    ("message", "said"),
    [
        ({"seq": 3, "type": "request"}, "has no command"),
        ({"seq": 3, "type": "request", "command": 5}, "not a command name"),
        ({"seq": 3, "type": "request", "command": ""}, "not a command name"),
        ({"seq": 3, "type": "request", "command": "threads", "arguments": [1]}, "not an object"),
        ({"seq": 3, "type": "reqest", "command": "threads"}, "'reqest', not 'request'"),
        ({"seq": 3, "command": "threads"}, "None, not 'request'"),
        (
            {"seq": 3, "type": "request", "command": "setBreakpoints", "arguments": {"source": 1}},
            "setBreakpoints",
        ),
    ],
)
def test_a_malformed_request_gets_an_error_response(
    dap: DapClient, message: dict[str, Any], said: str
) -> None:
    dap.send_raw(frame(message))
    response = dap._next(lambda m: m.get("type") == "response")
    assert response["request_seq"] == 3 and response["success"] is False, response
    assert said in response["message"], response
    dap._seq = 3
    dap.ok("threads")


def test_a_request_without_a_seq_is_answered_too(dap: DapClient) -> None:
    dap.send_raw(frame({"type": "request", "command": "threads"}))
    response = dap._next(lambda m: m.get("type") == "response")
    assert response["success"] is False and "no integer seq" in response["message"]
    dap.ok("threads")
