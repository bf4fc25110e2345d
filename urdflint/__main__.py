"""``python -m urdflint``."""

from urdflint.cli import main

raise SystemExit(main())
