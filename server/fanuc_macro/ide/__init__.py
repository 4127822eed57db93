"""Editor features without a protocol: plain data that every front end (the language server,
the command line) converts (see ARCHITECTURE.md)."""
