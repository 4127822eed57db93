-- The language server of FANUC Custom Macro B programs, as Neovim 0.11's vim.lsp.config reads
-- it from "lsp/" on 'runtimepath': vim.lsp.enable("fanuc_macro") starts it for the files the
-- ftdetect script of this folder recognises. fanuc-macro-ls is installed by `pip install .`
-- (pyproject.toml, [project.scripts]); `python3 -m fanuc_macro.lsp.server` is the same server.
return {
  cmd = { "fanuc-macro-ls" },
  filetypes = { "fanuc-macro" },
  root_markers = { ".git" },
  -- The settings are those of the VS Code extension, "fanuc-macro.*", answered to the
  -- server's workspace/configuration; a machine limit left out is not checked. For example:
  -- settings = { ["fanuc-macro"] = { controller = "0i-TF", machine = { maxSpindleSpeed = 4000 } } },
}
