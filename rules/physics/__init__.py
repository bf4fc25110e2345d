"""P: physics, computed with Pinocchio (needs the dynamics extra)."""
