"""tests/sim shares the top-level fixtures (tests/conftest.py)."""
