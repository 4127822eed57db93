"""Writes docs/rules.md from docs/rules-intro.md and the documentation beside each rule.

    python3 scripts/rules_doc.py          # writes docs/rules.md
    python3 scripts/rules_doc.py --check  # exits 1, saying so, if docs/rules.md is stale

Each rule's documentation is a ``RuleDoc`` constant (``MB101_DOC``) beside the function that
finds the rule in server/fanuc_macro/rules/ (MB000 in analysis.py); the general sections are
docs/rules-intro.md.
The package is read from this checkout's server/, whatever is installed.
"""

from __future__ import annotations

import argparse
import difflib
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
INTRO = ROOT / "docs" / "rules-intro.md"
OUTPUT = ROOT / "docs" / "rules.md"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--check", action="store_true", help="do not write: exit 1 if docs/rules.md is stale"
    )
    parser.add_argument(
        "--output", type=Path, default=OUTPUT, help="the file to write or check (docs/rules.md)"
    )
    args = parser.parse_args(argv)
    output: Path = args.output
    sys.path.insert(0, str(ROOT / "server"))
    from fanuc_macro.rules_doc import render

    text = render(INTRO.read_text("utf-8"))
    current = output.read_text("utf-8") if output.exists() else ""
    if args.check:
        if current == text:
            return 0
        diff = difflib.unified_diff(
            current.splitlines(keepends=True),
            text.splitlines(keepends=True),
            str(output),
            f"{output} as generated",
            n=1,
        )
        sys.stderr.writelines(list(diff)[:60])
        print(
            f"{output} is stale: it is generated from docs/rules-intro.md and the RuleDoc "
            "beside each rule; run `python3 scripts/rules_doc.py` and commit the result",
            file=sys.stderr,
        )
        return 1
    if current != text:
        output.write_text(text, "utf-8")
        print(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
