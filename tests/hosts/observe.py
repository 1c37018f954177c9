"""The operator's view for the HIL-topology test, run inside its namespace:
every 0.3 s one JSON line with the world clock (server, time), each
vehicle's NAVIGATOR (run state, active path, status time), its true
position (time, north, east), and the team's losses and takeovers as the
vehicles announce them (TEAM_EVENT: [time, vehicle, peer, text]).

    observe.py URL VEHICLE...
"""

import json
import signal
import sys
import time

import lcm

from auv import chasm_status_t, ground_truth_t, sim_clock_t, team_event_t

url, vehicles = sys.argv[1], sys.argv[2:]
view: dict = {"servers": [], "clock_s": 0.0, "nav": {}, "truth": {}, "lost": [], "taken": []}


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


def on_team(_c, d):
    m = team_event_t.decode(d)
    if m.kind in (team_event_t.PEER_LOST, team_event_t.LINES_TAKEN):
        key = "lost" if m.kind == team_event_t.PEER_LOST else "taken"
        view[key].append([m.utime / 1e6, m.vehicle, m.origin, m.text])


lc = lcm.LCM(url)
lc.subscribe("SIM.CLOCK", on_clock)
for v in vehicles:
    lc.subscribe(f"{v}.CHASM.NAVIGATOR", on_nav)
    lc.subscribe(f"{v}.TRUTH", on_truth)
    lc.subscribe(f"{v}.TEAM_EVENT", on_team)
signal.signal(signal.SIGINT, lambda *_: sys.exit(0))
signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
next_print = 0.0
while True:
    try:
        lc.handle_timeout(50)
    except OSError:  # interrupted by a signal: the handler exits
        continue
    if time.monotonic() >= next_print:
        next_print = time.monotonic() + 0.3
        print(json.dumps(view), flush=True)
