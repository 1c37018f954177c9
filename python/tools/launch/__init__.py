"""The launcher: start one host's part of a scenario, keep its clock, watch the mission, stop it.

`launcher.py` is the reusable core (the host agents start their part with it);
`cli.py` is `auv-launch`, the front end, which alone may import the agents.
"""
