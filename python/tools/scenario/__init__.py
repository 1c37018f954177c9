"""The scenario file: its reader and checks (`scenario_file.py`), planned faults, plan parameters."""
