"""The findings of ``check`` in the forms CI reads: SARIF 2.1.0 (GitHub code scanning), GitHub
Actions workflow commands, JUnit XML; the ``--statistics`` table; the text form, in colour on
a terminal."""

from __future__ import annotations

import os
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from types import MappingProxyType
from typing import Any, TextIO

from .. import __version__
from ..analysis import RULES
from ..rules_doc import rule_url
from ..translation import tr
from .language import said

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
HOMEPAGE = "https://github.com/fanuc-macro/fanuc-macro"
# SARIF's levels and GitHub's commands have no "information" and "hint": both are notes.
_SARIF_LEVELS = MappingProxyType(
    {"error": "error", "warning": "warning", "information": "note", "hint": "note"}
)
_GITHUB_COMMANDS = MappingProxyType(
    {"error": "error", "warning": "warning", "information": "notice", "hint": "notice"}
)


def _artifact_uri(path: str) -> str:
    """A finding's file as SARIF wants it: a relative path in / form, or a file: URI."""
    p = Path(path)
    return p.resolve().as_uri() if p.is_absolute() else p.as_posix()


def sarif(records: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """One SARIF 2.1.0 log of ``records`` (``check --format json``'s), with each rule that
    appears described (its name, summary, default severity and documentation link)."""
    codes = sorted({r["code"] for r in records})
    index = {code: n for n, code in enumerate(codes)}
    rules = []
    for code in codes:
        info = RULES.get(code)
        rule: dict[str, Any] = {"id": code, "helpUri": rule_url(code)}
        if info is not None:
            rule["name"] = info.name
            rule["shortDescription"] = {"text": info.summary}
            rule["defaultConfiguration"] = {"level": _SARIF_LEVELS[info.severity.value]}
        rules.append(rule)
    results = [
        {
            "ruleId": r["code"],
            "ruleIndex": index[r["code"]],
            "level": _SARIF_LEVELS[r["severity"]],
            "message": {"text": r["message"]},
            "locations": [
                {
                    "physicalLocation": {
                        "artifactLocation": {"uri": _artifact_uri(r["path"])},
                        "region": {
                            "startLine": r["line"],
                            "startColumn": r["column"],
                            "endLine": r["end_line"],
                            "endColumn": r["end_column"],
                        },
                    }
                }
            ],
        }
        for r in records
    ]
    driver = {
        "name": "fanuc-macro",
        "version": __version__,
        "informationUri": HOMEPAGE,
        "rules": rules,
    }
    return {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [{"tool": {"driver": driver}, "results": results}],
    }


def _escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _escape_property(text: str) -> str:
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


def github(records: Sequence[dict[str, Any]], out: TextIO) -> None:
    """Each finding as a GitHub Actions workflow command (an annotation on the file's line)."""
    for r in records:
        info = RULES.get(r["code"])
        title = r["code"] if info is None else f"{r['code']} {info.name}"
        properties = ",".join(
            f"{name}={_escape_property(str(value))}"
            for name, value in (
                ("file", Path(r["path"]).as_posix()),
                ("line", r["line"]),
                ("col", r["column"]),
                ("endLine", r["end_line"]),
                ("endColumn", r["end_column"]),
                ("title", title),
            )
        )
        command = _GITHUB_COMMANDS[r["severity"]]
        out.write(f"::{command} {properties}::{_escape_data(r['message'])}\n")


def junit(checked: Sequence[str], records: Sequence[dict[str, Any]]) -> str:
    """A JUnit XML report: a test case per file checked, failed by its findings."""
    from xml.etree import ElementTree as ET

    by_path: dict[str, list[dict[str, Any]]] = {path: [] for path in checked}
    for r in records:
        by_path.setdefault(r["path"], []).append(r)
    failures = sum(1 for found in by_path.values() if found)
    suites = ET.Element("testsuites", name="fanuc-macro", tests=str(len(by_path)))
    suite = ET.SubElement(
        suites, "testsuite", name="fanuc-macro check", tests=str(len(by_path)),
        failures=str(failures), errors="0", skipped="0",
    )  # fmt: skip
    for path, found in by_path.items():
        case = ET.SubElement(suite, "testcase", classname="fanuc-macro", name=path)
        if found:
            first = found[0]
            failure = ET.SubElement(
                case, "failure", type=first["code"],
                message=f"{len(found)} finding{'s' if len(found) > 1 else ''}",
            )  # fmt: skip
            failure.text = "\n".join(
                f"{path}:{r['line']}:{r['column']}: {r['code']} {r['severity']} {r['message']}"
                for r in found
            )
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, "unicode") + "\n"


def statistics(records: Sequence[dict[str, Any]], out: TextIO) -> None:
    """``--statistics``: how many findings each rule has, the most first, as ruff prints."""
    counts = Counter(r["code"] for r in records)
    width = len(str(max(counts.values(), default=0)))
    for code, count in sorted(counts.items(), key=lambda item: (-item[1], item[0])):
        info = RULES.get(code)
        name = "" if info is None else info.name
        out.write(f"{count:>{width}}\t{code}\t{name}\n")


# ANSI styles of the text form (SGR codes), by severity.
_STYLES = MappingProxyType({"error": "31;1", "warning": "33;1", "information": "36", "hint": "2"})


def use_colour(choice: str, out: TextIO) -> bool:
    """``--color``: always, never, or auto: on a terminal unless NO_COLOR is set (no-color.org)
    or TERM is dumb."""
    if choice != "auto":
        return choice == "always"
    if os.environ.get("NO_COLOR") or os.environ.get("TERM") == "dumb":
        return False
    return out.isatty()


# The severities said in words (``rule``'s documentation). The text form of ``check`` keeps
# the English keyword, as the code, whatever the language: the editor's check task finds the
# findings in it by that keyword (package.json's problem matcher), and so may other tools.
SEVERITY_WORDS = MappingProxyType(
    {
        "error": tr("error"),
        "warning": tr("warning"),
        "information": tr("information"),
        "hint": tr("hint"),
    }
)


def text_line(path: str, finding: dict[str, Any], colour: bool, message: str | None = None) -> str:
    """``PATH:LINE:COLUMN: CODE severity message``, the place bold and the code in its
    severity's colour when ``colour``; the message (``message``, else the finding's) in the
    command line's language, the severity its keyword (see ``SEVERITY_WORDS``)."""
    place = f"{path}:{finding['line']}:{finding['column']}:"
    head = f"{finding['code']} {finding['severity']}"
    if colour:
        place = f"\x1b[1m{place}\x1b[0m"
        head = f"\x1b[{_STYLES[finding['severity']]}m{head}\x1b[0m"
    shown = said(finding["message"]) if message is None else message
    return f"{place} {head} {shown}\n"
