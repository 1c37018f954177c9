"""The launcher's mission watch against hostile stamps (issue 12, item 3): one
SIM.CLOCK at INT64_MAX must not end a mission on its time limit, reports
stamped 10^18 or from the future are dropped; garbage on any channel is
counted (item 6). In-process, through the
watch's own typed subscriptions (decode, then the time rule), no network."""

from __future__ import annotations

from test_launch import vehicle, write_scenario

from auv import actuator_state_t, chasm_status_t, sim_clock_t
from auvlcm.offline import OfflineLcm
from tools.launch.mission_watch import MissionWatch
from tools.scenario.scenario_file import load_scenario


def feed(watch: MissionWatch, channel: str, msg) -> None:
    for sub in watch.rx.subscriptions:
        if sub.channel == channel:
            sub.on_raw(channel, msg.encode())
            return
    raise AssertionError(f"the watch does not read {channel}")


def clock(utime: int, term: int = 0) -> sim_clock_t:
    c = sim_clock_t()
    c.utime, c.server_id, c.term = utime, "launcher", term
    return c


def state(utime: int) -> actuator_state_t:
    m = actuator_state_t()
    m.utime, m.vehicle = utime, "AUV1"
    return m


def status(utime: int, manager: str) -> chasm_status_t:
    m = chasm_status_t()
    m.utime, m.vehicle, m.manager = utime, "AUV1", manager
    return m


def test_hostile_stamps_neither_end_the_mission_nor_reach_the_watch(tmp_path):
    sc = load_scenario(write_scenario(tmp_path, [vehicle("AUV1")]))
    watch = MissionWatch(OfflineLcm(), sc)
    for k in range(11):
        feed(watch, "SIM.CLOCK", clock(k * 100_000))
        feed(watch, "AUV1.ACTUATOR_STATE", state(k * 100_000))
        feed(watch, "AUV1.CHASM.NAVIGATOR", status(k * 100_000, "NAVIGATOR"))
        if k == 0:  # a manager that does not end the mission is read until it is seen, then dropped
            assert "AUV1.WATCHER" in watch.not_ready()
            feed(watch, "AUV1.CHASM.WATCHER", status(0, "OTHER"))  # another's name on its channel
            assert any(sub.channel == "AUV1.CHASM.WATCHER" for sub in watch.rx.subscriptions)
            feed(watch, "AUV1.CHASM.WATCHER", status(0, "WATCHER"))
            assert "AUV1.WATCHER" not in watch.not_ready()
            assert all(sub.channel != "AUV1.CHASM.WATCHER" for sub in watch.rx.subscriptions)
    assert watch.sim_time_us == 1_000_000
    for bad in (2**63 - 1, -(2**63), 10**18, -1):
        feed(watch, "SIM.CLOCK", clock(bad))
        feed(watch, "AUV1.ACTUATOR_STATE", state(bad))
        feed(watch, "AUV1.CHASM.NAVIGATOR", status(bad, "NAVIGATOR"))
    feed(watch, "SIM.CLOCK", clock(500_000))  # back in time
    feed(watch, "SIM.CLOCK", clock(1_000_000 + 3600 * 10**6))  # an hour ahead, once
    feed(watch, "AUV1.ACTUATOR_STATE", state(1_000_000 + 5_000_000))  # from the future
    feed(watch, "AUV1.CHASM.NAVIGATOR", status(900_000, "NAVIGATOR"))  # out of order
    assert watch.sim_time_us == 1_000_000  # no time limit reached
    assert watch.vehicles["AUV1"].sim_us == 1_000_000  # no report from the future
    feed(watch, "SIM.CLOCK", clock(1_100_000))  # and the world goes on
    assert watch.sim_time_us == 1_100_000
    for sub in watch.rx.subscriptions:  # garbage on every channel
        sub.on_raw(sub.channel, b"\x00" * 7)
        sub.on_raw(sub.channel, clock(1).encode()[:-1])
    assert watch.sim_time_us == 1_100_000
    n = 2 * len(watch.rx.subscriptions)
    assert watch.dropped() == {
        "decode_errors": n,
        "time": {"invalid": 12, "future": 1, "out_of_order": 1, "regression": 1, "jump": 1},
    }
