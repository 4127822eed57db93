-- Headless Neovim as a real LSP client of fanuc-macro-ls (driven by tests/test_neovim.py),
-- set up as the README says: editors/nvim on 'runtimepath' (its ftdetect gives program files
-- the filetype "fanuc-macro"), then vim.lsp.enable on Neovim 0.11 (editors/nvim/lsp/) or a
-- FileType autocommand that starts the server on older ones. It opens a seed program by its
-- name alone (no filetype set here), waits for the server's diagnostics, asks for a hover,
-- opens the other files it is given the same way, and writes what it got to $FANUC_NVIM_OUT
-- as JSON, then quits. Works on Neovim 0.7 (no vim.lsp.start) and later.
local out = assert(os.getenv("FANUC_NVIM_OUT"), "FANUC_NVIM_OUT is not set")
local seed = assert(os.getenv("FANUC_NVIM_SEED"), "FANUC_NVIM_SEED is not set")
local runtime = assert(os.getenv("FANUC_NVIM_RUNTIME"), "FANUC_NVIM_RUNTIME is not set")
local python = os.getenv("FANUC_NVIM_PYTHON") or "python3"
local root = os.getenv("FANUC_NVIM_ROOT") or vim.fn.fnamemodify(seed, ":h")
local timeout = tonumber(os.getenv("FANUC_NVIM_TIMEOUT") or "60000")
local hover_line = tonumber(os.getenv("FANUC_NVIM_HOVER_LINE") or "0")
local hover_col = tonumber(os.getenv("FANUC_NVIM_HOVER_COL") or "0")
-- More files to open, one a line: their filetype, and their diagnostics when it is the programs'.
local others = vim.split(os.getenv("FANUC_NVIM_OTHERS") or "", "\n", { trimempty = true })

-- Read before the filetype detection runs (after this file), as a plugin folder is.
vim.opt.runtimepath:append(runtime)

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

local cmd = { python, "-m", "fanuc_macro.lsp.server" } -- the README has { "fanuc-macro-ls" }
local init_options = { analysis = { debounceMs = 50 } }

local function setup()
  if vim.lsp.enable ~= nil then -- Neovim 0.11: editors/nvim/lsp/fanuc_macro.lua, with our cmd
    vim.lsp.config("fanuc_macro", { cmd = cmd, root_dir = root, init_options = init_options })
    vim.lsp.enable("fanuc_macro")
    return "vim.lsp.enable"
  end
  vim.api.nvim_create_autocmd("FileType", {
    pattern = "fanuc-macro",
    callback = function(args)
      local config = { name = "fanuc-macro", cmd = cmd, root_dir = root,
        init_options = init_options }
      if vim.lsp.start ~= nil then
        result.client_id = vim.lsp.start(config, { bufnr = args.buf })
      else -- Neovim 0.7
        result.client_id = result.client_id or vim.lsp.start_client(config)
        vim.lsp.buf_attach_client(args.buf, result.client_id)
      end
    end,
  })
  return "FileType"
end

local function clients_of(bufnr)
  if vim.lsp.get_clients ~= nil then
    return #vim.lsp.get_clients({ bufnr = bufnr })
  end
  return #vim.tbl_keys(vim.lsp.buf_get_clients(bufnr))
end

-- Open a file by its name; its filetype, and its diagnostics once they are there (when the
-- filetype is the programs').
local function open(path)
  vim.cmd("edit " .. vim.fn.fnameescape(path))
  local bufnr = vim.api.nvim_get_current_buf()
  local shown = { path = path, filetype = vim.bo[bufnr].filetype }
  if shown.filetype == "fanuc-macro" then
    local started = vim.loop.hrtime()
    shown.got_diagnostics = vim.wait(timeout, function()
      return #vim.diagnostic.get(bufnr) > 0
    end, 50)
    shown.diagnostics_ms = (vim.loop.hrtime() - started) / 1e6
  end
  shown.clients = clients_of(bufnr)
  shown.diagnostics = {}
  for _, d in ipairs(vim.diagnostic.get(bufnr)) do
    table.insert(shown.diagnostics, {
      lnum = d.lnum,
      col = d.col,
      code = diagnostic_code(d),
      source = d.source,
      severity = d.severity,
      message = d.message,
    })
  end
  return bufnr, shown
end

local function run()
  result.setup = setup()
  local bufnr, shown = open(seed)
  result.filetype = shown.filetype
  result.got_diagnostics = shown.got_diagnostics
  result.diagnostics_ms = shown.diagnostics_ms
  result.diagnostics = shown.diagnostics

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

  result.others = {}
  for _, path in ipairs(others) do
    local _, other = open(path)
    table.insert(result.others, other)
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
