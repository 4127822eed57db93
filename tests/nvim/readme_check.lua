-- Run after one of the README's Neovim blocks, loaded as init.lua (tests/test_neovim.py): opens
-- $FANUC_NVIM_PROGRAM by its name, as a user would, waits for the server's diagnostics and
-- writes what it got to $FANUC_NVIM_OUT as JSON, then quits. Works on Neovim 0.7 and later.
local out = assert(os.getenv("FANUC_NVIM_OUT"), "FANUC_NVIM_OUT is not set")
local program = assert(os.getenv("FANUC_NVIM_PROGRAM"), "FANUC_NVIM_PROGRAM is not set")
local timeout = tonumber(os.getenv("FANUC_NVIM_TIMEOUT") or "60000")

local version = vim.version()
local result = { nvim = tostring(version.major) .. "." .. tostring(version.minor) }

local function run()
  vim.cmd("edit " .. vim.fn.fnameescape(program))
  local bufnr = vim.api.nvim_get_current_buf()
  result.filetype = vim.bo[bufnr].filetype
  result.got_diagnostics = vim.wait(timeout, function()
    return #vim.diagnostic.get(bufnr) > 0
  end, 50)
  result.clients = {}
  local clients = vim.lsp.get_clients ~= nil and vim.lsp.get_clients({ bufnr = bufnr })
    or vim.lsp.buf_get_clients(bufnr) -- before Neovim 0.10
  for _, client in pairs(clients) do
    table.insert(result.clients, { name = client.name, root_dir = client.config.root_dir })
  end
  result.diagnostics = {}
  for _, d in ipairs(vim.diagnostic.get(bufnr)) do
    local lsp = d.user_data and d.user_data.lsp
    table.insert(result.diagnostics, {
      lnum = d.lnum,
      code = d.code or (lsp and lsp.code) or vim.NIL,
      source = d.source,
      message = d.message,
    })
  end
end

vim.schedule(function()
  local ok, err = pcall(run)
  if not ok then
    result.error = tostring(err)
  end
  local f = assert(io.open(out, "w"))
  f:write(vim.fn.json_encode(result))
  f:close()
  vim.cmd("qall!")
end)
