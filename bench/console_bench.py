"""Console server benchmark: prints figures, asserts nothing.

The console (python/tools/console/cli.py) serves pages while 8 vehicles publish
their state over LCM (ttl=0): TRUTH, NAV, NAV_STATUS, two managers' CHASM
status and MODEM_STATUS per vehicle at RATE Hz, SIM.CLOCK at 20 Hz, a contact
a second per vehicle and a modem frame heard every 2 s. PAGES event streams
are read as a browser would. Figures: the server's CPU (user + system, from
/proc, as % of one core), page updates per second and bytes per second per
page. The issue asks for under 10 % of a core at 8 vehicles x 5 Hz.
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


def cpu_s(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def messages(vid: str, i: int, utime: int) -> list[tuple[str, object]]:
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
        out.append((f"{vid}.CHASM.{mgr}", st))
    ms = modem_status_t()
    ms.utime, ms.vehicle, ms.sent, ms.received = utime, vid, i // 10, i // 12
    out.append((f"{vid}.MODEM_STATUS", ms))
    return out


def publish(lc: lcm.LCM, rate: float, stop: threading.Event) -> None:
    i, t0 = 0, time.monotonic()
    while not stop.is_set():
        utime = int(i / rate * 1e6)
        for vid in VEHICLES:
            for ch, m in messages(vid, i, utime):
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


def run(rate: float, pages: int) -> None:
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
    threads = [threading.Thread(target=publish, args=(lc, rate, stop), daemon=True)]
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
        f"  8 vehicles x {rate:4.0f} Hz ({n_msgs:5.0f} msg/s), {pages} page(s): server CPU "
        f"{100 * (c1 - c0) / wall:5.1f} % of a core; per page {ups:4.1f} updates/s, {bps / 1024:6.1f} kB/s"
    )


def main() -> None:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    print(f"console server, {SECONDS:.0f} s per case (updates pushed at most 5 Hz per page)")
    for rate, pages in ((5, 1), (5, 3), (25, 1)):
        run(rate, pages)


if __name__ == "__main__":
    main()
