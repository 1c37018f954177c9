"""gpsd (Debian's) reads the GPS emulator's NMEA on its pty, and its fixes are the
simulator's: the measurement to the centimetre, the truth within the GPS noise.

The simulator runs as its own process (`python -m sim`) publishing GPS and TRUTH on
LCM beside the NMEA; gpsd listens on localhost, inside the test's network namespace.
`make test` installs gpsd where it runs as root (the Makefile's `gpsd` target).
"""

from __future__ import annotations

import json
import math
import shutil
import socket
import subprocess
import time
from datetime import datetime, timezone

import lcm
import pytest
from lcm_proc import start_simulator, stop

from auv import gps_fix_t, ground_truth_t
from auvlcm.rx import Receiver
from sim.geo import radii

GPSD = shutil.which("gpsd") or shutil.which("gpsd", path="/usr/sbin:/sbin")
pytestmark = pytest.mark.skipif(
    GPSD is None, reason="gpsd is not installed (`make test` installs Debian's gpsd when run as root)"
)

NOISE_M = 1.0
START = datetime(2025, 6, 1, tzinfo=timezone.utc)
CONFIG = """
vehicle: {{id: AUV1}}
simulation: {{clock: scaled, warp: 4, duration_s: 40, truth_rate_hz: 10, lcm_url: "{url}"}}
initial: {{speed_mps: 1.5, prop_rpm: 1500, heading_rad: 0.5}}
environment: {{seed: 11, bathymetry: "flat:depth=50"}}
sensors:
  gps:
    noise: {noise}
    wire: {{protocol: nmea, pty: gps0, baud: 9600, talker: GN}}
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def gpsd_client(port: int) -> socket.socket:
    deadline = time.monotonic() + 10
    while True:
        try:
            sock = socket.create_connection(("127.0.0.1", port), timeout=1)
            break
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.1)
    sock.sendall(b'?WATCH={"enable":true,"json":true}\n')
    sock.setblocking(False)
    return sock


def test_gpsd_fixes_agree_with_the_simulator(tmp_path, child_env, lcm_url):
    (tmp_path / "sim.yaml").write_text(CONFIG.format(url=lcm_url, noise=NOISE_M))
    lc = lcm.LCM(lcm_url)
    rx = Receiver(lc)
    fixes: dict[int, gps_fix_t] = {}
    truth: dict[int, ground_truth_t] = {}
    rx.subscribe("AUV1.GPS", gps_fix_t, lambda ch, m: fixes.__setitem__(m.utime, m), queue_capacity=1000)
    rx.subscribe("AUV1.TRUTH", ground_truth_t, lambda ch, m: truth.__setitem__(m.utime, m), queue_capacity=5000)
    sim = start_simulator(tmp_path / "sim.yaml", child_env)
    port = free_port()
    gpsd = subprocess.Popen(
        [GPSD, "-N", "-n", "-b", "-S", str(port), str(tmp_path / "gps0")],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    tpv: dict[str, dict] = {}  # by time: the last report of each fix (gpsd refines it sentence by sentence)
    try:
        client = gpsd_client(port)
        buf = b""
        ended = None
        while ended is None or time.monotonic() < ended + 0.5:  # and what is on its way when it ends
            if ended is None and sim.poll() is not None:
                ended = time.monotonic()
            lc.handle_timeout(20)
            try:
                buf += client.recv(65536)
            except BlockingIOError:
                pass
            *lines, buf = buf.split(b"\n")
            for line in lines:
                report = json.loads(line)
                if report.get("class") == "TPV" and report.get("mode", 0) >= 2 and "time" in report:
                    tpv[report["time"]] = report
        client.close()
    finally:
        gpsd.terminate()
        gpsd_err = gpsd.communicate(timeout=10)[1]
        assert stop(sim) == 0
    out = sim.stdout.read()
    assert "gps nmea on pty" in out, out
    assert len(tpv) >= 6, f"gpsd reported {len(tpv)} fixes\n{gpsd_err}\n{out}"

    lat0 = next(iter(fixes.values())).latitude_deg
    rm, rn = radii(lat0)
    m_per_deg = (math.radians(1) * rm, math.radians(1) * rn * math.cos(math.radians(lat0)))
    to_measured, to_truth, speed_err = [], [], []
    for stamp, r in sorted(tpv.items()):
        t = datetime.fromisoformat(stamp.replace("Z", "+00:00"))
        utime = round((t - START).total_seconds() * 1e6)
        fix, tr = fixes[utime], truth[utime]  # the fix gpsd read is one the simulator made
        to_measured.append(
            math.hypot((r["lat"] - fix.latitude_deg) * m_per_deg[0], (r["lon"] - fix.longitude_deg) * m_per_deg[1])
        )
        to_truth.append(((r["lat"] - tr.latitude_deg) * m_per_deg[0], (r["lon"] - tr.longitude_deg) * m_per_deg[1]))
        if "speed" in r:
            speed_err.append(r["speed"] - math.hypot(tr.nu[0], tr.nu[1]))
    errs = [e for pair in to_truth for e in pair]
    rms = math.sqrt(sum(e * e for e in errs) / len(errs))
    print(
        f"gpsd: {len(tpv)} fixes; to the measurement: max {max(to_measured) * 100:.2f} cm; "
        f"to the truth: per-axis RMS {rms:.2f} m (noise {NOISE_M} m), max {max(math.hypot(*p) for p in to_truth):.2f} m; "
        f"speed: max error {max(map(abs, speed_err)):.3f} m/s"
    )
    assert max(to_measured) < 0.03  # NMEA carries 1e-5 minute (under 2 cm)
    assert max(math.hypot(*p) for p in to_truth) < 5 * NOISE_M
    assert 0.3 * NOISE_M < rms < 2.5 * NOISE_M  # the fixes carry the GPS noise, not the truth
    assert speed_err and max(map(abs, speed_err)) < 0.3
