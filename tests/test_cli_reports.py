"""The forms CI reads from ``check`` (SARIF validated against SARIF 2.1.0's own schema, GitHub
annotations, JUnit XML), ``--statistics``, colour, and ``fanuc-macro rule``: through the
command line in a subprocess."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from cli_runner import run


def write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


SARIF_PACKAGE = "@microsoft/jest-sarif@1.0.0-beta.0"  # ships SARIF 2.1.0's own JSON Schema
FAULTY = "O1000\n#1=93.82\nM#1\nG97 S5000 M03\nM30\n"


@pytest.fixture(scope="module")
def sarif_schema(tmp_path_factory: pytest.TempPathFactory) -> dict[str, object]:
    """The SARIF 2.1.0 schema (rtm.5, as OASIS published it), from the npm registry."""
    import shutil
    import subprocess
    import tarfile

    if shutil.which("npm") is None:
        pytest.skip("npm is needed to fetch the SARIF schema")
    folder = tmp_path_factory.mktemp("sarif")
    packed = subprocess.run(
        ["npm", "pack", "--silent", SARIF_PACKAGE],
        cwd=folder, capture_output=True, text=True, timeout=300, check=True,
    )  # fmt: skip
    with tarfile.open(folder / packed.stdout.strip().splitlines()[-1]) as archive:
        member = archive.extractfile("package/lib/schemas/sarif-2.1.0-rtm.5.json")
        assert member is not None
        schema: dict[str, object] = json.loads(member.read())
    return schema


def test_sarif_output_is_valid_sarif_with_the_rules_described(
    tmp_path: Path, sarif_schema: dict[str, object]
) -> None:
    write(tmp_path / "o1000.nc", FAULTY)
    result = run(tmp_path, "check", "--format", "sarif", "--max-spindle-speed", "3000", ".")
    assert result.returncode == 1, result.stderr
    log = json.loads(result.stdout)
    jsonschema.Draft4Validator(sarif_schema).validate(log)
    [run_] = log["runs"]
    rules = {r["id"]: r for r in run_["tool"]["driver"]["rules"]}
    assert set(rules) == {"MB601", "MB602"}
    assert rules["MB601"]["name"] == "address-not-integer"
    assert rules["MB601"]["helpUri"].endswith("docs/rules.md#mb601-address-not-integer")
    first = run_["results"][0]
    assert first["ruleId"] == "MB601" and first["level"] == "error"
    location = first["locations"][0]["physicalLocation"]
    assert location["artifactLocation"]["uri"] == "o1000.nc"
    assert location["region"]["startLine"] == 3


def test_github_annotations_and_junit_and_statistics(tmp_path: Path) -> None:
    from xml.etree import ElementTree as ET

    write(tmp_path / "o1000.nc", FAULTY)
    write(tmp_path / "o2000.nc", "O2000\nG00 X1.\nM30\n")
    options = ("--max-spindle-speed", "3000")
    lines = run(tmp_path, "check", "--format", "github", *options, "o1000.nc").stdout.splitlines()
    assert lines[0].startswith("::error file=o1000.nc,line=3,col=")
    assert ",title=MB601 address-not-integer::M gets 93.82" in lines[0]
    assert lines[1].startswith("::warning file=o1000.nc,line=4,")
    report = run(tmp_path, "check", "--format", "junit", *options, "o1000.nc", "o2000.nc").stdout
    suite = ET.fromstring(report).find("testsuite")
    assert suite is not None and suite.get("tests") == "2" and suite.get("failures") == "1"
    cases = {case.get("name"): case for case in suite.iter("testcase")}
    assert cases["o2000.nc"].find("failure") is None
    failure = cases["o1000.nc"].find("failure")
    assert failure is not None and "o1000.nc:3:" in (failure.text or "")
    counted = run(tmp_path, "check", "--statistics", *options, ".").stdout
    assert counted.splitlines() == [
        "1\tMB601\taddress-not-integer",
        "1\tMB602\taddress-out-of-range",
    ]


def test_colour_on_demand_and_never_when_no_color(tmp_path: Path) -> None:
    import os

    write(tmp_path / "o1000.nc", FAULTY)
    coloured = run(tmp_path, "check", "--color", "always", "o1000.nc").stdout
    assert "\x1b[31;1mMB601 error\x1b[0m" in coloured
    assert "\x1b[" not in run(tmp_path, "check", "o1000.nc").stdout  # a pipe: no colour
    os.environ["NO_COLOR"] = "1"
    try:
        assert "\x1b[" not in run(tmp_path, "check", "--color", "auto", "o1000.nc").stdout
    finally:
        del os.environ["NO_COLOR"]


def test_rule_prints_its_documentation_by_code_or_name(tmp_path: Path) -> None:
    by_code = run(tmp_path, "rule", "mb601")
    by_name = run(tmp_path, "rule", "address-not-integer")
    assert by_code.returncode == 0 and by_code.stdout == by_name.stdout
    assert by_code.stdout.startswith("## MB601 address-not-integer\n")
    assert "**How to fix.**" in by_code.stdout
    unknown = run(tmp_path, "rule", "MB60I")
    assert unknown.returncode == 2 and "nearest known one is MB601" in unknown.stderr
