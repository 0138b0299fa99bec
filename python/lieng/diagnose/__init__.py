"""``lieng diagnose`` (package; see the stage modules)."""
