"""The syntax: text to syntax trees, one block at a time (see ARCHITECTURE.md).

:mod:`.lines` decodes and splits the text, and :mod:`.limits` says how much of it is read.
:mod:`.parser` parses a block: plain NC words on a fast path, the rest with the LALR tables of
:mod:`.grammar_tables`, run by :mod:`.lalr_driver`. :mod:`.tree` is the typed syntax tree.
:mod:`.dialects` recognises other controls' forms, :mod:`.marks` is what a line tells the
layers above, and :mod:`.walk` walks expressions. :mod:`.diff` finds where a new version of a
document differs from the one before. Nothing here knows programs, values or rules.
"""
