-- urdflint lsp in a real Neovim (0.7+), headless: open a macro file of a real package, plant a
-- negative mass six times and time until its I002 shows and clears. Usage (from the package root):
--   T_FILE=pr2_description/urdf/forearm_v0/forearm.urdf.xacro T_ROOT=$PWD T_CACHE=/tmp/urdflint-nvim \
--   nvim --headless -u NONE -c "luafile /work/main/bench/nvim_lsp.lua"
-- (T_URDFLINT: the urdflint command, default /work/main/.venv/bin/urdflint). Prints to stderr.
local file = os.getenv("T_FILE")
local root = os.getenv("T_ROOT")
local cache = os.getenv("T_CACHE")
local out = {}
local function log(s) table.insert(out, s); io.stderr:write(s .. "\n") end
vim.cmd("edit " .. file)
local bufnr = vim.api.nvim_get_current_buf()
local client_id = vim.lsp.start_client({
  name = "urdflint",
  cmd = { os.getenv("T_URDFLINT") or "/work/main/.venv/bin/urdflint", "lsp", "--cache-dir", cache },
  root_dir = root,
  workspace_folders = { { uri = vim.uri_from_fname(root), name = "ws" } },
})
vim.lsp.buf_attach_client(bufnr, client_id)
local function count(code)
  local n = 0
  for _, d in ipairs(vim.diagnostic.get(bufnr)) do
    if d.code == code then n = n + 1 end
  end
  return n
end
local t0 = vim.loop.hrtime()
local ok = vim.wait(60000, function() return #vim.diagnostic.get(bufnr) > 0 end, 5)
log(string.format("open -> diagnostics: %s after %.0f ms (%d diagnostics)", tostring(ok), (vim.loop.hrtime() - t0) / 1e6, #vim.diagnostic.get(bufnr)))
vim.wait(4000, function() return false end, 50)  -- let every entry finish
local lines = vim.api.nvim_buf_get_lines(bufnr, 0, -1, false)
local target
for i, l in ipairs(lines) do
  if l:match('<mass value="[%d%.]+"') then target = i; break end
end
local original = lines[target]
local times = {}
for round = 1, 6 do
  local planted = original:gsub('<mass value="', '<mass value="-', 1)
  t0 = vim.loop.hrtime()
  vim.api.nvim_buf_set_lines(bufnr, target - 1, target, false, { planted })
  ok = vim.wait(10000, function() return count("I002") > 0 end, 2)
  local shown = (vim.loop.hrtime() - t0) / 1e6
  t0 = vim.loop.hrtime()
  vim.api.nvim_buf_set_lines(bufnr, target - 1, target, false, { original })
  local ok2 = vim.wait(10000, function() return count("I002") == 0 end, 2)
  local cleared = (vim.loop.hrtime() - t0) / 1e6
  log(string.format("round %d: I002 shown %s after %.0f ms, cleared %s after %.0f ms", round, tostring(ok), shown, tostring(ok2), cleared))
  vim.wait(1500, function() return false end, 50)
end
local d = vim.diagnostic.get(bufnr)
for _, x in ipairs(d) do
  if x.code == "I002" then log("stale I002 left: line " .. x.lnum) end
end
vim.lsp.stop_client(client_id)
vim.cmd("qa!")
