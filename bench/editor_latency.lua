-- The Neovim half of bench/editor_latency.py (the same measures as bench/editor_latency.el):
--   nvim --headless -u NONE -i NONE -c "luafile bench/editor_latency.lua"
-- Headless Neovim runs its event loop as at a keyboard (vim.wait), and its LSP client sends a
-- change after `debounce_text_changes` (150 ms, less when the last change was sent longer
-- ago), a libuv timer. Times from each step's start:
--   open:   :edit B_FILE, start the client (B_CMD, a JSON array; B_ROOT the workspace folder)
--           and attach it -> the first publishDiagnostics for the file (handled), -> the first
--           diagnostics shown, -> the server quiet (no publish for B_QUIET s);
--   plant:  line B_LINE (0-based) becomes B_PLANTED -> a publish for the file, handled by the
--           client (vim.diagnostic set), with more B_CODE diagnostics than as opened;
--   revert: the line back -> one with as many as then.
-- B_ROUNDS plant/revert rounds. Writes a JSON report to B_OUT. The buffer is never written.
vim.o.swapfile = false
local file = vim.fn.resolve(vim.fn.fnamemodify(os.getenv("B_FILE"), ":p"))
local root = os.getenv("B_ROOT")
local code = os.getenv("B_CODE")
local line = tonumber(os.getenv("B_LINE"))
local planted = os.getenv("B_PLANTED")
local rounds = tonumber(os.getenv("B_ROUNDS") or "5")
local quiet = tonumber(os.getenv("B_QUIET") or "2") * 1e3
local report = {}

local function now() return vim.loop.hrtime() / 1e6 end  -- ms
local last_publish, first_publish, publishes = 0, nil, 0
local published_total, published_code = nil, 0  -- the last publish for the file
local pending, passed = nil, nil  -- a test of the code count; when a publish first passed it
local handler = vim.lsp.handlers["textDocument/publishDiagnostics"]
vim.lsp.handlers["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
  handler(err, result, ctx, config)
  last_publish = now()
  if result and vim.fn.resolve(vim.uri_to_fname(result.uri)) == file then
    publishes = publishes + 1
    first_publish = first_publish or last_publish
    published_total, published_code = #result.diagnostics, 0
    for _, d in ipairs(result.diagnostics) do
      if d.code == code then published_code = published_code + 1 end
    end
    if pending and not passed and pending(published_code) then passed = now() end
  end
end

local ok, err = pcall(function()
  local start = now()
  vim.cmd("edit " .. vim.fn.fnameescape(file))
  local bufnr = vim.api.nvim_get_current_buf()
  local client = vim.lsp.start_client({
    name = "urdflint",
    cmd = vim.fn.json_decode(os.getenv("B_CMD")),
    root_dir = root,
    workspace_folders = { { uri = vim.uri_from_fname(root), name = vim.fn.fnamemodify(root, ":t") } },
  })
  vim.lsp.buf_attach_client(bufnr, client)
  local edit_at, sent = nil, {}  -- each edit -> its didChange sent
  local c = vim.lsp.get_client_by_id(client)
  local notify = c.notify
  c.notify = function(method, params)
    if method == "textDocument/didChange" and edit_at then
      table.insert(sent, (now() - edit_at) / 1e3)
      edit_at = nil
    end
    return notify(method, params)
  end
  -- the diagnostics with `code` in the last publish for the file, handled by the client (as
  -- bench/editor_latency.el counts them)
  local function with_code() return published_code end
  local shown
  vim.wait(180000, function()
    if not shown and #vim.diagnostic.get(bufnr) > 0 then shown = now() end
    return first_publish ~= nil and now() - last_publish > quiet
  end, 5)
  report.open_first_publish = first_publish and (first_publish - start) / 1e3
  report.open_first_shown = shown and (shown - start) / 1e3
  report.open_quiet = (last_publish - start) / 1e3
  report.open_diagnostics = published_total
  report.open_displayed = #vim.diagnostic.get(bufnr)
  local base = with_code()
  report.open_with_code = base
  report.open_publishes = publishes
  local original = vim.api.nvim_buf_get_lines(bufnr, line, line + 1, false)[1]
  -- the line set to `text` -> the first publish for the file whose code count passes `test`,
  -- handled (timed in the handler, not by vim.wait's polling)
  local function timed(text, test)
    pending, passed = test, nil
    local t0 = now()
    edit_at = t0
    vim.api.nvim_buf_set_lines(bufnr, line, line + 1, false, { text })
    vim.wait(120000, function() return passed ~= nil end, 10)
    pending = nil
    local waited = ((passed or now()) - t0) / 1e3
    vim.wait(120000, function() return now() - last_publish > quiet end, 5)
    return waited
  end
  report.shown, report.cleared, report.sent = {}, {}, sent
  for _ = 1, rounds do
    table.insert(report.shown, timed(planted, function(n) return n > base end))
    table.insert(report.cleared, timed(original, function(n) return n <= base end))
  end
  report.editor = "Neovim " .. tostring(vim.version().major) .. "." .. tostring(vim.version().minor)
    .. "." .. tostring(vim.version().patch)
  local flags = vim.lsp.get_client_by_id(client).config.flags or {}
  report.idle = (flags.debounce_text_changes or 150) / 1e3
  vim.api.nvim_buf_set_option(bufnr, "modified", false)
  vim.lsp.stop_client(client)
end)
report.ok = ok
report.error = err and tostring(err) or nil
local f = io.open(os.getenv("B_OUT"), "w")
f:write(vim.fn.json_encode(report))
f:close()
vim.cmd("qa!")
