"""Run inside a test's network namespace: exit 0 once every named vehicle's
NAVIGATOR reports DONE, 1 at the timeout (printing what it saw).

    watch_done.py URL TIMEOUT_S VEHICLE...
"""

import sys
import time

import lcm

from auv import chasm_status_t, sim_clock_t

url, timeout, vehicles = sys.argv[1], float(sys.argv[2]), sys.argv[3:]
state: dict[str, int] = {}
servers: list[str] = []
lc = lcm.LCM(url)
for v in vehicles:
    lc.subscribe(
        f"{v}.CHASM.NAVIGATOR",
        lambda _c, d: state.__setitem__(*(lambda m: (m.vehicle, m.run_state))(chasm_status_t.decode(d))),
    )
lc.subscribe(
    "SIM.CLOCK",
    lambda _c, d: (lambda m: servers.append(m.server_id) if not servers or servers[-1] != m.server_id else None)(
        sim_clock_t.decode(d)
    ),
)
deadline = time.monotonic() + timeout
while time.monotonic() < deadline:
    lc.handle_timeout(100)
    if all(state.get(v) == chasm_status_t.RUN_DONE for v in vehicles):
        print(f"done: {' '.join(vehicles)}; clock from {' '.join(servers)}", flush=True)
        sys.exit(0)
print(f"timeout: states {state}; clock from {servers}", flush=True)
sys.exit(1)
