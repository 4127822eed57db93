"""The program model, of the text alone: it never runs anything (see ARCHITECTURE.md).

:mod:`.index` is the index of programs, labels, loops and calls. :mod:`.variables` says what a
variable number is, and :mod:`.meanings` what comments say a variable means.
:mod:`.knowledge` says what codes, functions and addresses mean. :mod:`.papers` names the
papers the known thread modules come from.
"""
