"""Writes docs/rules.md from docs/rules-intro.md and the documentation beside each rule.

    python3 scripts/rules_doc.py          # writes docs/rules.md and docs/rules.zh-cn.md
    python3 scripts/rules_doc.py --check  # exits 1, saying so, if one of them is stale

Each rule's documentation is a ``RuleDoc`` constant (``MB101_DOC``) beside the function that
finds the rule in server/fanuc_macro/rules/ (MB000 in analysis.py); the general sections are
docs/rules-intro.md. docs/rules.zh-cn.md is the same page in Chinese, from the ``rules_doc``
catalogue (server/fanuc_macro/data/locale/zh_CN/LC_MESSAGES/rules_doc.po, kept in step by
scripts/catalogues.py), in English where a text is not translated yet.
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
# Each page and its locale.
PAGES = {OUTPUT: "en", ROOT / "docs" / "rules.zh-cn.md": "zh-cn"}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--check", action="store_true", help="do not write: exit 1 if a page is stale"
    )
    parser.add_argument(
        "--output", type=Path, help="write or check only this file (the page of --locale)"
    )
    parser.add_argument(
        "--locale", default="en", help="the language of --output's page (en, zh-cn)"
    )
    args = parser.parse_args(argv)
    sys.path.insert(0, str(ROOT / "server"))
    from fanuc_macro.rules_doc import render

    intro = INTRO.read_text("utf-8")
    pages: dict[Path, str] = PAGES if args.output is None else {args.output: args.locale}
    stale = 0
    for output, locale in pages.items():
        text = render(intro, locale)
        current = output.read_text("utf-8") if output.exists() else ""
        if current == text:
            continue
        if args.check:
            stale += 1
            report_stale(output, current, text)
        else:
            output.write_text(text, "utf-8")
            print(f"wrote {output}")
    return 1 if stale else 0


def report_stale(output: Path, current: str, text: str) -> None:
    diff = difflib.unified_diff(
        current.splitlines(keepends=True),
        text.splitlines(keepends=True),
        str(output),
        f"{output} as generated",
        n=1,
    )
    sys.stderr.writelines(list(diff)[:60])
    print(
        f"{output} is stale: it is generated from docs/rules-intro.md, the RuleDoc beside "
        "each rule and the rules_doc catalogue; run `python3 scripts/rules_doc.py` and commit "
        "the result",
        file=sys.stderr,
    )


if __name__ == "__main__":
    sys.exit(main())
