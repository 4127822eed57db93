"""Snapshots of every diagnostic of each fixture program, in tests/snapshots/.

    python3 scripts/snapshots.py            # exits 1, with a diff, if a snapshot is stale
    python3 scripts/snapshots.py --update   # rewrites the snapshots from the analysis

Each program under tests/fixtures/ has ``tests/snapshots/<its path under fixtures>.txt``: every
diagnostic the analysis gives it, with its code, severity, message, range, related places, fixes
(title and edits) and tags. The analysis is the front ends' (a ``Workspace`` holding the file
alone, read from its bytes), with the settings of the file's ``(settings: {...})`` comments, as
tests/test_rules.py reads them. tests/test_snapshots.py compares; review a rewrite in the diff.
The package is read from this checkout's server/, whatever is installed.
"""

from __future__ import annotations

import argparse
import difflib
import json
import re
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures"
SNAPSHOTS = ROOT / "tests" / "snapshots"
SETTINGS = re.compile(r"\(settings:([^)]*)\)")

if TYPE_CHECKING:
    from fanuc_macro.diagnostics import Diagnostic


def _import_package() -> None:
    server = str(ROOT / "server")
    if server not in sys.path:
        sys.path.insert(0, server)


def fixture_programs() -> list[Path]:
    """Every fixture program, in path order."""
    return sorted(p for p in FIXTURES.rglob("*.nc") if p.is_file())


def snapshot_path(fixture: Path) -> Path:
    return SNAPSHOTS / f"{fixture.relative_to(FIXTURES).as_posix()}.txt"


def fixture_settings(data: bytes) -> dict[str, object]:
    """The editor settings a fixture's ``(settings: {...})`` comments give (tests/test_rules.py
    reads them the same way)."""
    _import_package()
    from fanuc_macro.syntax.lines import decode_bytes, split_lines

    settings: dict[str, object] = {}
    for line_text in split_lines(decode_bytes(data).text):
        for m in SETTINGS.finditer(line_text):
            settings.update(json.loads(m.group(1)))
    return settings


def diagnostics_of(fixture: Path) -> list[Diagnostic]:
    """The diagnostics a front end gets for the fixture, alone in its workspace."""
    _import_package()
    from fanuc_macro.config import Config
    from fanuc_macro.workspace import Workspace

    data = fixture.read_bytes()
    settings = fixture_settings(data)
    workspace = Workspace(Config.from_settings(settings) if settings else None)
    uri = fixture.relative_to(ROOT).as_posix()
    workspace.add_bytes(uri, data)
    return workspace.analyse(uri).diagnostics


def _place(line: int, column: int, end_line: int, end_column: int) -> str:
    return f"{line + 1}:{column + 1}-{end_line + 1}:{end_column + 1}"


def _text(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)


def render(fixture: Path, diagnostics: Iterable[Diagnostic]) -> str:
    """The snapshot text of a fixture's diagnostics."""
    diags = list(diagnostics)
    lines = [
        f"# {fixture.relative_to(ROOT).as_posix()}: {len(diags)} "
        + ("diagnostic" if len(diags) == 1 else "diagnostics"),
        "# line:column-end line:end column, from 1, the end after the last character",
    ]
    for d in diags:
        lines.append("")
        lines.append(
            f"{_place(d.line, d.column, d.end_line, d.end_column)} {d.code} {d.severity.value}"
        )
        lines.append(f"  message {_text(d.message)}")
        for r in d.related:
            where = f" in {r.uri}" if r.uri is not None else ""
            lines.append(
                f"  related {_place(r.line, r.column, r.line, r.end_column)}{where} "
                f"{_text(r.message)}"
            )
        for fix in d.fixes:
            preferred = " (preferred)" if fix.preferred else ""
            lines.append(f"  fix {_text(fix.title)}{preferred}")
            for e in fix.edits:
                place = _place(e.line, e.column, e.end_line, e.end_column)
                lines.append(f"    edit {place} {_text(e.text)}")
        if d.tags:
            lines.append("  tags " + " ".join(sorted(tag.value for tag in d.tags)))
    return "\n".join(lines) + "\n"


def snapshot_diff(fixture: Path, text: str) -> str:
    """The unified diff from the fixture's saved snapshot to ``text``; empty when equal."""
    path = snapshot_path(fixture)
    saved = path.read_text("utf-8") if path.exists() else ""
    if saved == text:
        return ""
    name = path.relative_to(ROOT).as_posix()
    diff = difflib.unified_diff(
        saved.splitlines(keepends=True),
        text.splitlines(keepends=True),
        name if path.exists() else "/dev/null",
        f"{name} (as analysed now)",
        n=2,
    )
    return "".join(diff)


def stale_snapshots() -> list[Path]:
    """Snapshot files of no fixture program."""
    wanted = {snapshot_path(p) for p in fixture_programs()}
    return sorted(p for p in SNAPSHOTS.rglob("*.txt") if p not in wanted)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--update", action="store_true", help="rewrite the snapshots that differ, remove stale ones"
    )
    args = parser.parse_args(argv)
    differ = 0
    for fixture in fixture_programs():
        text = render(fixture, diagnostics_of(fixture))
        diff = snapshot_diff(fixture, text)
        if not diff:
            continue
        differ += 1
        path = snapshot_path(fixture)
        if args.update:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, "utf-8")
            print(f"wrote {path.relative_to(ROOT)}")
        else:
            sys.stderr.write(diff)
    for path in stale_snapshots():
        differ += 1
        if args.update:
            path.unlink()
            print(f"removed {path.relative_to(ROOT)}")
        else:
            print(f"{path.relative_to(ROOT)}: no fixture program", file=sys.stderr)
    if differ and not args.update:
        print(
            f"{differ} snapshots differ from the analysis: review, then run "
            "`python3 scripts/snapshots.py --update` and commit tests/snapshots/",
            file=sys.stderr,
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
