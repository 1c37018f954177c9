"""The operator's view for the HIL-topology test, run inside its namespace:
every 0.3 s one JSON line with the world clock (server, time), each
vehicle's NAVIGATOR (run state, active path, status time) and its true
position (time, north, east).

    observe.py URL VEHICLE...
"""

import json
import signal
import sys
import time

import lcm

from auv import chasm_status_t, ground_truth_t, sim_clock_t

url, vehicles = sys.argv[1], sys.argv[2:]
view: dict = {"servers": [], "clock_s": 0.0, "nav": {}, "truth": {}}


def on_clock(_c, d):
    m = sim_clock_t.decode(d)
    if not view["servers"] or view["servers"][-1] != m.server_id:
        view["servers"].append(m.server_id)
    view["clock_s"] = max(view["clock_s"], m.utime / 1e6)


def on_nav(_c, d):
    m = chasm_status_t.decode(d)
    view["nav"][m.vehicle] = [m.run_state, "/".join(m.active_path), m.utime / 1e6]


def on_truth(_c, d):
    m = ground_truth_t.decode(d)
    view["truth"][m.vehicle] = [m.utime / 1e6, m.eta[0], m.eta[1]]


lc = lcm.LCM(url)
lc.subscribe("SIM.CLOCK", on_clock)
for v in vehicles:
    lc.subscribe(f"{v}.CHASM.NAVIGATOR", on_nav)
    lc.subscribe(f"{v}.TRUTH", on_truth)
signal.signal(signal.SIGINT, lambda *_: sys.exit(0))
signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
next_print = 0.0
while True:
    try:
        lc.handle_timeout(50)
    except OSError:         # interrupted by a signal: the handler exits
        continue
    if time.monotonic() >= next_print:
        next_print = time.monotonic() + 0.3
        print(json.dumps(view), flush=True)
