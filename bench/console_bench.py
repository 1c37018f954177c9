"""Console server benchmark: prints figures, asserts nothing.

The console (python/tools/console/cli.py) serves pages while 8 vehicles publish
their state over LCM (ttl=0): TRUTH, NAV, NAV_STATUS, two managers' CHASM
status and MODEM_STATUS per vehicle at RATE Hz, SIM.CLOCK at 20 Hz, a contact
a second per vehicle and a modem frame heard every 2 s. PAGES event streams
are read as a browser would. Figures: the server's CPU (user + system, from
/proc, as % of one core), page updates per second and bytes per second per
page. The issue asks for under 10 % of a core at 8 vehicles x 5 Hz. The state
view's case (issue 35 asks for under 5 % of a core): each of the 16 managers
also sends its plan's structure (STATES states, chasm_structure_t, once and
again every 10 s like a manager) and statuses with its plan_id, 24 live test
values and 64 variables.
Run: tests/isolated_net.sh .venv/bin/python bench/console_bench.py
"""

from __future__ import annotations

import argparse
import http.client
import math
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import lcm

from auv import (
    chasm_status_t,
    chasm_structure_t,
    ground_truth_t,
    modem_rx_t,
    modem_status_t,
    nav_filter_status_t,
    nav_solution_t,
    sidescan_contact_t,
    sim_clock_t,
)

ROOT = Path(__file__).resolve().parents[1]

URL = "udpm://239.255.76.67:7793?ttl=0"
SECONDS = float(os.environ.get("CONSOLE_BENCH_SECONDS", 15))
VEHICLES = [f"AUV{i}" for i in range(1, 9)]
STATES = int(os.environ.get("CONSOLE_BENCH_STATES", 100))
PLAN_ID = "00c0ffee00c0ffee"


def structure(vid: str, mgr: str, n: int = STATES) -> chasm_structure_t:
    """A plan of n states: phases of 9 legs each, a transition per leg and an abort."""
    s = chasm_structure_t()
    s.utime, s.vehicle, s.manager, s.plan, s.plan_id = 0, vid, mgr, "bench.chasm", PLAN_ID
    paths, parents = [], []
    for i in range(n):
        if i % 10 == 0:
            paths.append(f"phase{i // 10}")
            parents.append(-1)
        else:
            paths.append(f"phase{i // 10}/leg{i % 10}")
            parents.append(i - i % 10)
    s.n_states, s.state_path, s.state_parent = n, paths, parents
    s.state_name = [p.rsplit("/", 1)[-1] for p in paths]
    s.state_default_child = [i + 1 if i % 10 == 0 and i + 1 < n else -1 for i in range(n)]
    s.state_next, s.state_next_done = [-1] * n, [False] * n
    s.state_loc = [f"bench.chasm:{i + 1}:7" for i in range(n)]
    s.initial_state = 0
    trans = [(-1, 0)] + [(i, (i + 1) % n) for i in range(n) if i % 10]
    s.n_transitions = len(trans)
    s.trans_from, s.trans_to = [f for f, _ in trans], [t for _, t in trans]
    s.trans_history = [0] * len(trans)
    s.trans_condition = ["stale"] + ["at_end and not lost"] * (len(trans) - 1)
    s.trans_first_test = [0] + [1 + 2 * k for k in range(len(trans) - 1)]
    s.trans_n_tests = [1] + [2] * (len(trans) - 1)
    s.trans_loc = [f"bench.chasm:{k + 1}:5" for k in range(len(trans))]
    s.trans_test_name = ["stale"] + ["at_end", "lost"] * (len(trans) - 1)
    s.n_trans_tests = len(s.trans_test_name)
    s.n_vars = 64
    s.var_name = [f"v{k}" for k in range(64)]
    s.var_kind, s.var_type, s.var_unit = [k % 3 for k in range(64)], ["double"] * 64, ["m"] * 64
    return s


def cpu_s(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def messages(vid: str, i: int, utime: int, view: bool = False) -> list[tuple[str, object]]:
    k = VEHICLES.index(vid)
    ang = 0.02 * i + k
    n, e = 100 * math.sin(ang) + 30 * k, 100 * math.cos(ang)
    tr = ground_truth_t()
    tr.utime, tr.vehicle, tr.eta = utime, vid, [n, e, 10.0, 0.0, 0.0, ang]
    nav = nav_solution_t()
    nav.utime, nav.vehicle, nav.north_m, nav.east_m, nav.heading_rad, nav.status = utime, vid, n + 1, e, ang, 3
    ns = nav_filter_status_t()
    ns.utime, ns.vehicle, ns.trusted, ns.position_sigma_m = utime, vid, True, 1.5
    out = [(f"{vid}.TRUTH", tr), (f"{vid}.NAV", nav), (f"{vid}.NAV_STATUS", ns)]
    for mgr in ("NAVIGATOR", "PILOT"):
        st = chasm_status_t()
        st.utime, st.vehicle, st.manager, st.plan, st.run_state, st.cycle = utime, vid, mgr, "p.chasm", 1, i
        st.active_path = ["mission", "survey", f"line{i // 50}"]
        st.path_len, st.time_in_state_s = 3, [i * 0.2, i * 0.1, 1.0]
        st.last_from, st.last_to, st.last_condition = "mission/survey/a", "mission/survey/b", "at_end and not lost"
        st.test_name, st.test_value, st.n_tests = ["at_end", "lost"], [True, False], 2
        if view:  # the state view's fields: a leg of the 100-state plan, its tests, the variables
            leg = i // 10 % (STATES - 1) + 1
            leg += leg % 10 == 0
            st.active_path = [f"phase{leg // 10}", f"leg{leg % 10}"]
            st.path_len, st.time_in_state_s = 2, [i * 0.2, 1.0]
            st.plan_id = PLAN_ID
            st.live_test_value = [False, i % 7 == 0, False]
            st.n_live_tests = 3
            st.var_value, st.n_var_values = [float(i + k) for k in range(64)], 64
        out.append((f"{vid}.CHASM.{mgr}", st))
    ms = modem_status_t()
    ms.utime, ms.vehicle, ms.sent, ms.received = utime, vid, i // 10, i // 12
    out.append((f"{vid}.MODEM_STATUS", ms))
    return out


def publish(lc: lcm.LCM, rate: float, stop: threading.Event, view: bool = False) -> None:
    i, t0 = 0, time.monotonic()
    plans = {(v, m): structure(v, m).encode() for v in VEHICLES for m in ("NAVIGATOR", "PILOT")} if view else {}
    while not stop.is_set():
        utime = int(i / rate * 1e6)
        if i % int(10 * rate) == 0:  # as a manager does: at start, then every 10 s
            for (v, m), data in plans.items():
                lc.publish(f"{v}.PLAN.{m}", data)
        for vid in VEHICLES:
            for ch, m in messages(vid, i, utime, view):
                lc.publish(ch, m.encode())
            if i % int(rate) == 0:
                c = sidescan_contact_t()
                c.utime, c.vehicle, c.contact_id, c.classification = utime, vid, i, "mine_like"
                c.north_m, c.east_m = 50.0 + i % 97, 20.0 + i % 89
                lc.publish(f"{vid}.CONTACTS", c.encode())
            if i % int(2 * rate) == 0:
                rx = modem_rx_t()
                rx.utime, rx.vehicle, rx.src_vehicle = utime, vid, VEHICLES[(VEHICLES.index(vid) + 1) % 8]
                lc.publish(f"{vid}.MODEM_RX", rx.encode())
        for _ in range(max(1, round(20 / rate))):
            clk = sim_clock_t()
            clk.utime = utime
            lc.publish("SIM.CLOCK", clk.encode())
        i += 1
        time.sleep(max(0.0, t0 + i / rate - time.monotonic()))


def read_page(port: int, stats: dict, stop: threading.Event) -> None:
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    conn.request("GET", "/api/events")
    r = conn.getresponse()
    while not stop.is_set():
        line = r.readline()
        if not line:
            break
        stats["bytes"] += len(line)
        if line.startswith(b"data: "):
            stats["updates"] += 1


def run(rate: float, pages: int, view: bool = False) -> None:
    env = dict(os.environ)
    proc = subprocess.Popen(
        [sys.executable, "-m", "tools.console", "--lcm-url", URL, "--port", "0"],
        env=env,
        stdout=subprocess.PIPE,
        text=True,
    )
    port = int(proc.stdout.readline().split("http://", 1)[1].split("/")[0].rsplit(":", 1)[1])
    stop = threading.Event()
    stats = [{"bytes": 0, "updates": 0} for _ in range(pages)]
    lc = lcm.LCM(URL)
    threads = [threading.Thread(target=publish, args=(lc, rate, stop, view), daemon=True)]
    threads += [threading.Thread(target=read_page, args=(port, s, stop), daemon=True) for s in stats]
    for t in threads:
        t.start()
    time.sleep(3.0)  # warm up: imports done, trails growing
    c0, w0 = cpu_s(proc.pid), time.monotonic()
    b0 = [dict(s) for s in stats]
    time.sleep(SECONDS)
    c1, w1 = cpu_s(proc.pid), time.monotonic()
    b1 = [dict(s) for s in stats]
    stop.set()
    proc.terminate()
    proc.wait(timeout=10)
    wall = w1 - w0
    ups = sum(b["updates"] - a["updates"] for a, b in zip(b0, b1)) / pages / wall
    bps = sum(b["bytes"] - a["bytes"] for a, b in zip(b0, b1)) / pages / wall
    n_msgs = len(VEHICLES) * 6 * rate + 20
    print(
        f"  8 vehicles x {rate:4.0f} Hz ({n_msgs:5.0f} msg/s), {pages} page(s)"
        + (f", 16 plans of {STATES} states" if view else "")
        + ": server CPU "
        f"{100 * (c1 - c0) / wall:5.1f} % of a core; per page {ups:4.1f} updates/s, {bps / 1024:6.1f} kB/s"
    )


def main() -> None:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    print(f"console server, {SECONDS:.0f} s per case (updates pushed at most 5 Hz per page)")
    for rate, pages, view in ((5, 1, False), (5, 3, False), (25, 1, False), (2, 1, True), (5, 1, True), (5, 3, True)):
        run(rate, pages, view)


if __name__ == "__main__":
    main()
