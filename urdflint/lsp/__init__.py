"""The language server (``urdflint lsp``): urdflint in the editor, over LSP (pygls).

Needs the ``lsp`` extra (``pip install 'urdflint[lsp]'``); nothing here is imported by a check.
"""
