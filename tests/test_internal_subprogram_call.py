"""``M98 Q<n>`` without P: a subprogram call of the block N<n> of the running program, run by
the evaluator as the control runs it (the trace through the command line), M99 returning to
the block after the call, an L repeat starting again at N<n>."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from cli_runner import run

POCKETS = """\
O0034 (TWO POCKETS)
G90 G54 G00 X0 Y0
#100=0
M98 Q101
M98 Q102 L3
G00 Z100.
M30
N101 #100=#100+1
G01 X10. F100.
M99
N102 #100=#100+10
G91 G01 Y10. F100.
G90
M99
"""


def trace(tmp_path: Path, text: str) -> dict[str, Any]:
    (tmp_path / "o0034.nc").write_text(text)
    result = run(tmp_path, "trace", "--format", "json", "--controller", "0i-MF", "o0034.nc")
    assert result.returncode == 0, result.stdout + result.stderr
    answer: dict[str, Any] = json.loads(result.stdout)
    return answer


def test_the_called_blocks_run_and_return_after_the_call(tmp_path: Path) -> None:
    answer = trace(tmp_path, POCKETS)
    moves = [(m["line"], m["end"]) for m in answer["motions"]]
    assert moves == [
        (2, {"X": 0.0, "Y": 0.0}),
        (9, {"X": 10.0, "Y": 0.0}),
        (12, {"X": 10.0, "Y": 10.0}),  # N102 three times: Y in G91, 10 each
        (12, {"X": 10.0, "Y": 20.0}),
        (12, {"X": 10.0, "Y": 30.0}),
        (6, {"X": 10.0, "Y": 30.0, "Z": 100.0}),
    ]


def test_the_calls_are_no_error_but_a_missing_sequence_number_is(tmp_path: Path) -> None:
    (tmp_path / "o0034.nc").write_text(POCKETS)
    clean = run(tmp_path, "check", "--format", "json", "o0034.nc")
    assert [d["code"] for d in json.loads(clean.stdout) if d["severity"] == "error"] == []
    (tmp_path / "o0034.nc").write_text(POCKETS.replace("M98 Q101", "M98 Q105"))
    wrong = run(tmp_path, "check", "--format", "json", "o0034.nc")
    errors = [d for d in json.loads(wrong.stdout) if d["severity"] == "error"]
    assert [(d["code"], d["line"]) for d in errors] == [("MB405", 4)]
    assert errors[0]["message"].startswith("M98 Q105 calls N105 of O0034, which has none")
