"""What turns files into documents: package resolution, xacro expansion, meshes, changed files.

Imports only :mod:`urdflint.model`.
"""
