"""docs/alarms.md: the 0i-F's program and macro alarms, and the rule that predicts each.

The page's table is checked against the code: the rules it names are registered and its links
land on their sections of docs/rules.md, every alarm the evaluator raises itself has a row with
a rule, each row without a rule says why, and the counts at the top of the page are the table's.
"""

from __future__ import annotations

import re
from collections import Counter
from functools import cache
from pathlib import Path
from typing import NamedTuple

import pytest

from fanuc_macro.analysis import RULES

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "alarms.md"
SOURCE = ROOT / "server" / "fanuc_macro"

HEADER = ["Alarm", "Name", "When the control raises it", "Predicted by", "Why not / notes"]
COVERAGE = ["Alarms", "Count"]
NO_RULE = "—"
# The coverage table's totals; its other rows are the reasons a row without a rule gives.
LISTED = "Listed"
PREDICTED = "Predicted by a rule"
NOT_DECIDABLE = "Not decidable from the program text"
DECIDABLE = "Decidable by a run, not yet predicted"
USER_ALARM = "3000+n"  # the row of the program's own #3000=n alarm

ALARM = re.compile(r"PS(\d{4})|3000\+n")
LINK = re.compile(r"\[(MB\d{3})\]\(rules\.md#([a-z0-9-]+)\)")
# An alarm the evaluator raises itself: MacroAlarm("PS0112", ...), MacroAlarm("3000", ...).
RAISED = re.compile(r'MacroAlarm\(\s*"([^"]+)"')


class Row(NamedTuple):
    alarm: str
    name: str
    when: str
    predicted_by: str
    notes: str

    @property
    def rules(self) -> list[str]:
        return [code for code, _anchor in LINK.findall(self.predicted_by)]


def tables(text: str) -> list[list[list[str]]]:
    """The markdown tables of a text: rows of cells, the separator row left out."""
    found: list[list[list[str]]] = []
    rows: list[list[str]] = []
    for line in [*text.splitlines(), ""]:
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().removeprefix("|").removesuffix("|").split("|")]
            if not all(re.fullmatch(r":?-+:?", cell) for cell in cells):
                rows.append(cells)
        elif rows:
            found.append(rows)
            rows = []
    return found


def table(header: list[str]) -> list[list[str]]:
    """The rows of the page's table with this header."""
    matching = [t[1:] for t in tables(PAGE.read_text("utf-8")) if t[0] == header]
    assert len(matching) == 1, f"docs/alarms.md needs one table headed {header}"
    return matching[0]


@cache
def alarm_rows() -> list[Row]:
    rows = table(HEADER)
    for cells in rows:
        assert len(cells) == len(HEADER), f"a row of {len(cells)} cells: {cells}"
    return [Row(*cells) for cells in rows]


@cache
def coverage() -> dict[str, int]:
    return {label: int(count) for label, count in table(COVERAGE)}


def reasons() -> list[str]:
    return [label for label in coverage() if label not in (LISTED, PREDICTED, NOT_DECIDABLE)]


def reason_of(row: Row) -> str:
    return row.notes.split(":", 1)[0]


def raised_by_the_evaluator() -> list[str]:
    found = {n for path in SOURCE.rglob("*.py") for n in RAISED.findall(path.read_text("utf-8"))}
    assert found, 'no MacroAlarm("...") found in server/fanuc_macro: RAISED is stale'
    return sorted(found)


def order(alarm: str) -> tuple[int, int]:
    """PS alarms by number, then the program's own #3000 alarm."""
    match = ALARM.fullmatch(alarm)
    assert match, f"{alarm!r} is neither PSnnnn nor {USER_ALARM}"
    return (0, int(match[1])) if match[1] else (1, 3000)


def test_each_alarm_has_one_row_in_ascending_order() -> None:
    alarms = [row.alarm for row in alarm_rows()]
    twice = [alarm for alarm, n in Counter(alarms).items() if n > 1]
    assert not twice, f"alarms listed twice: {twice}"
    assert alarms == sorted(alarms, key=order), "rows are not in ascending order"


def test_the_predicting_rules_are_registered_and_linked() -> None:
    for row in alarm_rows():
        if row.predicted_by == NO_RULE:
            continue
        assert row.rules, f"{row.alarm}: Predicted by names no rule: {row.predicted_by!r}"
        assert LINK.sub("", row.predicted_by).strip(", ") == "", (
            f"{row.alarm}: Predicted by holds more than links: {row.predicted_by!r}"
        )
        for code, anchor in LINK.findall(row.predicted_by):
            assert code in RULES, f"{row.alarm}: {code} is not a registered rule"
            wanted = f"{code.lower()}-{RULES[code].name}"
            assert anchor == wanted, f"{row.alarm}: {code} links to #{anchor}, not #{wanted}"


@pytest.mark.parametrize("number", raised_by_the_evaluator())
def test_every_alarm_the_evaluator_raises_has_a_rule(number: str) -> None:
    alarm = USER_ALARM if number == "3000" else number
    row = next((row for row in alarm_rows() if row.alarm == alarm), None)
    assert row is not None, f"the evaluator raises {number}: docs/alarms.md needs its row"
    assert row.rules, f"the evaluator raises {number}: its row must name the rule reporting it"


def test_each_row_without_a_rule_says_why() -> None:
    for row in alarm_rows():
        if row.rules:
            assert reason_of(row) not in reasons(), f"{row.alarm} has a rule and a reason"
        else:
            assert reason_of(row) in reasons(), (
                f"{row.alarm}: the note of a row without a rule starts with one of {reasons()}"
            )


def test_the_counts_at_the_top_are_the_tables() -> None:
    rows = alarm_rows()
    by_reason = Counter(reason_of(row) for row in rows if not row.rules)
    assert DECIDABLE in reasons(), f"the counts at the top need a row {DECIDABLE!r}"
    expected = {
        LISTED: len(rows),
        PREDICTED: sum(1 for row in rows if row.rules),
        NOT_DECIDABLE: sum(by_reason[reason] for reason in reasons() if reason != DECIDABLE),
        **{reason: by_reason[reason] for reason in reasons()},
    }
    assert coverage() == expected, "the counts at the top of docs/alarms.md are stale"
