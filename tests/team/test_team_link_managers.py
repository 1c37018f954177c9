"""team_link between two NAVIGATOR managers over real LCM, the test acting
as the modem: AUV1 (search) and AUV4 (RI) run their plans on a driven sim
clock; every KIND_TEAM frame one posts on <V>.MODEM_TX is handed to the other
as a modem_rx_t, except AUV1's first frame that carries the contact (lost).
The contact is repeated in AUV1's next slot, reaches AUV4 (TARGET_QUEUED),
AUV4 acks it in its own slot and AUV1 stops repeating (CONTACT_ACKED). Frames
are checked with the Python team codec (the same bits as the C one) and sent
only in each vehicle's TDMA slot. Then the takeover rule across processes:
three search managers, one killed, the two survivors each deal its lines
and reach the same deal. Both builds."""

from __future__ import annotations

import signal
import subprocess

import lcm
import pytest
from conftest import ROOT, c_program, manager_cmd
from lcm_proc import pump, stop

from auv import chasm_status_t, modem_rx_t, modem_tx_t, nav_solution_t, sidescan_contact_t, sim_clock_t, team_event_t
from auvlcm.rx import Receiver
from auvlcm.team_codec import TeamCodec

HERE = ROOT / "tests" / "team"
PERIOD_US = 100_000


def start(url: str, env: dict, sanitized: bool, vehicle: str, plan: str, *extra: str) -> subprocess.Popen:
    plugins = c_program("plugins/chasm_team.so", sanitized).parent
    cmd = manager_cmd(
        HERE / f"{plan}.chasm",
        HERE / f"{plan}.bind",
        url,
        "--plugin-path",
        plugins,
        *extra,
        sanitized=sanitized,
        vehicle=vehicle,
    )
    return subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)


class Sea:
    """The clock, the navigation of both vehicles, and the modem (by hand)."""

    def __init__(self, url: str, north: dict[str, float]) -> None:
        self.lc = lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.utime = 0
        self.north = north  # where each vehicle stands
        self.status: dict[str, list] = {v: [] for v in north}
        self.frames: dict[str, list] = {v: [] for v in north}
        self.events: dict[str, list] = {v: [] for v in north}
        self.pending: list[tuple[str, modem_tx_t]] = []
        for v in north:
            self.rx.subscribe(f"{v}.CHASM.NAVIGATOR", chasm_status_t, lambda c, m, v=v: self.status[v].append(m), 1000)
            self.rx.subscribe(f"{v}.MODEM_TX", modem_tx_t, lambda c, m, v=v: self.sent(v, m), 1000)
            self.rx.subscribe(f"{v}.TEAM_EVENT", team_event_t, lambda c, m, v=v: self.events[v].append(m), 1000)

    def sent(self, v: str, m: modem_tx_t) -> None:
        self.frames[v].append(m)
        self.pending.append((v, m))

    def running(self) -> bool:
        return all(s and s[-1].utime > 0 for s in self.status.values())

    def tick(self) -> None:
        self.utime += PERIOD_US
        for v, n in self.north.items():
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.north_m, nav.depth_m, nav.speed_over_ground_mps = self.utime, v, n, 5.0, 1.5
            self.lc.publish(f"{v}.NAV", nav.encode())
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.step_us = self.utime, "test", PERIOD_US
        self.lc.publish("SIM.CLOCK", clock.encode())
        assert pump(self.lc, lambda: all(s and s[-1].utime >= self.utime for s in self.status.values()), timeout=30), (
            f"a manager did not run its cycle at {self.utime} us"
        )

    def start(self) -> None:
        for _ in range(300):  # the managers start: clock ticks (time 0) until all run
            clock = sim_clock_t()
            clock.utime, clock.server_id, clock.step_us = self.utime, "test", PERIOD_US
            self.lc.publish("SIM.CLOCK", clock.encode())
            if pump(self.lc, lambda: all(self.status.values()), timeout=0.1):
                return
        raise AssertionError("the managers did not start")

    def kill(self, v: str) -> None:
        """v no longer runs: nothing waits for it, nothing reaches it."""
        del self.status[v]
        del self.north[v]

    def deliver(self, drop) -> None:
        """Hands the frames sent so far to every other running vehicle (drop(v, m) -> lost)."""
        pending, self.pending = self.pending, []
        for v, m in pending:
            if drop(v, m):
                continue
            for to in [t for t in self.status if t != v]:
                self.hand(v, to, m)

    def hand(self, v: str, to: str, m: modem_tx_t) -> None:
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
    sea = Sea(lcm_url, {"AUV1": 0.0, "AUV4": 500.0})
    procs = [start(lcm_url, child_env, sanitized, "AUV1", "search"), start(lcm_url, child_env, sanitized, "AUV4", "ri")]
    dropped: list[modem_tx_t] = []

    def drop_first_contact(v: str, m: modem_tx_t) -> bool:
        names = [d.name for d in codec.decode_frame(bytes(m.payload)).messages]
        if v == "AUV1" and "contact" in names and not dropped:
            dropped.append(m)
            return True
        return False

    try:
        sea.start()
        c = sidescan_contact_t()
        c.utime, c.vehicle, c.contact_id, c.north_m, c.east_m = sea.utime, "AUV1", 0, 100.0, 50.0
        c.position_sigma_m, c.confidence, c.classification = 1.0, 0.8, "mine_like"
        sea.lc.publish("AUV1.CONTACTS", c.encode())
        t_acked = None
        while sea.utime < 40_000_000 and t_acked is None:
            sea.tick()
            sea.deliver(drop_first_contact)
            if 3 in sea.kinds("AUV1"):  # CONTACT_ACKED
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
    sends = [
        m.utime
        for m in sea.frames["AUV1"]
        if any(d.name == "contact" for d in codec.decode_frame(bytes(m.payload)).messages)
    ]
    assert len(sends) >= 2 and all(t < t_acked for t in sends), (sends, t_acked)
    assert sea.kinds("AUV1").count(1) == 1 and sea.kinds("AUV1").count(3) == 1  # CONTACT_NEW, CONTACT_ACKED
    queued = [e for e in sea.events["AUV4"] if e.kind == 4]  # TARGET_QUEUED
    assert len(queued) == 1 and queued[0].origin == "AUV1" and queued[0].number == 0
    acks = [d for m in sea.frames["AUV4"] for d in codec.decode_frame(bytes(m.payload)).messages if d.name == "ack"]
    assert acks and all(a.values == {"to": 0, "number": 0} for a in acks)
    print(
        f"acked at {t_acked / 1e6:.1f} s after {len(sends)} sends; frames AUV1 {len(sea.frames['AUV1'])}, "
        f"AUV4 {len(sea.frames['AUV4'])}; events AUV1 {sea.kinds('AUV1')}, AUV4 {sea.kinds('AUV4')}"
    )


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_a_killed_search_vehicle_lines_are_dealt_the_same_way_by_both_survivors(lcm_url, child_env, sanitized):
    """Three search managers; AUV2 (lines 2, 3, 4, none flown) is killed after
    its first status. Both survivors decide it is lost after 10 s of silence
    and deal its lines round-robin in line order to AUV1 and AUV3: AUV1 takes
    2 and 4, AUV3 takes 3, each computed on its own."""
    sea = Sea(lcm_url, {"AUV1": 0.0, "AUV2": 40.0, "AUV3": 100.0})
    procs = {
        v: start(lcm_url, child_env, sanitized, v, "survey", "-D", f'me="{v}"', "-D", f"my_slot={i}")
        for i, v in enumerate(("AUV1", "AUV2", "AUV3"))
    }
    try:
        sea.start()
        while sea.utime < 30_000_000:
            sea.tick()
            sea.deliver(lambda v, m: False)
            if sea.utime == 6_000_000:
                procs["AUV2"].kill()
                procs["AUV2"].wait(timeout=30)
                sea.kill("AUV2")
    finally:
        rcs = {v: stop(p, signal.SIGTERM) for v, p in procs.items() if v != "AUV2"}
    errs = {v: procs[v].stderr.read() for v in rcs}
    assert all(rc == 0 for rc in rcs.values()), errs
    assert [m.vehicle for m in sea.frames["AUV2"]], "AUV2 sent nothing before it was killed"
    for v, share in (("AUV1", "2 4"), ("AUV3", "3")):
        lost = [e for e in sea.events[v] if e.kind == 8]  # PEER_LOST
        taken = [e for e in sea.events[v] if e.kind == 9]  # LINES_TAKEN
        assert [(e.origin, e.text.startswith("silent")) for e in lost] == [("AUV2", True)], (v, sea.kinds(v))
        assert [(e.origin, e.text) for e in taken] == [("AUV2", share)], v
        # lost 10 s after the last frame heard from AUV2 (its slot: 1 s into a 3 s round), not before
        assert 10_000_000 <= lost[0].utime - 4_000_000 < 12_000_000, lost[0].utime
