"""Rule family."""
