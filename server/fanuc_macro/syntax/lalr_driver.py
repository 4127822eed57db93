"""A lean LALR(1) driver over the tables Lark has already built for a grammar.

Lark's general machinery (lexer thread, line counter, per-token ``ParserState.feed_token``) costs
most of the time of a one-line parse. :class:`TableParser` keeps everything Lark computed — the
parse table, the terminal definitions and the callbacks built from the transformer — and runs
them with compiled master regexes and one flat shift/reduce loop. It returns what
``lark.parse(code)`` returns and raises the same exception classes with the same data
(``UnexpectedToken.state`` and ``.interactive_parser`` are left ``None``).

Only what :mod:`fanuc_macro.syntax.parser` uses is supported: ``parser="lalr"``,
``lexer="basic"``, a ``str`` input, no ``postlex``, no ``lexer_callbacks``, no ``use_bytes``.
"""

from __future__ import annotations

import importlib
import re
import sys
from collections.abc import Callable, Collection, Iterable, Mapping
from functools import partial
from typing import Any

from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedToken
from lark.lexer import PatternRE, PatternStr, TerminalDef
from lark.parse_tree_builder import ExpandSingleChild
from lark.parsers.lalr_analysis import Shift

__all__ = ["TableParser"]

_Callback = Callable[[list[Any]], Any]
_Match = Callable[[str, int], Any]
# A reduction: (2 * arity = its length on the parse stack, nonterminal to go to, callback,
# unit chain or None). A unit chain maps the state under the top one to the state reached after
# a run of one-child `?rule` reductions that return their child unchanged: one step for the run.
_Rule = tuple[int, str, _Callback, dict[int, int] | None]

_END = "$END"
_ASCII = frozenset(chr(i) for i in range(128))
_new_str = str.__new__


def _children(children: list[Any]) -> Any:
    """The value of a reduction when Lark built no callbacks (no tree, no transformer)."""
    return children


def _only_child(children: list[Any]) -> Any:
    """ExpandSingleChild with one child: the child itself."""
    return children[0]


def _has_newline(regexp: str) -> bool:
    """Lark's test of whether a terminal may span lines (only those update the line count)."""
    return (
        "\n" in regexp
        or "\\n" in regexp
        or "\\s" in regexp
        or "[^" in regexp
        or ("(?s" in regexp and "." in regexp)
    )


def _order_key(term: TerminalDef) -> tuple[int, int, int, str]:
    # The order BasicLexer tries terminals in: priority, then longest possible match.
    return (-term.priority, -term.pattern.max_width, -len(term.pattern.value), term.name)


# ---- first characters of a regex (to split the master regex by the next input character)
#
# A regex alternation is tried branch by branch, so one master regex of 35 terminals spends
# most of its time failing branches. Each ASCII character gets its own master regex holding
# only the terminals that can start with it, in Lark's order: the first branch that matches is
# the same. The analysis may say "any" (None) when unsure; that only costs speed.


def _re_module(new: str, old: str) -> Any:
    """``re._parser`` / ``re._constants`` since Python 3.11, ``sre_parse`` before."""
    try:
        return importlib.import_module(new)
    except ImportError:
        return importlib.import_module(old)


_sre: Any = _re_module("re._parser", "sre_parse")
_sc: Any = _re_module("re._constants", "sre_constants")
# Python 3.11 added these two opcodes; on 3.10 no pattern can contain them.
_POSSESSIVE_REPEAT: Any = getattr(_sc, "POSSESSIVE_REPEAT", object())
_ATOMIC_GROUP: Any = getattr(_sc, "ATOMIC_GROUP", object())


def _class_first(items: Iterable[tuple[Any, Any]], ignorecase: bool) -> frozenset[str] | None:
    """ASCII characters a character class [...] accepts, or None if unsure."""
    negate = False
    members: set[str] = set()
    for op, av in items:
        if op is _sc.NEGATE:
            negate = True
        elif op is _sc.LITERAL:
            if av >= 128 and ignorecase:
                return None  # e.g. KELVIN SIGN matches "k" when case is ignored
            members.add(chr(av))
        elif op is _sc.RANGE:
            lo, hi = av
            if hi >= 128 and ignorecase:
                return None
            members.update(chr(c) for c in range(lo, min(hi, 127) + 1))
        else:  # categories (\d, \s, \w) and the rest: not worth modelling
            return None
    if ignorecase:
        if negate:
            return None
        members |= {c.swapcase() for c in members}
    found = frozenset(members) & _ASCII
    return _ASCII - found if negate else found


def _seq_first(items: Iterable[tuple[Any, Any]], flags: int) -> tuple[frozenset[str] | None, bool]:
    """(ASCII characters a match can start with or None if unsure, can it match empty)."""
    first: set[str] = set()
    for op, av in items:
        ignorecase = bool(flags & _sc.SRE_FLAG_IGNORECASE)
        part: frozenset[str] | None
        nullable = False
        if op is _sc.LITERAL:
            ch = chr(av)
            if av >= 128:
                part = None if ignorecase else frozenset()
            else:
                part = frozenset({ch, ch.swapcase()}) if ignorecase else frozenset(ch)
        elif op is _sc.IN:
            part = _class_first(av, ignorecase)
        elif op is _sc.BRANCH:
            part, nullable = frozenset(), False
            for alt in av[1]:
                alt_first, alt_nullable = _seq_first(alt, flags)
                if alt_first is None:
                    return None, False
                part |= alt_first
                nullable = nullable or alt_nullable
        elif op is _sc.SUBPATTERN:
            _group, add_flags, del_flags, sub = av
            part, nullable = _seq_first(sub, (flags | add_flags) & ~del_flags)
        elif op in (_sc.MAX_REPEAT, _sc.MIN_REPEAT, _POSSESSIVE_REPEAT):
            low, _high, sub = av
            part, nullable = _seq_first(sub, flags)
            nullable = nullable or low == 0
        elif op is _ATOMIC_GROUP:
            part, nullable = _seq_first(av, flags)
        elif op in (_sc.AT, _sc.ASSERT, _sc.ASSERT_NOT):
            part, nullable = frozenset(), True  # zero width: the next item decides
        else:  # ANY, NOT_LITERAL, group references, ...
            return None, False
        if part is None:
            return None, False
        first |= part
        if not nullable:
            return frozenset(first), False
    return frozenset(first), True


def _regex_first(regexp: str, flags: int) -> frozenset[str] | None:
    try:
        parsed = _sre.parse(regexp, flags)
    except Exception:  # a syntax this analysis does not know: stay correct, just slower
        return None
    first, nullable = _seq_first(parsed, parsed.state.flags)
    return None if nullable else first


class TableParser:
    """Parses one text with the tables of a ``Lark(parser="lalr", lexer="basic")`` object.

    ``parse`` keeps all its state in locals, so one instance serves several threads.
    """

    def __init__(self, lark: Lark, start: str | None = None) -> None:
        frontend: Any = lark.parser  # lark.parser_frontends.ParsingFrontend
        conf: Any = lark.lexer_conf
        if lark.options.parser != "lalr" or conf.lexer_type != "basic":
            raise ValueError("TableParser needs parser='lalr' and lexer='basic'")
        if conf.postlex is not None or conf.callbacks or conf.use_bytes:
            raise ValueError("TableParser supports neither postlex, lexer_callbacks nor use_bytes")
        starts: list[str] = list(frontend.parser_conf.start)
        if start is None:
            if len(starts) != 1:
                raise ValueError(f"several start rules, choose one of {starts}")
            start = starts[0]
        lalr: Any = frontend.parser.parser  # lark.parsers.lalr_parser._Parser
        self._build_lexer(conf)
        self._build_parser(lalr.parse_table, lalr.callbacks, start)

    # ---- set-up: lexer

    def _build_lexer(self, conf: Any) -> None:
        re_module: Any = conf.re_module
        flags: int = conf.g_regex_flags
        terminals = sorted(conf.terminals, key=_order_key)
        # A string terminal that a regex terminal of the same priority also matches is found
        # through the regex and then renamed (Lark's "unless" rule, e.g. keywords vs. NAME).
        embedded: set[str] = set()
        retype: dict[str, Any] = {}
        strings = [t for t in terminals if isinstance(t.pattern, PatternStr)]
        for term in terminals:
            if not isinstance(term.pattern, PatternRE):
                continue
            regexp = term.pattern.to_regexp()
            unless: list[TerminalDef] = []
            for stok in strings:
                if stok.priority != term.priority:
                    continue
                m = re_module.match(regexp, stok.pattern.value, flags)
                if m is not None and m.group(0) == stok.pattern.value:
                    unless.append(stok)
                    if stok.pattern.flags <= term.pattern.flags:
                        embedded.add(stok.name)
            if unless:
                retype[term.name] = re_module.compile(_alternation(unless), flags)
        scanned = [t for t in terminals if t.name not in embedded]

        def compile_match(terms: list[TerminalDef]) -> _Match:
            regexp = _alternation(terms) if terms else "(?!)"  # "(?!)" matches nothing
            match: _Match = re_module.compile(regexp, flags).match
            return match

        def install_master(match: _Match) -> None:
            self._master_match = match

        self._master_match = _on_first_use(partial(compile_match, scanned), install_master)
        # Per ASCII character: the terminal's name when the first terminal that can start with
        # it is that very character as a literal (it always wins: the alternation takes the
        # first branch that matches), else a master regex of just the terminals that can.
        singles: dict[str, str] = {}
        scanners: dict[str, _Match] = {}
        ignore = frozenset(conf.ignore)
        if re_module is re:  # the analysis reads the syntax of the standard re module
            firsts = [_regex_first(t.pattern.to_regexp(), flags) for t in scanned]
            chars_of: dict[tuple[int, ...], list[str]] = {}
            for ch in sorted(_ASCII):
                subset = tuple(i for i, f in enumerate(firsts) if f is None or ch in f)
                if subset:
                    head = scanned[subset[0]]
                    if head.name not in ignore and _is_char_literal(head, ch, flags):
                        singles[ch] = sys.intern(head.name)
                        continue
                chars_of.setdefault(subset, []).append(ch)

            # A scanner's regex is compiled when a text first needs it (a short program meets a
            # few of the 20): the first call puts the compiled one in place for all its chars.
            def install(chars: list[str], match: _Match) -> None:
                for ch in chars:
                    scanners[ch] = match

            for subset, chars in chars_of.items():
                terms = [scanned[i] for i in subset]
                lazy = _on_first_use(partial(compile_match, terms), partial(install, chars))
                for ch in chars:
                    scanners[ch] = lazy
        self._singles = singles
        self._scanners = scanners
        self._scanned_names = tuple(t.name for t in scanned)  # for tests: Lark's order
        self._retype: Mapping[str, Any] = retype
        self._ignore = ignore
        self._newline_types = frozenset(
            t.name for t in conf.terminals if _has_newline(t.pattern.to_regexp())
        )
        allowed = {t.name for t in scanned} - self._ignore
        self._allowed = frozenset(allowed or {"<END-OF-FILE>"})
        self._terminals_by_name: dict[str, TerminalDef] = conf.terminals_by_name

    # ---- set-up: parser

    def _build_parser(self, table: Any, callbacks: Mapping[Any, Any], start: str) -> None:
        lark_states: Mapping[int, Mapping[Any, tuple[Any, Any]]] = table.states
        if sorted(lark_states) != list(range(len(lark_states))):
            raise ValueError("expected Lark's IntParseTable (states numbered 0..n-1)")
        self._start_state: int = table.start_states[start]
        self._end_state: int = table.end_states[start]
        rule_index: dict[Any, int] = {}
        rules: list[_Rule] = []
        passes_child: list[bool] = []
        # Actions become ints: a shift (or goto) is the target state, a reduce is ~rule index.
        rows: list[dict[str, int]] = []
        for state in range(len(lark_states)):
            row: dict[str, int] = {}
            for name, (action, arg) in lark_states[state].items():
                # Lark's names are often Token objects; plain str keys keep lookups in C
                # (Token.__eq__ is Python code).
                symbol = sys.intern(str(name))
                if action is Shift:
                    row[symbol] = arg
                    continue
                index = rule_index.get(arg)
                if index is None:
                    index = rule_index[arg] = len(rules)
                    entry, passes = _rule_entry(arg, callbacks)
                    rules.append(entry)
                    passes_child.append(passes)
                row[symbol] = ~index
            rows.append(row)
        # What Lark's feed_token reports: the state's terminals (nonterminals are lowercase).
        self._expected = tuple(frozenset(s for s in row if s.isupper()) for row in rows)
        self._fold_unit_chains(rows, rules, passes_child)
        self._rows = tuple(rows)
        self._rules = tuple(rules)
        # Lark also calls a transformer method named after a terminal on each shifted token.
        self._token_callbacks: dict[str, Callable[[Token], Any]] = {
            sys.intern(str(k)): v for k, v in callbacks.items() if isinstance(k, str)
        }

    def _fold_unit_chains(
        self, rows: list[dict[str, int]], rules: list[_Rule], passes_child: list[bool]
    ) -> None:
        """Replace each terminal's pass-through reduce by one entry with its whole chain.

        The state reached after reducing a one-symbol rule is goto(state below, rule), and the
        state below does not change along a chain of them; so the chain's end is a function of
        (state below, top state, lookahead), computed here for every possible state below.
        """
        below: list[set[int]] = [set() for _ in rows]
        for state, row in enumerate(rows):
            for action in row.values():
                if action >= 0:
                    below[action].add(state)
        folded: list[tuple[int, str, dict[int, int]]] = []
        for top, row in enumerate(rows):
            for kind, action in row.items():
                if action >= 0 or not passes_child[~action] or not kind.isupper():
                    continue
                chain: dict[int, int] = {}
                for under in below[top]:
                    end = _chain_end(rows, rules, passes_child, under, top, kind, self._end_state)
                    if end is None:
                        break  # leave this one to the general reduce step
                    chain[under] = end
                else:
                    if chain:
                        folded.append((top, kind, chain))
        for top, kind, chain in folded:
            span, origin, callback, _ = rules[~rows[top][kind]]
            rows[top][kind] = ~len(rules)
            rules.append((span, origin, callback, chain))
            passes_child.append(False)

    # ---- parsing

    def parse(self, code: str) -> Any:
        """What ``lark.parse(code)`` returns, or the exception it raises."""
        singles = self._singles
        scanners = self._scanners
        master = self._master_match
        ignore = self._ignore
        retype = self._retype
        token_callbacks = self._token_callbacks
        rows = self._rows
        rules = self._rules
        end_state = self._end_state
        new_str = _new_str
        has_newline = "\n" in code
        newline_types = self._newline_types

        # One stack for both: state, value, state, value, ..., state (the top one is last).
        stack: list[Any] = [self._start_state]
        row = rows[self._start_state]
        pos = 0
        size_text = len(code)
        line = 1
        line_start = 0  # position of the first character of the current line
        last: Token | None = None

        while True:
            # ---- the next token (the basic lexer never depends on the parser state)
            if pos < size_text:
                value = code[pos]
                single = singles.get(value)
                if single is not None:
                    kind = single
                    end = pos + 1
                else:
                    m = scanners.get(value, master)(code, pos)
                    if m is None:
                        raise self._unexpected_characters(
                            code, pos, line, pos - line_start + 1, last
                        )
                    kind = m.lastgroup
                    value = m.group()
                    end = m.end()
                    if kind in ignore:
                        if has_newline and kind in newline_types and "\n" in value:
                            line += value.count("\n")
                            line_start = pos + value.rindex("\n") + 1
                        pos = end
                        continue
                    if retype and kind in retype:
                        full = retype[kind].fullmatch(value)
                        if full is not None:
                            kind = full.lastgroup
                # Filling the slots here skips Token.__new__'s argument handling.
                tok: Token = new_str(Token, value)
                tok.type = kind
                tok.value = value
                tok.start_pos = pos
                tok.end_pos = end
                tok.line = line
                tok.column = pos - line_start + 1
                if has_newline and kind in newline_types and "\n" in value:
                    line += value.count("\n")
                    line_start = pos + value.rindex("\n") + 1
                tok.end_line = line
                tok.end_column = end - line_start + 1
                pos = end
                last = tok
            else:
                kind = _END
            # ---- feed it: reduce as long as the table says so, then shift (or accept)
            while True:
                try:
                    action = row[kind]
                except KeyError:
                    raise self._unexpected_token(stack[-1], kind, last) from None
                if action >= 0:
                    if token_callbacks and kind in token_callbacks:
                        stack.append(token_callbacks[kind](tok))
                    else:
                        stack.append(tok)
                    stack.append(action)
                    row = rows[action]
                    break
                span, origin, callback, chain = rules[~action]
                if chain is not None:
                    goto = chain[stack[-3]]
                    stack[-1] = goto
                    row = rows[goto]
                    continue
                if span:
                    children = stack[-span::2]
                    del stack[-span:]
                else:
                    children = []
                result = callback(children)
                goto = rows[stack[-1]][origin]
                if goto == end_state and kind == _END:
                    return result
                stack.append(result)
                stack.append(goto)
                row = rows[goto]

    # ---- errors, with the data Lark puts in them

    def _unexpected_characters(
        self, code: str, pos: int, line: int, column: int, last: Token | None
    ) -> UnexpectedCharacters:
        return UnexpectedCharacters(  # type: ignore[no-untyped-call]
            code,
            pos,
            line,
            column,
            allowed=set(self._allowed),
            token_history=[last] if last is not None else None,
            terminals_by_name=self._terminals_by_name,
        )

    def _unexpected_token(self, state: int, kind: str, last: Token | None) -> UnexpectedToken:
        token: Token
        if kind != _END:
            assert last is not None
            token = last
        elif last is not None:  # Lark's $END borrows the position of the last token
            token = Token.new_borrow_pos(_END, "", last)
        else:
            token = Token(_END, "", 0, 1, 1)
        expected: Collection[str] = set(self._expected[state])
        return UnexpectedToken(token, expected)  # type: ignore[no-untyped-call]


def _on_first_use(compile_match: Callable[[], _Match], install: Callable[[_Match], None]) -> _Match:
    """A match function that compiles its regex on its first call and has ``install`` put the
    compiled one where the parser looks it up; until then (or in a parse that already holds
    this one) it calls the compiled one itself."""
    compiled: _Match | None = None

    def first_use(code: str, pos: int) -> Any:
        nonlocal compiled
        if compiled is None:
            compiled = compile_match()
            install(compiled)
        return compiled(code, pos)

    return first_use


def _is_char_literal(term: TerminalDef, ch: str, flags: int) -> bool:
    """Does `term` match exactly the one character `ch` (then nothing else can come first)?"""
    pattern = term.pattern
    if not isinstance(pattern, PatternStr) or len(pattern.value) != 1:
        return False
    return re.fullmatch(pattern.to_regexp(), ch, flags) is not None


def _alternation(terms: Iterable[TerminalDef]) -> str:
    return "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terms)


def _rule_entry(rule: Any, callbacks: Mapping[Any, Any]) -> tuple[_Rule, bool]:
    """The reduce entry of a Lark rule, and whether it returns its only child unchanged."""
    size = len(rule.expansion)
    span = 2 * size  # a value and a state per symbol
    origin = sys.intern(str(rule.origin.name))
    if not callbacks:
        return (span, origin, _children, None), False
    callback = callbacks[rule]
    if type(callback) is ExpandSingleChild:
        # ExpandSingleChild (a `?rule` without alias) tests len(children) == 1 on each call;
        # with LALR that length is the arity, so decide it once here.
        if size == 1:
            return (span, origin, _only_child, None), True
        inner: _Callback = callback.node_builder
        return (span, origin, inner, None), False
    return (span, origin, callback, None), False


def _chain_end(
    rows: list[dict[str, int]],
    rules: list[_Rule],
    passes_child: list[bool],
    under: int,
    top: int,
    kind: str,
    end_state: int,
) -> int | None:
    """The top state after the pass-through reductions from `top` on lookahead `kind`.

    None when a step has no goto or reaches the end state (where Lark checks for acceptance).
    """
    action = rows[top][kind]
    for _ in range(len(rows)):  # a chain visits each state at most once
        goto = rows[under].get(rules[~action][1])
        if goto is None or goto == end_state:
            return None
        top = goto
        next_action = rows[top].get(kind)
        if next_action is None or next_action >= 0 or not passes_child[~next_action]:
            return top
        action = next_action
    return None
