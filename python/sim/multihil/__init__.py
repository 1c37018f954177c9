"""Multi-HIL: several simulators share one environment and one global clock.

Every simulator runs an EnvNode (node.py): it joins the world as a client,
or serves it when no server is heard (election.py), synchronises its clock
NTP-style (clock.py, clocksync.py) and takes part in lockstep (lockstep.py).
hook.py plugs a node into the simulator; standalone.py runs one alone.
See docs/multihil.md.
"""
