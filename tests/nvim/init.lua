-- Headless Neovim as a real LSP client of fanuc-macro-ls (driven by tests/test_neovim.py).
-- It opens a seed program, waits for the server's diagnostics, asks for a hover and writes
-- what it got to $FANUC_NVIM_OUT as JSON, then quits. Works on Neovim 0.7 (no vim.lsp.start)
-- and later.
local out = assert(os.getenv("FANUC_NVIM_OUT"), "FANUC_NVIM_OUT is not set")
local seed = assert(os.getenv("FANUC_NVIM_SEED"), "FANUC_NVIM_SEED is not set")
local python = os.getenv("FANUC_NVIM_PYTHON") or "python3"
local root = os.getenv("FANUC_NVIM_ROOT") or vim.fn.fnamemodify(seed, ":h")
local timeout = tonumber(os.getenv("FANUC_NVIM_TIMEOUT") or "60000")
local hover_line = tonumber(os.getenv("FANUC_NVIM_HOVER_LINE") or "0")
local hover_col = tonumber(os.getenv("FANUC_NVIM_HOVER_COL") or "0")

local result = { nvim = tostring(vim.version().major) .. "." .. tostring(vim.version().minor) }

local function finish()
  local f = assert(io.open(out, "w"))
  f:write(vim.fn.json_encode(result))
  f:close()
  vim.cmd("qall!")
end

local function diagnostic_code(d)
  if d.code ~= nil then
    return d.code
  end
  local lsp = d.user_data and d.user_data.lsp
  return lsp and lsp.code or nil
end

local function run()
  vim.cmd("edit " .. vim.fn.fnameescape(seed))
  local bufnr = vim.api.nvim_get_current_buf()
  vim.bo[bufnr].filetype = "fanuc-macro"
  local config = {
    name = "fanuc-macro",
    cmd = { python, "-m", "fanuc_macro.lsp.server" },
    root_dir = root,
    init_options = { analysis = { debounceMs = 50 } },
  }
  local client_id
  if vim.lsp.start ~= nil then
    client_id = vim.lsp.start(config)
  else
    client_id = vim.lsp.start_client(config)
    vim.lsp.buf_attach_client(bufnr, client_id)
  end
  result.client_id = client_id

  local started = vim.loop.hrtime()
  result.got_diagnostics = vim.wait(timeout, function()
    return #vim.diagnostic.get(bufnr) > 0
  end, 50)
  result.diagnostics_ms = (vim.loop.hrtime() - started) / 1e6
  result.diagnostics = {}
  for _, d in ipairs(vim.diagnostic.get(bufnr)) do
    table.insert(result.diagnostics, {
      lnum = d.lnum,
      col = d.col,
      code = diagnostic_code(d),
      source = d.source,
      severity = d.severity,
      message = d.message,
    })
  end

  local params = {
    textDocument = { uri = vim.uri_from_bufnr(bufnr) },
    position = { line = hover_line, character = hover_col },
  }
  local replies, err = vim.lsp.buf_request_sync(bufnr, "textDocument/hover", params, timeout)
  result.hover_error = err
  for _, reply in pairs(replies or {}) do
    if reply.error ~= nil then
      result.hover_error = vim.inspect(reply.error)
    elseif reply.result ~= nil then
      local contents = reply.result.contents
      result.hover = type(contents) == "table" and (contents.value or vim.inspect(contents))
        or contents
    end
  end
end

vim.api.nvim_create_autocmd("VimEnter", {
  callback = function()
    vim.schedule(function()
      local ok, err = pcall(run)
      if not ok then
        result.error = tostring(err)
      end
      finish()
    end)
  end,
})
