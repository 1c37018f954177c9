"""The acoustic modem of the simulator (docs/modem.md).

Each simulator process models its own vehicle's modem and knows only its own
vehicle's truth. The water between vehicles is the shared channel
SIM.ACOUSTIC: the sender's simulator puts each accepted frame there with its
true position and send time, and every other simulator decides, for its own
vehicle only, whether and when the frame arrives.
"""

from sim.modem.config import ModemConfig

__all__ = ["ModemConfig"]
