"""Build-time generators: the LCM type table for C, the team link's codec, the wheels' paths."""
