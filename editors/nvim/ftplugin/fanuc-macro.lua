-- A FANUC comment is "( ... )" (it ends at the first ")"); a block ends at the line end.
vim.bo.commentstring = "(%s)"
vim.b.undo_ftplugin = (vim.b.undo_ftplugin or "") .. "\n setlocal commentstring<"
