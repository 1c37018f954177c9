"""The operator's console (`auv-console`, a map in a browser) and `auvctl`: live or from a log."""
