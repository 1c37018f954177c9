"""The surface radio over real processes: a chasm-manager, the radio model
(python -m sim.radio), the shore and vehicle gateways, on one LCM world. The
test drives the clock and the vehicle (AUV1.NAV for the software, AUV1.TRUTH
for the radio) as a simulator would, and publishes what the operator's tool
would on the shore's side (SHORE.AUV1.*).

- a vehicle out of range: the upload waits, queued;
- an upload started at the surface, cut by a dive, completed at the next
  surfacing, then used by a plan (`use test_other`) loaded over the radio;
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

from conftest import BUILD
from lcm_proc import pump, stop
from test_manager import World, start_manager

from auv import (
    acoustic_frame_t,
    chasm_status_t,
    ground_truth_t,
    mission_ack_t,
    mission_command_t,
    modem_rx_t,
    plugin_upload_t,
    radio_link_t,
    radio_report_t,
)
from auv import (
    radio_command_status_t as cs,
)
from auvlcm import programs

BITRATE = 40000.0  # bit/s: the plugin (~16 KB) takes about 3.5 s of air


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

    def sail(self, seconds: float, depth: float, until=lambda: False) -> bool:
        end = self.utime + int(seconds * 1e6)
        while self.utime < end:
            t = ground_truth_t()
            t.utime, t.vehicle = self.utime + 50_000, "AUV1"
            t.eta = [self.north, 0.0, depth, 0.0, 0.0, 0.0]
            self.lc.publish("AUV1.TRUTH", t.encode())
            self.tick(0.05, depth=depth)
            pump(self.lc, lambda: False, timeout=0.004)  # let the gateways and the radio keep up
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
    cmds = [
        programs.radio_sim(vehicles=["AUV1"], lcm_url=url, settings={"bitrate_bps": BITRATE, "max_range_m": 1000.0}),
        programs.radio_shore(vehicles=["AUV1"], lcm_url=url, acoustic={"AUV1": 0}, link_timeout_s=1.0, retry_s=0.5),
        programs.radio_vehicle(vehicle="AUV1", spool=spool, lcm_url=url, team_index=0, report_period_s=0.3),
    ]
    return [subprocess.Popen(c, env=env, stderr=subprocess.PIPE, text=True) for c in cmds]


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
        assert w.sail(5.0, 0.0, lambda: 0 < (w.last(501).bytes_held or 0)), w.status_by
        assert w.sail(1.0, 0.0, lambda: w.last(501).bytes_held > 4000)
        assert w.reports and w.reports[-1].mission.startswith("RUNNING")
        w.sail(3.0, 8.0)  # ... and a dive cuts it
        held = w.last(501).bytes_held
        assert w.last(501).state == cs.STATE_IN_FLIGHT and 0 < held < len(other), held
        assert list(pdir.iterdir()) == [] and w.links[-1].up is False
        assert [p.suffix for p in spool.iterdir() if p.suffix == ".part"] == [".part"]
        # at the next surfacing it resumes from what the vehicle holds, and the manager loads it
        assert w.sail(10.0, 0.0, lambda: w.last(501).state == cs.STATE_ACKNOWLEDGED), w.last(501)
        assert "NAVIGATOR ok" in w.last(501).message, w.last(501).message
        assert (pdir / "chasm_test_other.so").read_bytes() == other
        assert not list(spool.glob("*.part"))

        # a plan larger than one surfacing window, using the plugin
        plan = tmp_path / "plan.chasm"
        text = (BUILD.parent / "tests" / "managers" / "dive.chasm").read_text()
        text = text.replace('mission "manager test"', 'mission "radio test"\nuse test_other')
        text += "".join(
            f"# padding line {i:05d} so the plan spans more than one surfacing window\n" for i in range(250)
        )
        plan.write_text(text)
        cmd = mission_command_t()
        cmd.utime, cmd.vehicle, cmd.seq, cmd.command = w.utime, "AUV1", 502, mission_command_t.CMD_LOAD_PLAN
        cmd.plan_name, cmd.plan_text, cmd.reason = "radio.chasm", text, "test"
        w.lc.publish("SHORE.AUV1.MISSION_CMD", cmd.encode())
        assert w.sail(1.0, 0.0, lambda: (w.last(502) and w.last(502).bytes_held or 0) > 0)
        w.sail(0.4, 0.0)
        w.sail(3.0, 8.0)
        assert 0 < w.last(502).bytes_held < len(cmd.encode()), w.last(502)
        assert w.sail(10.0, 0.0, lambda: w.last(502).state == cs.STATE_ACKNOWLEDGED), w.last(502)
        assert "NAVIGATOR ok" in w.last(502).message, w.last(502).message
        assert w.sail(2.0, 0.0, lambda: w.status[-1].plan == "radio.chasm"), w.status[-1].plan

        # an abort at depth goes through the water, and its answer comes home at the surface
        w.sail(3.0, 8.0)
        abort = mission_command_t()
        abort.utime, abort.vehicle, abort.seq, abort.command = w.utime, "AUV1", 503, mission_command_t.CMD_ABORT
        abort.reason = "test"
        w.lc.publish("SHORE.AUV1.MISSION_CMD", abort.encode())
        assert w.sail(3.0, 8.0, lambda: w.status[-1].run_state == chasm_status_t.RUN_ABORTED), w.status[-1]
        assert w.last(503).route == "acoustic" and w.last(503).state == cs.STATE_IN_FLIGHT
        assert any(a.seq == 503 and a.result == mission_ack_t.RESULT_OK for a in w.acks)
        assert w.sail(5.0, 0.0, lambda: w.last(503).state == cs.STATE_ACKNOWLEDGED), w.last(503)
    finally:
        codes = [stop(p, signal.SIGTERM) for p in procs]
        errs = [p.stderr.read() for p in procs]
        assert stop(mgr, signal.SIGTERM) == 0
    print("\n".join(errs), file=sys.stderr)
    assert codes == [0, 0, 0], errs
    assert "auv-radio-vehicle AUV1: delivered 2, acoustic commands 1" in errs[2], errs[2]
