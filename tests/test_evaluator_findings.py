"""The evaluator's findings are typed records: a class per kind, with the fields its rule
reads, matched by type (``RuleContext.findings``); their ``kind`` is what the trace prints."""

from __future__ import annotations

import dataclasses

import pytest

from fanuc_macro.evaluator import evaluate
from fanuc_macro.evaluator.facts import (
    AddressNotInteger,
    AddressOutOfRange,
    AlarmFinding,
    ArithmeticAlarm,
    EndlessLoop,
    FeedNotSet,
    FeedZero,
    Finding,
    GotoAlarm,
    ProgramNotFound,
    ReturnMissing,
)
from fanuc_macro.evaluator.values import AlarmKind
from fanuc_macro.program.index import build_index
from fanuc_macro.rules.context import RuleContext
from fanuc_macro.syntax.parser import parse_text

URI = "file:///findings.nc"


def context(text: str) -> RuleContext:
    doc = parse_text(text, URI)
    index = build_index(doc)
    return RuleContext(doc, index, facts=evaluate([(URI, doc, index)], only_uri=URI))


def reported(text: str) -> list[Finding]:
    ctx = context(text)
    facts = ctx.doc_facts()
    assert facts is not None
    return list(facts.findings)


def test_an_alarm_is_a_record_of_its_class_with_its_kind_and_number() -> None:
    (found,) = reported("O1000\n#1=3\nGOTO#1\nM30\n")
    assert isinstance(found, GotoAlarm) and isinstance(found, AlarmFinding)
    assert found.alarm is AlarmKind.GOTO_MISSING and found.number == "PS0128"
    assert found.kind == "alarm:goto-missing"  # as the trace and the debugger print it
    assert (found.line, found.uri) == (2, URI)


def test_each_kind_of_finding_has_its_class() -> None:
    assert isinstance(reported("O1\n#1=1/0\nM30\n")[0], ArithmeticAlarm)
    (zero,) = reported("O1\nG01 X1. F0\nM30\n")
    assert isinstance(zero, FeedZero) and not zero.lead and zero.kind == "alarm:feed-zero"
    (lead,) = reported("O1\nG32 Z-10. F0\nM30\n")
    assert isinstance(lead, FeedZero) and lead.lead
    (fraction,) = reported("O1\n#1=1.5\nM#1\nM30\n")
    assert isinstance(fraction, AddressNotInteger) and fraction.address == "M"
    assert fraction.kind == "address-non-integer"
    (negative,) = reported("O1\n#1=-1\nS#1\nM30\n")
    assert isinstance(negative, AddressOutOfRange) and negative.address == "S"
    (missing,) = reported("O1\nM98 P4321\nM30\n")
    assert isinstance(missing, ProgramNotFound) and missing.program == 4321
    (loop,) = reported("O1\nN1 #1=1\nGOTO1\nM30\n")
    assert isinstance(loop, EndlessLoop) and loop.kind == "endless-loop"
    (feedless,) = reported("O1\nG01 X1.\nM30\n")
    assert isinstance(feedless, FeedNotSet) and feedless.kind == "feed-not-set"


def test_a_finding_cannot_be_changed() -> None:
    (found,) = reported("O1000\n#1=3\nGOTO#1\nM30\n")
    with pytest.raises(dataclasses.FrozenInstanceError):
        found.line = 7  # type: ignore[misc]


def test_rules_match_findings_by_class_and_subclass_in_the_order_found() -> None:
    text = "O1\nM98 P2\nM30\nO2\nG01 X1. F-1\nM99 P7\n"
    ctx = context(text)
    assert [f.kind for f in ctx.findings(ReturnMissing)] == ["alarm:return-missing"]
    assert [f.kind for f in ctx.findings(AlarmFinding)] == ["alarm:return-missing"]
    assert [f.kind for f in ctx.findings(GotoAlarm)] == []
    both = [type(f) for f in ctx.findings(ReturnMissing, AddressOutOfRange)]
    assert both == [AddressOutOfRange, ReturnMissing]
    assert [type(f) for f in ctx.findings(Finding)] == both
