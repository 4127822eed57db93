"""Every fixture program's diagnostics, as the front ends get them, against their snapshot.

Each program under tests/fixtures/ has a snapshot in tests/snapshots/ (the same path, ``.txt``
added): every diagnostic's code, severity, message, range, related places, fixes (title and
edits) and tags. A change of any of them fails here with the diff. When the change is meant,
rewrite the snapshots with one command and review them in the commit's diff:

    python3 scripts/snapshots.py --update

(``python3 scripts/snapshots.py`` alone prints the diffs and exits 1 when a snapshot is stale.)
The analysis is a ``Workspace`` holding the file alone, read from its bytes, with the settings
of its ``(settings: {...})`` comments, as tests/test_rules.py uses them.
"""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import replace
from pathlib import Path
from types import ModuleType

import pytest

from fanuc_macro.diagnostics import Tag

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "snapshots.py"


def _load_script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("snapshots_script", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses and annotations look the module up
    spec.loader.exec_module(module)
    return module


snapshots = _load_script()
PROGRAMS: list[Path] = snapshots.fixture_programs()


def test_every_fixture_program_is_covered() -> None:
    assert len(PROGRAMS) >= 100
    assert all(p.is_relative_to(ROOT / "tests" / "fixtures") for p in PROGRAMS)


def test_no_snapshot_without_its_fixture() -> None:
    stale = [p.relative_to(ROOT).as_posix() for p in snapshots.stale_snapshots()]
    assert not stale, f"snapshots of no fixture program (remove them with --update): {stale}"


@pytest.mark.parametrize("fixture", PROGRAMS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_snapshot(fixture: Path) -> None:
    text = snapshots.render(fixture, snapshots.diagnostics_of(fixture))
    diff = snapshots.snapshot_diff(fixture, text)
    assert not diff, (
        f"the diagnostics of {fixture.relative_to(ROOT)} are not its snapshot; if the change is "
        f"meant, run `python3 scripts/snapshots.py --update` and review the diff:\n{diff}"
    )


@pytest.mark.parametrize("part", ["message", "range", "fix", "tags"])
def test_a_change_of_any_part_fails(part: str) -> None:
    """The comparison sees a change of a message, a range, a fix or a tag."""
    fixture = ROOT / "tests" / "fixtures" / "rules" / "MB101_goto-missing-label.nc"
    diags = snapshots.diagnostics_of(fixture)
    assert snapshots.snapshot_diff(fixture, snapshots.render(fixture, diags)) == ""
    first = diags[0]
    assert first.fixes, "the fixture's first MB101 has a fix"
    changed = {
        "message": replace(first, message=first.message + "!"),
        "range": replace(first, end_column=first.end_column + 1),
        "fix": replace(first, fixes=(replace(first.fixes[0], title="other"),)),
        "tags": replace(first, tags=frozenset({Tag.UNNECESSARY})),
    }[part]
    diff = snapshots.snapshot_diff(fixture, snapshots.render(fixture, [changed, *diags[1:]]))
    changed_lines = [
        line
        for line in diff.splitlines()
        if line[:1] in "+-" and not line.startswith(("+++", "---"))
    ]
    assert changed_lines, diff
