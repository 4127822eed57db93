-- Filetype detection of FANUC Custom Macro B programs: filetype "fanuc-macro".
--
-- The extensions are those the VS Code extension declares (package.json, "languages"); a file
-- with no extension is a program when its name is a program number (O1234, as a control's
-- memory card holds them) or its first line that is not blank starts with "%" or "O<digit>",
-- as `fanuc-macro check` decides (server/fanuc_macro/workspace.py, is_program_file).
-- Neovim 0.8 and later: vim.filetype.add; Neovim 0.7: autocommands.
local extensions = { "nc", "NC", "mac", "tap", "cnc", "eia" }

local function has_extension(path)
  return vim.fn.fnamemodify(path, ":t"):find(".", 2, true) ~= nil
end

-- Whether a file without an extension is a program, by its name or its first lines.
local function is_program(path, bufnr)
  if has_extension(path) then
    return false
  end
  local name = vim.fn.fnamemodify(path, ":t")
  if name:match("^[Oo]%d+$") and #name <= 9 then
    return true
  end
  for _, line in ipairs(vim.api.nvim_buf_get_lines(bufnr, 0, 10, false)) do
    if line:find("%S") then
      return line:find("^%s*%%") ~= nil or line:find("^%s*[Oo]%d") ~= nil
    end
  end
  return false
end

if vim.fn.has("nvim-0.8") == 1 then
  local by_extension = {}
  for _, extension in ipairs(extensions) do
    by_extension[extension] = "fanuc-macro"
  end
  vim.filetype.add({
    extension = by_extension,
    pattern = {
      [".*"] = {
        function(path, bufnr)
          if is_program(path, bufnr) then
            return "fanuc-macro"
          end
        end,
        { priority = -math.huge }, -- only when nothing else knows the file
      },
    },
  })
else
  local globs = {}
  for _, extension in ipairs(extensions) do
    table.insert(globs, "*." .. extension)
  end
  -- Sourced after the built-in detection: "set filetype" wins over it (*.mac is also asm).
  vim.api.nvim_create_autocmd({ "BufNewFile", "BufRead" }, {
    pattern = globs,
    command = "set filetype=fanuc-macro",
  })
  vim.api.nvim_create_autocmd("BufRead", {
    pattern = "*",
    callback = function(args)
      if vim.bo[args.buf].filetype == "" and is_program(args.file, args.buf) then
        vim.bo[args.buf].filetype = "fanuc-macro"
      end
    end,
  })
end
