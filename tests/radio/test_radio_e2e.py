"""The surface radio over real processes: a chasm-manager, the radio model
(python -m sim.radio), the shore and vehicle gateways, on one LCM world. The
vehicle's gateway is the vehicle's driver, auv-radio, on the radio modem's
pty that the model makes (its byte pipe, as at sea). The test drives the
clock and the vehicle (AUV1.NAV for the software, AUV1.TRUTH for the radio) as a simulator would, and publishes what the operator's tool
would on the shore's side (SHORE.AUV1.*).

- a vehicle out of range: the upload waits, queued;
- an upload started at the surface, cut by a dive (the vehicle's gateway
  restarting down there), completed at the next surfacing from what its spool
  held, then used by a plan (`use test_other`) loaded over the radio;
- that plan is larger than one surfacing window;
- an abort delivered acoustically to the vehicle at depth (the shore modem's
  frame goes into SIM.ACOUSTIC from the radio model; the test stands for the
  vehicle's simulated modem and hands it on as AUV1.MODEM_RX), acknowledged
  home at the next surfacing.
"""

from __future__ import annotations

import hashlib
import signal
import subprocess
import sys
import time

from conftest import BUILD
from lcm_proc import pump, stop, wait_for_line
from test_manager import PERIOD_US, World, start_manager

from auv import (
    acoustic_frame_t,
    ground_truth_t,
    mission_ack_t,
    mission_command_t,
    modem_rx_t,
    nav_solution_t,
    plugin_upload_t,
    radio_link_t,
    radio_report_t,
    sim_clock_t,
)
from auv import (
    radio_command_status_t as cs,
)
from auvlcm import programs

PACE_S = 0.006  # wall seconds per 0.05 s step
BITRATE = 20000.0  # bit/s: the plugin takes seconds of air


def _show(m) -> str:
    return f"state {m.state} held {m.bytes_held}/{m.bytes_total} {m.message!r}" if m is not None else "none"


class Sea(World):
    """World's clock and NAV, plus where the vehicle truly is, for the radio."""

    def __init__(self, url: str) -> None:
        super().__init__(url)
        self.north = 0.0
        self.status_by: dict[int, list] = {}
        self.reports: list = []
        self.links: list = []
        self.frames: list = []
        self.rx.subscribe(
            "SHORE.AUV1.RADIO_CMD_STATUS", cs, lambda c, m: self.status_by.setdefault(m.seq, []).append(m)
        )
        self.rx.subscribe("SHORE.AUV1.RADIO_REPORT", radio_report_t, lambda c, m: self.reports.append(m))
        self.rx.subscribe("AUV1.RADIO_LINK", radio_link_t, lambda c, m: self.links.append(m))
        self.rx.subscribe("SIM.ACOUSTIC", acoustic_frame_t, lambda c, m: self.frames.append(m))

    def tick(self, dt_s: float, depth: float | None = None) -> None:
        """World.tick, waiting for a cycle within the last period rather than on
        the old grid: a plan loaded over the radio starts its cycles at the
        command's step, off the grid the first plan ran on."""
        self.utime += int(dt_s * 1e6)
        nav = nav_solution_t()
        nav.utime, nav.vehicle, nav.depth_m = self.utime, "AUV1", depth
        self.lc.publish("AUV1.NAV", nav.encode())
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.step_us = self.utime, "test", int(dt_s * 1e6)
        self.lc.publish("SIM.CLOCK", clock.encode())
        if not self.status:  # still starting: nothing is due
            pump(self.lc, lambda: bool(self.status), timeout=0.05)
            return
        ok = pump(self.lc, lambda: self.status[-1].utime > self.utime - PERIOD_US, timeout=30)
        assert ok, f"the manager ran no cycle up to {self.utime} us"

    def sail(self, seconds: float, depth: float, until=lambda: False) -> bool:
        end = self.utime + int(seconds * 1e6)
        while self.utime < end:
            t = ground_truth_t()
            t.utime, t.vehicle = self.utime + 50_000, "AUV1"
            t.eta = [self.north, 0.0, depth, 0.0, 0.0, 0.0]
            self.lc.publish("AUV1.TRUTH", t.encode())
            self.tick(0.05, depth=depth)
            # the radio model reports every step: wait for it, as tick() waits for the manager
            deadline = time.monotonic() + 30
            while not (self.links and self.links[-1].utime >= self.utime):
                assert time.monotonic() < deadline, "the radio model fell behind"
                self.lc.handle_timeout(5)
            # the gateways follow the clock on their own: a few ms of wall time per step for them
            # (about x8 real time), or a slow one would send at the surface what arrives after a dive
            pace = time.monotonic() + PACE_S
            while time.monotonic() < pace:
                self.lc.handle_timeout(1)
            self._hear_acoustic()
            if until():
                return True
        return False

    def _hear_acoustic(self) -> None:
        for f in self.frames:
            rx = modem_rx_t()
            rx.utime, rx.vehicle, rx.src_vehicle, rx.dst_vehicle = self.utime, "AUV1", f.src_vehicle, f.dst_vehicle
            rx.seq, rx.kind, rx.tx_utime, rx.n_bytes, rx.payload = f.seq, f.kind, f.utime, f.n_bytes, f.payload
            self.lc.publish("AUV1.MODEM_RX", rx.encode())
        self.frames.clear()

    def last(self, seq: int):
        return self.status_by.get(seq, [None])[-1]


def _procs(url: str, env: dict, spool) -> list[subprocess.Popen]:
    pty = spool.parent / "AUV1.radio.pty"  # the vehicle's radio modem, made by the model
    cmds = [
        programs.radio_sim(
            vehicles=["AUV1"],
            lcm_url=url,
            settings={"bitrate_bps": BITRATE, "max_range_m": 1000.0, "status_period_s": 0.05},
            pipes={"AUV1": pty},
        ),
        programs.radio_shore(vehicles=["AUV1"], lcm_url=url, acoustic={"AUV1": 0}, link_timeout_s=1.0, retry_s=1.0),
        programs.radio_vehicle(
            BUILD, vehicle="AUV1", spool=spool, lcm_url=url, port=pty, team_index=0, report_period_s=0.3
        ),
    ]
    procs = [subprocess.Popen(c, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for c in cmds]
    for p in procs:
        wait_for_line(p, ": ready", timeout=30)
    return procs


def test_upload_cut_by_a_dive_resumes_then_a_plan_uses_it_and_an_abort_goes_acoustically(lcm_url, child_env, tmp_path):
    other = (BUILD / "plugins" / "chasm_test_other.so").read_bytes()
    pdir, allow, spool = tmp_path / "uploads", tmp_path / "allowlist", tmp_path / "spool"
    pdir.mkdir()
    allow.write_text(f"{hashlib.sha256(other).hexdigest()} test_other\n")
    child_env["TMPDIR"] = str(tmp_path)
    w = Sea(lcm_url)
    mgr = start_manager(lcm_url, child_env, extra=["--plugin-dir", pdir, "--allowlist", allow])
    procs = _procs(lcm_url, child_env, spool)
    try:
        w.north = 5000.0  # at the surface, out of range
        w.wait_for_first_cycle()
        up = plugin_upload_t()
        up.utime, up.vehicle, up.seq, up.plugin_name, up.plugin_version = w.utime, "AUV1", 501, "test_other", "2"
        up.sha256_hex, up.n_bytes, up.data = hashlib.sha256(other).hexdigest(), len(other), other
        w.lc.publish("SHORE.AUV1.PLUGIN_UPLOAD", up.encode())
        w.sail(3.0, 0.0)
        assert w.last(501).state == cs.STATE_QUEUED and w.last(501).bytes_held == 0
        assert w.links and not w.links[-1].up and w.links[-1].antenna_clear and w.links[-1].range_m == 5000.0
        assert not w.reports  # nothing heard from it

        w.north = 100.0  # in range: the upload starts ...
        assert w.sail(20.0, 0.0, lambda: 0 < (w.last(501).bytes_held or 0)), w.status_by
        assert w.sail(20.0, 0.0, lambda: w.last(501).bytes_held > 1000), w.last(501)
        assert w.reports and w.reports[-1].mission.startswith("RUNNING")
        w.sail(3.0, 8.0)  # ... and a dive cuts it
        held = w.last(501).bytes_held
        assert w.last(501).state == cs.STATE_IN_FLIGHT and 0 < held < len(other), held
        assert list(pdir.iterdir()) == [] and w.links[-1].up is False
        assert [p.suffix for p in spool.iterdir() if p.suffix == ".part"] == [".part"]
        # the vehicle's gateway restarts while down there: it holds the chunks in its spool
        assert stop(procs[2], signal.SIGTERM) == 0
        first_life = procs[2].stderr.read()
        procs[2] = subprocess.Popen(
            procs[2].args, env=child_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        wait_for_line(procs[2], ": ready", timeout=30)
        # at the next surfacing it resumes from what the vehicle holds, and the manager loads it
        assert w.sail(40.0, 0.0, lambda: w.last(501).state == cs.STATE_ACKNOWLEDGED), _show(w.last(501))
        assert "NAVIGATOR ok" in w.last(501).message, w.last(501).message
        assert (pdir / "chasm_test_other.so").read_bytes() == other
        assert not list(spool.glob("*.part"))

        # a plan larger than one surfacing window, using the plugin
        plan = tmp_path / "plan.chasm"
        text = (BUILD.parent / "tests" / "managers" / "dive.chasm").read_text()
        text = text.replace('mission "manager test"', 'mission "radio test"\nuse test_other')
        text = text.replace("    when deep -> hold\n", "")  # it dives and stays down: a plan the abort ends
        text += "".join(
            f"# padding line {i:05d} so the plan spans more than one surfacing window\n" for i in range(250)
        )
        plan.write_text(text)
        cmd = mission_command_t()
        cmd.utime, cmd.vehicle, cmd.seq, cmd.command = w.utime, "AUV1", 502, mission_command_t.CMD_LOAD_PLAN
        cmd.plan_name, cmd.plan_text, cmd.reason = "radio.chasm", text, "test"
        w.lc.publish("SHORE.AUV1.MISSION_CMD", cmd.encode())
        assert w.sail(20.0, 0.0, lambda: (w.last(502) and w.last(502).bytes_held or 0) > 0)
        w.sail(0.4, 0.0)
        w.sail(3.0, 8.0)
        assert 0 < w.last(502).bytes_held < len(cmd.encode()), w.last(502)
        assert w.sail(40.0, 0.0, lambda: w.last(502).state == cs.STATE_ACKNOWLEDGED), _show(w.last(502))
        assert "NAVIGATOR ok" in w.last(502).message, w.last(502).message
        print("load:", w.last(502).message, file=sys.stderr)

        # an abort at depth goes through the water, and its answer comes home at the surface
        w.sail(3.0, 8.0)
        ctl = subprocess.Popen(
            [sys.executable, "-m", "tools.console.auvctl", "--lcm-url", lcm_url, "--timeout", "60", "--shore"]
            + ["abort", "AUV1", "--reason", "test"],
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        assert w.sail(30.0, 8.0, lambda: len(w.status_by) > 2), "auvctl sent nothing"
        seq = next(s for s in w.status_by if s not in (501, 502))
        assert w.sail(20.0, 8.0, lambda: w.leaf() == "surface"), w.leaf()
        assert w.last(seq).route == "acoustic" and w.last(seq).state == cs.STATE_IN_FLIGHT
        counter = seq & 0xFFFFFF
        assert any(a.seq == counter and a.result == mission_ack_t.RESULT_OK for a in w.acks)
        assert w.sail(40.0, 0.0, lambda: w.last(seq).state == cs.STATE_ACKNOWLEDGED), _show(w.last(seq))
        out, err = ctl.communicate(timeout=30)
        assert ctl.returncode == 0, out + err
        assert "AUV1 abort (acoustic): in flight" in out and "acknowledged: NAVIGATOR ok: aborting" in out, out
    finally:
        codes = [stop(p, signal.SIGTERM) for p in procs]
        errs = [p.stderr.read() for p in procs]
        print("\n".join(errs), file=sys.stderr)
        code = stop(mgr, signal.SIGTERM)
        print("MANAGER:", code, mgr.stderr.read()[-2000:], file=sys.stderr)
        assert code == 0
    assert codes == [0, 0, 0], errs
    assert "auv-radio AUV1: delivered 0, acoustic commands 0" in first_life, first_life
    assert "auv-radio AUV1: delivered 2, acoustic commands 1" in errs[2], errs[2]
    assert "unknown transfer" not in errs[2], errs[2]  # it resumed from its spool, never from chunk 0
