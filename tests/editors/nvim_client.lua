-- A real editor as the client of `urdflint lsp` (tests/test_editors.py): Neovim 0.7+, headless.
-- Opens T_FILE, waits for diagnostics, asks the code actions of the first T_CODE diagnostic,
-- applies the fix, saves, and waits until that diagnostic is gone. Writes a JSON report to
-- T_OUT. T_PYTHON is the Python that runs `-m urdflint lsp`.
local report = { steps = {} }
local function step(name, value) report.steps[#report.steps + 1] = { name = name, value = value } end
local function finish()
  local f = io.open(os.getenv("T_OUT"), "w")
  f:write(vim.fn.json_encode(report))
  f:close()
  vim.cmd("qa!")
end
local ok, err = pcall(function()
  vim.cmd("edit " .. os.getenv("T_FILE"))
  local bufnr = vim.api.nvim_get_current_buf()
  local code = os.getenv("T_CODE")
  local id = vim.lsp.start_client({
    name = "urdflint",
    cmd = { os.getenv("T_PYTHON"), "-m", "urdflint", "lsp", "--no-cache" },
    root_dir = os.getenv("T_ROOT"),
  })
  vim.lsp.buf_attach_client(bufnr, id)
  local function with_code()
    local found = {}
    for _, d in ipairs(vim.diagnostic.get(bufnr)) do
      if d.code == code then found[#found + 1] = d end
    end
    return found
  end
  vim.wait(60000, function() return #with_code() > 0 end, 20)
  local before = with_code()
  step("diagnostics", #vim.diagnostic.get(bufnr))
  step("with code", #before)
  if #before == 0 then return end
  local d = before[1]
  local kept = (d.user_data and d.user_data.lsp) or {}  -- 0.7 keeps only code and data
  local lsp_diagnostic = {
    range = { start = { line = d.lnum, character = d.col },
              ["end"] = { line = d.end_lnum or d.lnum, character = d.end_col or d.col } },
    message = d.message, code = d.code, source = d.source, data = kept.data,
  }
  local params = {
    textDocument = { uri = vim.uri_from_bufnr(bufnr) },
    range = lsp_diagnostic.range,
    context = { diagnostics = { lsp_diagnostic } },
  }
  local answers = vim.lsp.buf_request_sync(bufnr, "textDocument/codeAction", params, 20000) or {}
  local titles, fix = {}, nil
  for _, answer in pairs(answers) do
    for _, action in ipairs(answer.result or {}) do
      titles[#titles + 1] = action.title
      if fix == nil and action.title:find("^Fix ") then fix = action end
    end
  end
  step("actions", titles)
  if fix == nil then return end
  vim.lsp.util.apply_workspace_edit(fix.edit, "utf-16")
  vim.cmd("write")
  local gone = vim.wait(60000, function() return #with_code() < #before end, 20)
  step("fixed", gone)
  step("with code after", #with_code())
  vim.lsp.stop_client(id)
end)
report.ok = ok
report.error = err and tostring(err) or nil
finish()
