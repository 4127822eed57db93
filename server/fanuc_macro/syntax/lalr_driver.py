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

from lark import Lark, Token, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedToken
from lark.grammar import NonTerminal, Rule, RuleOptions, Terminal
from lark.lexer import PatternRE, PatternStr, TerminalDef
from lark.parse_tree_builder import ExpandSingleChild, ParseTreeBuilder
from lark.parser_frontends import _get_lexer_callbacks
from lark.parsers.lalr_analysis import Shift

__all__ = ["TABLES_FORMAT", "TableParser", "lalr_tables"]

_Callback = Callable[[list[Any]], Any]
_Match = Callable[[str, int], Any]
# A reduction: (2 * arity = its length on the parse stack, nonterminal to go to, callback,
# unit chain or None). A unit chain maps the state under the top one to the state reached after
# a run of one-child `?rule` reductions that return their child unchanged: one step for the run.
_Rule = tuple[int, str, _Callback, dict[int, int] | None]
# The same in the tables' data, with the index of the Lark rule whose callback it runs.
_RuleData = tuple[int, str, int, dict[int, int] | None]

_END = "$END"
_ASCII = frozenset(chr(i) for i in range(128))
_new_str = str.__new__


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
    """Parses one text with the tables of a ``Lark(parser="lalr", lexer="basic")`` object, or
    with those tables as plain data (:func:`lalr_tables`, shipped in ``lalr_tables.py``).

    ``parse`` keeps all its state in locals, so one instance serves several threads.
    """

    def __init__(self, lark: Lark, start: str | None = None) -> None:
        self._load(lalr_tables(lark, start), lark.options.transformer)

    @classmethod
    def from_tables(cls, tables: Mapping[str, Any], transformer: Any) -> TableParser:
        """The parser of :func:`lalr_tables`' data, its callbacks built for ``transformer``
        as Lark builds them: no grammar to load, no table to convert."""
        parser = cls.__new__(cls)
        parser._load(tables, transformer)
        return parser

    # ---- set-up: from the tables' data

    def _load(self, tables: Mapping[str, Any], transformer: Any) -> None:
        if tables["format"] != TABLES_FORMAT:
            raise ValueError(f"tables of format {tables['format']}, not {TABLES_FORMAT}")
        re_module: Any = importlib.import_module(tables["re_module"])
        flags: int = tables["flags"]
        terminals = [_terminal(*t) for t in tables["terminals"]]
        self._terminals_by_name: dict[str, TerminalDef] = {t.name: t for t in terminals}
        scanned: list[tuple[str, str]] = tables["scanned"]

        def compile_match(indices: Iterable[int]) -> _Match:
            parts = [f"(?P<{scanned[i][0]}>{scanned[i][1]})" for i in indices]
            regexp = "|".join(parts) if parts else "(?!)"  # "(?!)" matches nothing
            match: _Match = re_module.compile(regexp, flags).match
            return match

        def install_master(match: _Match) -> None:
            self._master_match = match

        self._master_match = _on_first_use(
            partial(compile_match, range(len(scanned))), install_master
        )
        # Per ASCII character: the terminal's name when the first terminal that can start with
        # it is that very character as a literal (it always wins: the alternation takes the
        # first branch that matches), else a master regex of just the terminals that can.
        # A scanner's regex is compiled when a text first needs it (a short program meets a
        # few of the 20): the first call puts the compiled one in place for all its chars.
        self._singles: dict[str, str] = {ch: sys.intern(n) for ch, n in tables["singles"].items()}
        scanners: dict[str, _Match] = {}

        def install(chars: str, match: _Match) -> None:
            for ch in chars:
                scanners[ch] = match

        for chars, subset in tables["scanners"]:
            lazy = _on_first_use(partial(compile_match, subset), partial(install, chars))
            for ch in chars:
                scanners[ch] = lazy
        self._scanners = scanners
        self._scanned_names = tuple(name for name, _ in scanned)  # for tests: Lark's order
        self._retype: Mapping[str, Any] = {
            name: re_module.compile(regexp, flags) for name, regexp in tables["retype"].items()
        }
        self._ignore = frozenset(tables["ignore"])
        self._newline_types = frozenset(tables["newline_types"])
        self._allowed = frozenset(tables["allowed"])

        # The parser: a shift (or goto) is the target state, a reduce is ~index in the rules.
        rows = tuple({sys.intern(s): a for s, a in row.items()} for row in tables["rows"])
        self._rows = rows
        self._start_state: int = tables["start_state"]
        self._end_state: int = tables["end_state"]
        # What Lark's feed_token reports: the state's terminals (nonterminals are lowercase).
        self._expected = tuple(frozenset(s for s in row if s.isupper()) for row in rows)
        lark_rules = [_lark_rule(*r) for r in tables["lark_rules"]]
        propagate_positions, maybe_placeholders = tables["tree_options"]
        builder = ParseTreeBuilder(  # type: ignore[no-untyped-call]
            lark_rules, Tree, propagate_positions, False, maybe_placeholders
        )
        callbacks = builder.create_callback(transformer)  # type: ignore[no-untyped-call]
        self._rules: tuple[_Rule, ...] = tuple(
            (span, sys.intern(origin), _reduce_callback(callbacks[lark_rules[i]], span), chain)
            for span, origin, i, chain in tables["rules"]
        )
        # Lark also calls a transformer method named after a terminal on each shifted token.
        self._token_callbacks: dict[str, Callable[[Token], Any]] = {
            sys.intern(k): v
            for k, v in _get_lexer_callbacks(transformer, terminals).items()  # type: ignore[no-untyped-call]
        }

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


# ---- the tables as data

TABLES_FORMAT = 1


def lalr_tables(lark: Lark, start: str | None = None) -> dict[str, Any]:
    """What :class:`TableParser` needs of a Lark object, as plain data (str, int, lists,
    dicts), the same whatever the hash seed: the states are numbered in the order a walk from
    the start state meets them, symbols taken in sorted order."""
    frontend: Any = lark.parser  # lark.parser_frontends.ParsingFrontend
    conf: Any = lark.lexer_conf
    options: Any = lark.options
    if options.parser != "lalr" or conf.lexer_type != "basic":
        raise ValueError("TableParser needs parser='lalr' and lexer='basic'")
    if conf.postlex is not None or conf.callbacks or conf.use_bytes:
        raise ValueError("TableParser supports neither postlex, lexer_callbacks nor use_bytes")
    if options.tree_class not in (None, Tree) or not isinstance(options.propagate_positions, bool):
        raise ValueError("TableParser supports neither a tree_class nor a propagate_positions")
    starts: list[str] = list(frontend.parser_conf.start)
    if start is None:
        if len(starts) != 1:
            raise ValueError(f"several start rules, choose one of {starts}")
        start = starts[0]
    lalr: Any = frontend.parser.parser  # lark.parsers.lalr_parser._Parser
    tables: dict[str, Any] = {"format": TABLES_FORMAT}
    tables.update(_lexer_tables(conf))
    tables.update(_parser_tables(lalr.parse_table, lalr.callbacks, start))
    tables["tree_options"] = [options.propagate_positions, bool(options.maybe_placeholders)]
    return tables


def _lexer_tables(conf: Any) -> dict[str, Any]:
    re_module: Any = conf.re_module
    flags: int = conf.g_regex_flags
    terminals = sorted(conf.terminals, key=_order_key)
    # A string terminal that a regex terminal of the same priority also matches is found
    # through the regex and then renamed (Lark's "unless" rule, e.g. keywords vs. NAME).
    embedded: set[str] = set()
    retype: dict[str, str] = {}
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
            retype[term.name] = _alternation(unless)
    scanned = [t for t in terminals if t.name not in embedded]
    singles: dict[str, str] = {}
    chars_of: dict[tuple[int, ...], list[str]] = {}
    ignore = frozenset(conf.ignore)
    if re_module is re:  # the analysis reads the syntax of the standard re module
        firsts = [_regex_first(t.pattern.to_regexp(), flags) for t in scanned]
        for ch in sorted(_ASCII):
            subset = tuple(i for i, f in enumerate(firsts) if f is None or ch in f)
            if subset:
                head = scanned[subset[0]]
                if head.name not in ignore and _is_char_literal(head, ch, flags):
                    singles[ch] = head.name
                    continue
            chars_of.setdefault(subset, []).append(ch)
    allowed = {t.name for t in scanned} - ignore
    return {
        "re_module": re_module.__name__,
        "flags": flags,
        "terminals": [_terminal_data(t) for t in conf.terminals],
        "scanned": [[t.name, t.pattern.to_regexp()] for t in scanned],
        "singles": singles,
        "scanners": [["".join(chars), list(subset)] for subset, chars in chars_of.items()],
        "retype": retype,
        "ignore": sorted(ignore),
        "newline_types": sorted(
            t.name for t in conf.terminals if _has_newline(t.pattern.to_regexp())
        ),
        "allowed": sorted(allowed or {"<END-OF-FILE>"}),
    }


def _parser_tables(table: Any, callbacks: Mapping[Any, Any], start: str) -> dict[str, Any]:
    lark_states: Mapping[int, Mapping[Any, tuple[Any, Any]]] = table.states
    if sorted(lark_states) != list(range(len(lark_states))):
        raise ValueError("expected Lark's IntParseTable (states numbered 0..n-1)")
    # Lark numbers its states in an order that depends on the hash seed: renumber them in
    # the order of a walk from the start state, symbols in sorted order.
    start_state: int = table.start_states[start]
    number = {start_state: 0}
    walk = [start_state]
    for state in walk:
        for _name, (action, arg) in sorted(lark_states[state].items(), key=lambda i: str(i[0])):
            if action is Shift and arg not in number:
                number[arg] = len(walk)
                walk.append(arg)
    if len(walk) != len(lark_states):
        raise ValueError("states the start state does not reach")
    rule_index: dict[Any, int] = {}
    lark_rules: list[Any] = []
    rules: list[_RuleData] = []
    passes_child: list[bool] = []
    rows: list[dict[str, int]] = []
    for state in walk:
        row: dict[str, int] = {}
        for name, (action, arg) in sorted(lark_states[state].items(), key=lambda i: str(i[0])):
            # Lark's names are often Token objects; plain str keys keep lookups in C
            # (Token.__eq__ is Python code).
            symbol = str(name)
            if action is Shift:
                row[symbol] = number[arg]
                continue
            index = rule_index.get(arg)
            if index is None:
                index = rule_index[arg] = len(rules)
                span = 2 * len(arg.expansion)  # a value and a state per symbol
                rules.append((span, str(arg.origin.name), len(lark_rules), None))
                lark_rules.append(arg)
                callback = callbacks[arg]
                passes_child.append(type(callback) is ExpandSingleChild and span == 2)
            row[symbol] = ~index
        rows.append(row)
    end_state = number[table.end_states[start]]
    _fold_unit_chains(rows, rules, passes_child, end_state)
    return {
        "start_state": 0,
        "end_state": end_state,
        "rows": rows,
        "rules": [list(r) for r in rules],
        "lark_rules": [_lark_rule_data(r) for r in lark_rules],
    }


def _fold_unit_chains(
    rows: list[dict[str, int]],
    rules: list[_RuleData],
    passes_child: list[bool],
    end_state: int,
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
            for under in sorted(below[top]):
                end = _chain_end(rows, rules, passes_child, under, top, kind, end_state)
                if end is None:
                    break  # leave this one to the general reduce step
                chain[under] = end
            else:
                if chain:
                    folded.append((top, kind, chain))
    for top, kind, chain in folded:
        span, origin, index, _ = rules[~rows[top][kind]]
        rows[top][kind] = ~len(rules)
        rules.append((span, origin, index, chain))
        passes_child.append(False)


def _terminal_data(term: TerminalDef) -> list[Any]:
    pattern = term.pattern
    kind = "str" if isinstance(pattern, PatternStr) else "re"
    return [term.name, kind, pattern.value, sorted(pattern.flags), pattern.raw, term.priority]


def _terminal(
    name: str, kind: str, value: str, flags: list[str], raw: str | None, priority: int
) -> TerminalDef:
    pattern = PatternStr(value, flags, raw) if kind == "str" else PatternRE(value, flags, raw)
    return TerminalDef(name, pattern, priority)


def _lark_rule_data(rule: Any) -> list[Any]:
    o = rule.options
    symbols = [[s.name, s.is_term, bool(getattr(s, "filter_out", False))] for s in rule.expansion]
    empty = list(o.empty_indices)
    return [
        rule.origin.name, symbols, rule.order, rule.alias,
        [o.keep_all_tokens, o.expand1, o.priority, o.template_source, empty],
    ]  # fmt: skip


def _lark_rule(
    origin: str, symbols: list[list[Any]], order: int, alias: str | None, options: list[Any]
) -> Rule:
    keep_all_tokens, expand1, priority, template_source, empty = options
    expansion = [Terminal(n, f) if term else NonTerminal(n) for n, term, f in symbols]
    rule_options = RuleOptions(keep_all_tokens, expand1, priority, template_source, tuple(empty))
    return Rule(NonTerminal(origin), expansion, order, alias, rule_options)


def _reduce_callback(callback: Any, span: int) -> _Callback:
    """The callback of a reduction of ``span // 2`` symbols."""
    if type(callback) is ExpandSingleChild:
        # ExpandSingleChild (a `?rule` without alias) tests len(children) == 1 on each call;
        # with LALR that length is the arity, so decide it once here.
        if span == 2:
            return _only_child
        inner: _Callback = callback.node_builder
        return inner
    reduce: _Callback = callback
    return reduce


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


def _chain_end(
    rows: list[dict[str, int]],
    rules: list[_RuleData],
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
