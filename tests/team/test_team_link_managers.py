"""team_link between two NAVIGATOR managers over real LCM, the test acting
as the modem: AUV1 (search) and AUV4 (RI) run their plans on a driven sim
clock; every KIND_TEAM frame one posts on <V>.MODEM_TX is handed to the other
as a modem_rx_t, except AUV1's first frame that carries the contact (lost).
The contact is repeated in AUV1's next slot, reaches AUV4 (TARGET_QUEUED),
AUV4 acks it in its own slot and AUV1 stops repeating (CONTACT_ACKED). Frames
are checked with the Python team codec (the same bits as the C one) and sent
only in each vehicle's TDMA slot. Both builds."""

from __future__ import annotations

import signal
import subprocess

import lcm
import pytest

from auv import (chasm_status_t, modem_rx_t, modem_tx_t, nav_solution_t, sidescan_contact_t, sim_clock_t,
                 team_event_t)
from auvlcm.rx import Receiver
from auvlcm.team_codec import TeamCodec
from conftest import ROOT, c_program
from lcm_proc import pump, stop

HERE = ROOT / "tests" / "team"
PERIOD_US = 100_000


def start(url: str, env: dict, sanitized: bool, vehicle: str, plan: str) -> subprocess.Popen:
    return subprocess.Popen(
        [c_program("bin/chasm-manager", sanitized), "--plan", HERE / f"{plan}.chasm", "--bind",
         HERE / f"{plan}.bind", "--vehicle", vehicle, "--name", "NAVIGATOR", "--rate", "10", "--clock", "sim",
         "--url", url, "--plugin-path", c_program("plugins/chasm_team.so", sanitized).parent],
        env=env, stderr=subprocess.PIPE, text=True)


class Sea:
    """The clock, the navigation of both vehicles, and the modem (by hand)."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.utime = 0
        self.status: dict[str, list] = {"AUV1": [], "AUV4": []}
        self.frames: dict[str, list] = {"AUV1": [], "AUV4": []}
        self.events: dict[str, list] = {"AUV1": [], "AUV4": []}
        self.pending: list[tuple[str, modem_tx_t]] = []
        for v in ("AUV1", "AUV4"):
            self.rx.subscribe(f"{v}.CHASM.NAVIGATOR", chasm_status_t, lambda c, m, v=v: self.status[v].append(m),
                              1000)
            self.rx.subscribe(f"{v}.MODEM_TX", modem_tx_t, lambda c, m, v=v: self.sent(v, m), 1000)
            self.rx.subscribe(f"{v}.TEAM_EVENT", team_event_t, lambda c, m, v=v: self.events[v].append(m), 1000)

    def sent(self, v: str, m: modem_tx_t) -> None:
        self.frames[v].append(m)
        self.pending.append((v, m))

    def running(self) -> bool:
        return all(s and s[-1].utime > 0 for s in self.status.values())

    def tick(self) -> None:
        self.utime += PERIOD_US
        for v, n in (("AUV1", 0.0), ("AUV4", 500.0)):
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.north_m, nav.depth_m, nav.speed_over_ground_mps = self.utime, v, n, 5.0, 1.5
            self.lc.publish(f"{v}.NAV", nav.encode())
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.step_us = self.utime, "test", PERIOD_US
        self.lc.publish("SIM.CLOCK", clock.encode())
        assert pump(self.lc, lambda: all(s and s[-1].utime >= self.utime for s in self.status.values()),
                    timeout=30), f"a manager did not run its cycle at {self.utime} us"

    def deliver(self, drop) -> None:
        """Hands the frames sent so far to the other vehicle (drop(v, m) -> lost)."""
        pending, self.pending = self.pending, []
        for v, m in pending:
            if drop(v, m):
                continue
            to = "AUV4" if v == "AUV1" else "AUV1"
            r = modem_rx_t()
            r.utime, r.vehicle, r.src_vehicle, r.dst_vehicle = self.utime, to, v, m.dst_vehicle
            r.seq, r.kind, r.tx_utime, r.range_m, r.snr_db = m.seq, m.kind, m.utime, 500.0, 20.0
            r.payload, r.n_bytes = m.payload, m.n_bytes
            self.lc.publish(f"{to}.MODEM_RX", r.encode())

    def kinds(self, v: str) -> list[int]:
        return [e.kind for e in self.events[v]]


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_a_lost_contact_report_is_repeated_acked_and_queued(lcm_url, child_env, sanitized):
    codec = TeamCodec(ROOT / "c" / "plugins" / "team" / "team_link.schema")
    sea = Sea(lcm_url)
    procs = [start(lcm_url, child_env, sanitized, "AUV1", "search"), start(lcm_url, child_env, sanitized, "AUV4", "ri")]
    dropped: list[modem_tx_t] = []

    def drop_first_contact(v: str, m: modem_tx_t) -> bool:
        names = [d.name for d in codec.decode_frame(bytes(m.payload)).messages]
        if v == "AUV1" and "contact" in names and not dropped:
            dropped.append(m)
            return True
        return False

    try:
        for _ in range(300):   # the managers start: clock ticks until both run
            sea.utime += 0
            clock = sim_clock_t()
            clock.utime, clock.server_id, clock.step_us = sea.utime, "test", PERIOD_US
            sea.lc.publish("SIM.CLOCK", clock.encode())
            if pump(sea.lc, lambda: all(sea.status.values()), timeout=0.1):
                break
        assert all(sea.status.values()), "the managers did not start"
        c = sidescan_contact_t()
        c.utime, c.vehicle, c.contact_id, c.north_m, c.east_m = sea.utime, "AUV1", 0, 100.0, 50.0
        c.position_sigma_m, c.confidence, c.classification = 1.0, 0.8, "mine_like"
        sea.lc.publish("AUV1.CONTACTS", c.encode())
        t_acked = None
        while sea.utime < 40_000_000 and t_acked is None:
            sea.tick()
            sea.deliver(drop_first_contact)
            if 3 in sea.kinds("AUV1"):   # CONTACT_ACKED
                t_acked = sea.utime
        assert t_acked is not None, (sea.kinds("AUV1"), sea.kinds("AUV4"))
        # a few more rounds: the acked contact is not sent again
        for _ in range(100):
            sea.tick()
            sea.deliver(lambda v, m: False)
    finally:
        rcs = [stop(p, signal.SIGTERM) for p in procs]
    errs = [p.stderr.read() for p in procs]
    assert rcs == [0, 0], errs
    assert dropped, "no frame carried the contact"
    contact = [d for d in codec.decode_frame(bytes(dropped[0].payload)).messages if d.name == "contact"][0]
    assert contact.values["origin"] == 0 and contact.values["number"] == 0
    assert contact.values["north_m"] == 100.0 and contact.values["east_m"] == 50.0
    assert abs(contact.values["score"] - 0.8) < 0.006
    # every frame in its sender's slot: AUV1 in [0, 0.5) s, AUV4 in [3, 3.5) s of each 4 s round
    for v, start_us in (("AUV1", 0), ("AUV4", 3_000_000)):
        assert sea.frames[v], v
        for m in sea.frames[v]:
            assert m.kind == modem_tx_t.KIND_TEAM and m.n_bytes <= 32 and m.vehicle == v
            assert start_us <= m.utime % 4_000_000 < start_us + 500_000, (v, m.utime)
            assert codec.decode_frame(bytes(m.payload)).ok
    sends = [m.utime for m in sea.frames["AUV1"] if any(d.name == "contact" for d in
                                                        codec.decode_frame(bytes(m.payload)).messages)]
    assert len(sends) >= 2 and all(t < t_acked for t in sends), (sends, t_acked)
    assert sea.kinds("AUV1").count(1) == 1 and sea.kinds("AUV1").count(3) == 1   # CONTACT_NEW, CONTACT_ACKED
    queued = [e for e in sea.events["AUV4"] if e.kind == 4]   # TARGET_QUEUED
    assert len(queued) == 1 and queued[0].origin == "AUV1" and queued[0].number == 0
    acks = [d for m in sea.frames["AUV4"] for d in codec.decode_frame(bytes(m.payload)).messages if d.name == "ack"]
    assert acks and all(a.values == {"to": 0, "number": 0} for a in acks)
    print(f"acked at {t_acked / 1e6:.1f} s after {len(sends)} sends; frames AUV1 {len(sea.frames['AUV1'])}, "
          f"AUV4 {len(sea.frames['AUV4'])}; events AUV1 {sea.kinds('AUV1')}, AUV4 {sea.kinds('AUV4')}")
