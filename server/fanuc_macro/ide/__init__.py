"""Editor features without a protocol: plain data that every front end (the language server,
the command line) converts (see ARCHITECTURE.md).

- :mod:`.data`: the results (positions in code points, ranges, markdown, edits, locations,
  symbols, completion items, code actions);
- :mod:`.view`: one analysed document with the workspace around it, what the features read;
- :mod:`.locate`: what is under the cursor in a block;
- :mod:`.values`: values and variables in words;
- :mod:`.hover`, :mod:`.inlay`, :mod:`.navigation` (definition, references, symbols),
  :mod:`.completion`, :mod:`.actions`, :mod:`.semantic` (semantic tokens, their kinds in
  :mod:`.token_legend`), :mod:`.signature`, :mod:`.lenses`: the features;
- :mod:`.trace`: the motions a program executes; :mod:`.thread_module`: the generator, loaded
  when first asked for.
"""
