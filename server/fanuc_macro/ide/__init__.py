"""Editor features without a protocol: plain data that every front end (the language server,
the command line) converts (see ARCHITECTURE.md).

The front ends import this package, never its modules: the names below are its public API.
Each name loads its module when first read, so that a start of the language server or a check
loads only what it uses.

- :mod:`.data`: the results (positions in code points, ranges, markdown, edits, locations,
  symbols, completion items, code actions);
- :mod:`.view`: one analysed document with the workspace around it, what the features read;
- :mod:`.locate`: what is under the cursor in a block;
- :mod:`.values`: values and variables in words;
- :mod:`.hover`, :mod:`.inlay`, :mod:`.navigation` (definition, references, symbols),
  :mod:`.completion`, :mod:`.actions`, :mod:`.semantic` (semantic tokens, their kinds in
  :mod:`.token_legend`), :mod:`.signature`, :mod:`.lenses`: the features;
- :mod:`.trace`, :mod:`.toolpath_view`, :mod:`.plot`: the motions a program executes;
  :mod:`.trace_view`: the trace view's text;
- :mod:`.formatting`, :mod:`.renumber`: blocks and labels rewritten; :mod:`.fixing`: the
  rules' quick fixes applied to a file;
- :mod:`.number_uses`, :mod:`.rename`, :mod:`.highlight`, :mod:`.calls`, :mod:`.ranges`,
  :mod:`.workspace_symbols`: navigation by number, ranges and symbols;
- :mod:`.messages`: the server's words in other languages; :mod:`.controllers`: the controllers
  an editor offers, and the machine a document was read as; :mod:`.variable_at`: the variable
  under the mouse;
  :mod:`.thread_completion`: a generated thread module fitted into the user's program.
"""

from __future__ import annotations

import importlib
import sys
from types import MappingProxyType, ModuleType
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .actions import code_actions as code_actions
    from .calls import CallItem as CallItem
    from .calls import incoming_calls as incoming_calls
    from .calls import outgoing_calls as outgoing_calls
    from .calls import prepare_call_hierarchy as prepare_call_hierarchy
    from .completion import completion as completion
    from .controllers import DEFAULT_CONTROLLER as DEFAULT_CONTROLLER
    from .controllers import DocumentMachine as DocumentMachine
    from .controllers import controller_choices as controller_choices
    from .controllers import document_machine as document_machine
    from .controllers import machine_text as machine_text
    from .data import ActionKind as ActionKind
    from .data import CodeAction as CodeAction
    from .data import CompletionItem as CompletionItem
    from .data import CompletionKind as CompletionKind
    from .data import Location as Location
    from .data import Position as Position
    from .data import Problem as Problem
    from .data import Range as Range
    from .data import Symbol as Symbol
    from .data import SymbolKind as SymbolKind
    from .data import TextEdit as TextEdit
    from .fixing import Fixed as Fixed
    from .fixing import fix_file as fix_file
    from .fixing import unified_diff as unified_diff
    from .formatting import CannotFormat as CannotFormat
    from .formatting import FormatOptions as FormatOptions
    from .formatting import format_document as format_document
    from .formatting import format_file as format_file
    from .formatting import format_lines as format_lines
    from .highlight import HighlightKind as HighlightKind
    from .highlight import highlights as highlights
    from .hover import hover as hover
    from .inlay import inlay_hints as inlay_hints
    from .lenses import code_lenses as code_lenses
    from .messages import Catalogue as Catalogue
    from .messages import catalogue as catalogue
    from .navigation import definition as definition
    from .navigation import document_symbols as document_symbols
    from .navigation import references as references
    from .plot import NothingToPlot as NothingToPlot
    from .plot import backplot as backplot
    from .plot import pass_maps as pass_maps
    from .plot import run_plot as run_plot
    from .ranges import FoldKind as FoldKind
    from .ranges import folding_ranges as folding_ranges
    from .ranges import selection_ranges as selection_ranges
    from .rename import Refusal as Refusal
    from .rename import prepare_rename as prepare_rename
    from .rename import rename as rename
    from .renumber import renumber_labels as renumber_labels
    from .semantic import SemanticToken as SemanticToken
    from .semantic import semantic_tokens as semantic_tokens
    from .signature import signature_help as signature_help
    from .token_legend import TOKEN_MODIFIERS as TOKEN_MODIFIERS
    from .token_legend import TOKEN_TYPES as TOKEN_TYPES
    from .toolpath_view import NoToolpathView as NoToolpathView
    from .toolpath_view import ToolpathViewData as ToolpathViewData
    from .toolpath_view import toolpath_view as toolpath_view
    from .trace import MOVE_NAMES as MOVE_NAMES
    from .trace import Trace as Trace
    from .trace import TraceMotion as TraceMotion
    from .trace import cycle_time_text as cycle_time_text
    from .trace import motion_text as motion_text
    from .trace import trace as trace
    from .trace_view import TraceView as TraceView
    from .trace_view import view_of_trace as view_of_trace
    from .values import Precision as Precision
    from .variable_at import variable_at as variable_at
    from .view import Indexed as Indexed
    from .view import View as View
    from .workspace_symbols import workspace_symbols as workspace_symbols

# The public API: each name and the module that defines it (the imports above, for the type
# checker; a test keeps the two the same).
PUBLIC: MappingProxyType[str, str] = MappingProxyType(
    {
        "code_actions": "actions",
        "CallItem": "calls",
        "incoming_calls": "calls",
        "outgoing_calls": "calls",
        "prepare_call_hierarchy": "calls",
        "completion": "completion",
        "ActionKind": "data",
        "CodeAction": "data",
        "CompletionItem": "data",
        "CompletionKind": "data",
        "Location": "data",
        "Position": "data",
        "Problem": "data",
        "Range": "data",
        "Symbol": "data",
        "SymbolKind": "data",
        "TextEdit": "data",
        "Fixed": "fixing",
        "fix_file": "fixing",
        "unified_diff": "fixing",
        "CannotFormat": "formatting",
        "FormatOptions": "formatting",
        "format_document": "formatting",
        "format_file": "formatting",
        "format_lines": "formatting",
        "HighlightKind": "highlight",
        "highlights": "highlight",
        "hover": "hover",
        "inlay_hints": "inlay",
        "code_lenses": "lenses",
        "Catalogue": "messages",
        "catalogue": "messages",
        "definition": "navigation",
        "document_symbols": "navigation",
        "references": "navigation",
        "NothingToPlot": "plot",
        "backplot": "plot",
        "pass_maps": "plot",
        "run_plot": "plot",
        "FoldKind": "ranges",
        "folding_ranges": "ranges",
        "selection_ranges": "ranges",
        "Refusal": "rename",
        "prepare_rename": "rename",
        "rename": "rename",
        "renumber_labels": "renumber",
        "SemanticToken": "semantic",
        "semantic_tokens": "semantic",
        "signature_help": "signature",
        "TOKEN_MODIFIERS": "token_legend",
        "TOKEN_TYPES": "token_legend",
        "NoToolpathView": "toolpath_view",
        "ToolpathViewData": "toolpath_view",
        "toolpath_view": "toolpath_view",
        "Trace": "trace",
        "TraceMotion": "trace",
        "cycle_time_text": "trace",
        "MOVE_NAMES": "trace",
        "motion_text": "trace",
        "trace": "trace",
        "TraceView": "trace_view",
        "view_of_trace": "trace_view",
        "DEFAULT_CONTROLLER": "controllers",
        "DocumentMachine": "controllers",
        "controller_choices": "controllers",
        "machine_text": "controllers",
        "document_machine": "controllers",
        "Precision": "values",
        "variable_at": "variable_at",
        "Indexed": "view",
        "View": "view",
        "workspace_symbols": "workspace_symbols",
    }
)


class _Facade(ModuleType):
    """This package as its importers see it. A public name loads its module when first read.
    The import system binds a module loaded later to its package's attribute of the same name
    (``hover``, ``trace``): that binding is skipped, so the name keeps meaning the function."""

    def __getattr__(self, name: str) -> object:
        module = PUBLIC.get(name)
        if module is None:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
        value: object = getattr(importlib.import_module(f"{__name__}.{module}"), name)
        ModuleType.__setattr__(self, name, value)
        return value

    def __setattr__(self, name: str, value: object) -> None:
        if name in PUBLIC and isinstance(value, ModuleType):
            return
        ModuleType.__setattr__(self, name, value)


sys.modules[__name__].__class__ = _Facade
