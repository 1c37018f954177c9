"""The in-process pilot (sim.pilot: libauvpilot.so through ctypes) flies the
pilot's law: the same inputs, cycle by cycle, through missions/pilot/pilot.chasm
run by libchasm with the pilot plugin (`chasm run`), and through the library
with the gains sim.pilot reads from that plan, give the same fin and prop
commands. The inputs sweep the limits: heading across north and steps past
the turn-rate limit, depth steps that saturate the pitch command, pitch
setpoints past max_pitch, rpm past max_rpm, a stop, speed through the water.

`chasm run` prints 6 significant digits; the library's command must match to
that precision at every cycle (a different law, start or gain would not)."""

from __future__ import annotations

import math
import re
import subprocess

import numpy as np
import pytest
from conftest import ROOT, c_program

from sim.pilot import Pilot, plan_gains

PLAN = ROOT / "missions" / "pilot" / "pilot.chasm"
DT = 0.05
SECONDS = 40.0
OUT = ("actuators.rudder_rad", "actuators.stern_plane_rad", "actuators.prop_rpm")
LINE = re.compile(r"^\s*(\d+\.\d+) s  (\S+)")


def scenario(vertical: int, speed_mode: int, reference: int, seed: int) -> list[dict[str, float]]:
    """One row of inputs per cycle: a noisy vehicle and stepped setpoints."""
    rng = np.random.default_rng(seed)
    rows = []
    for k in range(int(SECONDS / DT) + 1):
        t = k * DT
        rows.append(
            {
                "nav.heading_rad": (0.4 * math.sin(0.15 * t) + 0.02 * rng.standard_normal()) % (2 * math.pi),
                "nav.r_radps": 0.05 * math.cos(0.15 * t) + 0.01 * rng.standard_normal(),
                "nav.depth_m": 10.0 + 3.0 * math.sin(0.08 * t) + 0.05 * rng.standard_normal(),
                "nav.altitude_m": 20.0,
                "nav.pitch_rad": 0.1 * math.sin(0.3 * t) + 0.01 * rng.standard_normal(),
                "nav.q_radps": 0.03 * math.cos(0.3 * t) + 0.005 * rng.standard_normal(),
                "nav.u_mps": 1.4 + 0.1 * math.sin(0.2 * t) + 0.02 * rng.standard_normal(),
                "setpoint.heading_rad": 0.1 if t < 5 else 1.6 if t < 15 else 6.1 if t < 30 else 3.0,
                "setpoint.depth_m": 10.0 if t < 4 else 16.0 if t < 20 else 4.0,
                "setpoint.altitude_m": 8.0,
                "setpoint.pitch_rad": -0.1 if t < 10 else 0.4 if t < 25 else 0.05,
                "setpoint.speed_mps": 1.5 if t < 20 else 0.0 if t < 26 else 1.2,
                "setpoint.prop_rpm": 1200.0 if t < 15 else 3000.0 if t < 30 else 0.0,
                "setpoint.vertical_mode": vertical,
                "setpoint.speed_mode": speed_mode,
                "setpoint.speed_reference": reference,
                "setpoint.utime": int(round(t * 1e6)),
            }
        )
    return rows


def run_plan(tmp_path, rows: list[dict[str, float]]) -> list[tuple[float, str, list[float]]]:
    """The plan with the plugin, a line per cycle: (t, leaf, commands)."""
    names = list(rows[0])
    csv = tmp_path / "in.csv"
    csv.write_text(
        "time,"
        + ",".join(names)
        + "\n"
        + "".join(f"{k * DT!r}," + ",".join(repr(r[n]) for n in names) + "\n" for k, r in enumerate(rows))
    )
    watch = [a for name in OUT for a in ("--watch", name)]
    p = subprocess.run(
        [str(c_program("bin/chasm")), "run", "-P", str(c_program("plugins")), str(PLAN), "--inputs", str(csv)]
        + ["--dt", str(DT), "--until", str(SECONDS), "--trace", *watch],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr
    lines = []
    for text in p.stdout.splitlines():
        m = LINE.match(text)
        values = [re.search(rf" {re.escape(n)}=(\S+)", text) for n in OUT]
        if m and all(values):
            lines.append((float(m.group(1)), m.group(2), [float(v.group(1)) for v in values]))
    return lines


@pytest.mark.parametrize(
    "vertical,speed_mode,reference,leaf",
    [(0, 0, 0, "fly/mps/depth"), (2, 1, 0, "fly/rpm/pitch"), (0, 0, 1, "fly/mps/depth")],
    ids=["depth-speed", "pitch-rpm", "through-water"],
)
def test_the_library_gives_the_plugins_commands(tmp_path, vertical, speed_mode, reference, leaf):
    rows = scenario(vertical, speed_mode, reference, seed=7 + vertical + speed_mode + reference)
    lines = run_plan(tmp_path, rows)
    assert lines and lines[-1][1] == leaf, lines[-1:]
    pilot = Pilot(plan_gains(PLAN))
    # A behavior starts in the cycle the plan enters its state, from the
    # actuator's command then, and steps from the next cycle on, the first
    # step with dt = 0 (libchasm's ctx.dt_s); the plan enters `fly`
    # (heading) a cycle before its leaf. cycles: of each, steps taken so far
    # (None: not started).
    cycles: dict[str, int | None] = {"heading": None, "leaf": None}
    last = [0.0, 0.0, 0.0]
    compared = 0
    for t, path, got in lines:
        r = rows[int(round(t / DT))]
        want = list(last)
        if path.startswith("fly"):
            if cycles["heading"] is None:
                pilot.start_heading(last[0])
                cycles["heading"] = 0
            else:
                pilot.dt = DT if cycles["heading"] else 0.0
                want[0] = pilot.rudder(r["setpoint.heading_rad"], r["nav.heading_rad"], r["nav.r_radps"])
                cycles["heading"] += 1
        if path == leaf:
            if cycles["leaf"] is None:
                pilot.start_vertical(r["nav.pitch_rad"], last[1])
                pilot.start_prop(last[2])
                cycles["leaf"] = 0
            else:
                pilot.dt = DT if cycles["leaf"] else 0.0
                nav = (r["nav.pitch_rad"], r["nav.q_radps"])
                if vertical == 0:
                    want[1] = pilot.stern_for_depth(r["setpoint.depth_m"], r["nav.depth_m"], *nav)
                else:
                    want[1] = pilot.stern_for_pitch(r["setpoint.pitch_rad"], *nav)
                if speed_mode == 0:
                    want[2] = pilot.prop(r["setpoint.speed_mps"], r["nav.u_mps"], through_water=reference == 1)
                else:
                    want[2] = pilot.prop_rpm(r["setpoint.prop_rpm"])
                cycles["leaf"] += 1
                compared += 1
        assert got == pytest.approx(want, rel=2e-5, abs=1e-8), f"t = {t:.2f} s in {path}"
        last = got
    assert compared > 0.9 * SECONDS / DT
