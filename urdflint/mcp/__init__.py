"""``urdflint mcp``: the linter as tools for AI coding agents (the Model Context Protocol).

The server speaks MCP over stdio with the official SDK (the ``mcp`` extra), which only
:mod:`urdflint.mcp.server` imports, and only when the server starts. The other modules are
plain Python: :mod:`.roots` (the client's folders, every path confined to them),
:mod:`.runs` (one lint as ``urdflint check`` does it), :mod:`.tools` and :mod:`.fixing` (what
each tool answers), :mod:`.schemas` (the tools' arguments) and :mod:`.catalogue` (the rule
resources).
"""
