"""The checker's warnings and notes on ``../shared/corpus``, analysed as one workspace.

``tests/test_corpus_findings.py`` compares them with the table of findings judged by hand.
Run this module to print what the checker finds now, as rows to judge:

    python3 tests/corpus_findings.py > /tmp/rows.txt

The files are others' programs: they are read from ../shared, never copied here.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

from fanuc_macro.diagnostics import Severity
from fanuc_macro.workspace import Workspace

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus"
JUDGED = (Severity.WARNING, Severity.INFORMATION, Severity.HINT)


@dataclass(frozen=True)
class Finding:
    file: str
    line: int  # 1-based
    code: str
    severity: Severity
    message: str


def corpus_files() -> list[Path]:
    return sorted(p for p in CORPUS.iterdir() if p.is_file() and p.suffix not in (".md", ".tsv"))


def corpus_findings() -> list[Finding]:
    """Every warning, information and hint on the corpus, each file known to the others."""
    files = corpus_files()
    workspace = Workspace()
    for path in files:
        workspace.add_bytes(path.name, path.read_bytes())
    programs = workspace.program_numbers()
    found: list[Finding] = []
    for path in files:
        analysis = workspace.analyse(path.name, workspace_programs=programs)
        for d in analysis.diagnostics:
            if d.severity in JUDGED:
                found.append(Finding(path.name, d.line + 1, d.code, d.severity, d.message))
    return found


def main() -> None:
    current = ""
    for f in corpus_findings():
        if f.file != current:
            current = f.file
            print(f"    {f.file!r}: [")
        print(f"        ({f.line}, {f.code!r}, True, ''),  # {f.severity.value}: {f.message}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
