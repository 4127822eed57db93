"""``fanuc-macro hover`` and ``fanuc-macro definition``: what the editor answers at a place of a
file, from the same ide layer as the language server. Lines and columns are 1-based, columns
in characters, as editors show them."""

from __future__ import annotations

import argparse
import json
import sys

from ..config import Config
from ..ide import Location, View, definition, hover
from ..translation import tr
from ..workspace import Workspace
from . import EXIT_ERRORS, EXIT_OK, read_one, read_with_files
from .language import said
from .streams import writes_unicode


def _view(args: argparse.Namespace, config: Config) -> View:
    workspace = Workspace(config)
    key = read_one(args.command, workspace, args.file, args.stdin_filename)
    read_with_files(workspace, args.with_files, key)
    documents = {}
    for uri in workspace.uris():
        doc = workspace.document(uri)
        if doc is not None:
            documents[uri] = (doc, workspace.index(uri))
    return View(key, workspace.analyse(key), config, documents)


def _place(location: Location) -> dict[str, object]:
    r = location.range
    return {
        "path": location.key,
        "line": r.start.line + 1,
        "column": r.start.column + 1,
        "end_line": r.end.line + 1,
        "end_column": r.end.column + 1,
    }


def _nothing(args: argparse.Namespace) -> None:
    place = f"{args.file}:{args.line}:{args.column}"
    sys.stderr.write(said(tr("fanuc-macro: nothing there: {place}", place=place)) + "\n")


def _dump(value: object) -> None:
    json.dump(value, sys.stdout, ensure_ascii=not writes_unicode(sys.stdout), indent=1)
    sys.stdout.write("\n")


def cmd_hover(args: argparse.Namespace, config: Config) -> int:
    view = _view(args, config)
    found = hover(view, args.line - 1, args.column - 1)
    if args.format == "json":
        _dump(
            None
            if found is None
            else {**_place(Location(view.key, found.range)), "markdown": found.markdown}
        )
    elif found is not None:
        sys.stdout.write(said(found.markdown) + "\n")
    else:
        _nothing(args)
    return EXIT_OK if found is not None else EXIT_ERRORS


def cmd_definition(args: argparse.Namespace, config: Config) -> int:
    view = _view(args, config)
    found = definition(view, args.line - 1, args.column - 1)
    if args.format == "json":
        _dump([_place(loc) for loc in found])
    else:
        for loc in found:
            start = loc.range.start
            sys.stdout.write(f"{loc.key}:{start.line + 1}:{start.column + 1}\n")
        if not found:
            _nothing(args)
    return EXIT_OK if found else EXIT_ERRORS
