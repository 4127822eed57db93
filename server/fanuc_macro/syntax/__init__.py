"""The syntax: text to lines, the grammar and its LALR driver, the parser, the syntax
tree, other controls' dialects and the walks over expressions (see ARCHITECTURE.md)."""
