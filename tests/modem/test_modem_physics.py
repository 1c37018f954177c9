"""Rate profiles, collisions at a receiver and half duplex (docs/modem.md,
"Profiles" and "Collisions and half duplex"): in-process for the exact
cases, and between simulator processes in a stepped world for two senders
that share a slot."""

from __future__ import annotations

from pathlib import Path

import pytest
from world import World

from auv import acoustic_frame_t, modem_status_t, modem_tx_t
from sim.config import ConfigError, loads
from sim.environment import Environment, EnvParams
from sim.modem.acoustics import frame_duration_s
from sim.modem.config import PROFILES, with_profile
from sim.modem.receiver import Receiver
from sim.modem.transmitter import Transmitter

C = 1500.0
DT = 0.02
LOSSLESS = dict(loss_at_zero=0.0, loss_at_max_range=0.0)


def tx_msg(n=10, seq=1, kind=modem_tx_t.KIND_RAW, dst="") -> modem_tx_t:
    m = modem_tx_t()
    m.vehicle, m.dst_vehicle, m.seq, m.kind = "", dst, seq, kind
    m.n_bytes, m.payload = n, bytes(n)
    return m


def sent(cfg, src, t0, pos, n=20, seq=1, dst="") -> acoustic_frame_t:
    """A frame as src's transmitter puts it in the water (duration included)."""
    f = Transmitter(cfg, src, modem_status_t()).send(t0, pos, tx_msg(n, seq, dst=dst))
    assert isinstance(f, acoustic_frame_t)
    return f


def listen(rx, pos, t_end, t=0.0):
    got = []
    while t < t_end:
        t = round(t + DT, 9)
        got += rx.step(t, pos)
    return got


def receiver(cfg, vehicle="AUV3"):
    return Receiver(cfg, vehicle, 7, Environment(EnvParams(sound_speed_mps=C)), modem_status_t())


# ---------------------------------------------------------------- profiles
def test_fsk80_refuses_a_33_byte_frame_and_times_32_bytes_at_80_bps():
    cfg = with_profile("fsk80")
    st = modem_status_t()
    tx = Transmitter(cfg, "AUV1", st)
    assert tx.send(0.0, (0, 0, 0), tx_msg(33, seq=1)) == "33 bytes is over max_frame_bytes = 32"
    f = tx.send(0.0, (0, 0, 0), tx_msg(32, seq=2))
    assert f.duration_us == round((cfg.frame_overhead_s + 32 * 8 / 80) * 1e6) == 4_200_000
    assert (st.sent, st.refused_size) == (1, 1)
    big = PROFILES["psk1300"]
    assert big["max_frame_bytes"] == 256 and big["bitrate_bps"] > 1000


def test_team_frames_are_accepted():
    st = modem_status_t()
    f = Transmitter(with_profile("fsk80"), "AUV1", st).send(0.0, (0, 0, 0), tx_msg(20, kind=modem_tx_t.KIND_TEAM))
    assert isinstance(f, acoustic_frame_t) and f.kind == modem_tx_t.KIND_TEAM and st.sent == 1


def test_profile_in_config_and_explicit_keys_override_it():
    cfg = loads("modem: {profile: fsk80}\n").modem
    assert (cfg.profile, cfg.max_frame_bytes, cfg.bitrate_bps) == ("fsk80", 32, 80.0)
    cfg = loads("modem:\n  bitrate_bps: 100\n  profile: psk1300\n").modem
    assert (cfg.max_frame_bytes, cfg.bitrate_bps) == (256, 100.0)  # the key wins, wherever it is
    assert loads("modem: {}\n").modem.profile == ""


@pytest.mark.parametrize(
    "text,error",
    [
        (
            "modem:\n  profile: fsk8\n",
            "m.yaml:2:12: modem.profile: unknown profile 'fsk8'; did you mean 'fsk80'? "
            "(known: fsk80, psk250, psk1300, psk5300)",
        ),
        (
            "modem:\n  profile: zzz\n",
            "m.yaml:2:12: modem.profile: unknown profile 'zzz'; (known: fsk80, psk250, psk1300, psk5300)",
        ),
        ("modem:\n  profile: 3\n", "m.yaml:2:12: modem.profile: expected a string, got '3'"),
    ],
)
def test_unknown_profile_is_a_config_error_with_position(text, error):
    with pytest.raises(ConfigError) as exc:
        loads(text, Path("m.yaml"))
    assert exc.value.errors == [error]


# -------------------------------------------------------------- collisions
def test_two_senders_in_one_slot_collide_at_a_receiver_both_lost():
    cfg = with_profile("fsk80", **LOSSLESS)
    rx = receiver(cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0), seq=1))
    rx.hear(sent(cfg, "AUV2", 10.0, (0.0, 900.0, 10.0), seq=1))
    got = listen(rx, (0.0, 300.0, 10.0), 20.0, t=10.0)  # 300 m and 600 m: 0.2 s apart, 4.2 s long
    assert got == []
    assert (rx.status.collided, rx.status.received, rx.status.lost) == (2, 0, 0)


def test_frames_apart_do_not_collide():
    cfg = with_profile("fsk80", **LOSSLESS)
    rx = receiver(cfg)
    d = frame_duration_s(20, cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0)))
    # AUV2's frame starts arriving just after AUV1's has ended (both 300 m away)
    rx.hear(sent(cfg, "AUV2", 10.0 + d + 0.05, (0.0, 600.0, 10.0)))
    got = listen(rx, (0.0, 300.0, 10.0), 25.0, t=10.0)
    assert [m.src_vehicle for m in got] == ["AUV1", "AUV2"]
    assert (rx.status.collided, rx.status.received) == (0, 2)


def test_a_later_frame_that_arrives_first_still_collides():
    """AUV2 sends after AUV1 but is closer: its frame arrives while AUV1's is
    still in the water; both are lost, whichever arrives first."""
    cfg = with_profile("fsk80", **LOSSLESS)
    rx = receiver(cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0)))  # 1500 m: arrives at 11.0
    rx.hear(sent(cfg, "AUV2", 10.5, (0.0, 1550.0, 10.0)))  # 50 m: arrives at 10.53
    got = listen(rx, (0.0, 1500.0, 10.0), 20.0, t=10.0)
    assert got == [] and rx.status.collided == 2


def test_a_frame_for_another_vehicle_still_jams_the_channel():
    cfg = with_profile("fsk80", **LOSSLESS)
    rx = receiver(cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0)))
    rx.hear(sent(cfg, "AUV2", 10.0, (0.0, 900.0, 10.0), dst="AUV4"))
    assert listen(rx, (0.0, 300.0, 10.0), 20.0, t=10.0) == []
    assert (rx.status.collided, rx.status.received) == (1, 0)  # only our frames are counted


def test_frames_beyond_range_jam_nothing():
    cfg = with_profile("fsk80", max_range_m=1000.0, **LOSSLESS)
    rx = receiver(cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0)))
    rx.hear(sent(cfg, "AUV2", 10.0, (0.0, 1500.0, 10.0)))  # 1200 m from the receiver
    got = listen(rx, (0.0, 300.0, 10.0), 20.0, t=10.0)
    assert [m.src_vehicle for m in got] == ["AUV1"]
    assert (rx.status.collided, rx.status.out_of_range) == (0, 1)


# -------------------------------------------------------------- half duplex
def test_a_modem_does_not_hear_while_it_sends():
    cfg = with_profile("fsk80", **LOSSLESS)
    rx = receiver(cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0)))  # arrives 10.2 .. 14.4
    rx.transmit(9.0, 9.0 + frame_duration_s(20, cfg))  # we send 9.0 .. 12.6
    assert listen(rx, (0.0, 300.0, 10.0), 20.0, t=10.0) == []
    assert (rx.status.deaf, rx.status.collided, rx.status.received) == (1, 0, 0)


def test_sending_while_a_frame_is_on_its_way_loses_it():
    cfg = with_profile("fsk80", **LOSSLESS)
    rx = receiver(cfg)
    rx.hear(sent(cfg, "AUV1", 10.0, (0.0, 0.0, 10.0)))  # arrives at 11.0
    rx.step(10.02, (0.0, 1500.0, 10.0))
    rx.transmit(10.04, 11.5)  # on the air when it arrives
    assert listen(rx, (0.0, 1500.0, 10.0), 20.0, t=10.04) == []
    rx.hear(sent(cfg, "AUV1", 20.0, (0.0, 0.0, 10.0), seq=2))  # after we stopped: heard
    assert [m.seq for m in listen(rx, (0.0, 1500.0, 10.0), 30.0, t=20.0)] == [2]
    assert (rx.status.deaf, rx.status.received) == (1, 1)


def test_collisions_repeat_exactly():
    def run():
        cfg = with_profile("fsk80", loss_at_zero=0.2, loss_at_max_range=0.2)
        rx = receiver(cfg)
        for k in range(30):
            rx.hear(
                sent(cfg, f"AUV{1 + k % 2}", 10.0 + 2.0 * k + (k * 7 % 5) * 0.9, (0.0, 900.0 * (k % 2), 10.0), seq=k)
            )
        got = listen(rx, (0.0, 300.0, 10.0), 100.0, t=10.0)
        st = rx.status
        return [(m.src_vehicle, m.seq, m.utime) for m in got], (st.collided, st.lost, st.received)

    first = run()
    assert first == run()
    assert first[1][0] > 0 and first[1][2] > 0


# ------------------------------------------------------- between processes
@pytest.fixture
def world(lcm_url, tmp_path, child_env):
    w = World(lcm_url, tmp_path, child_env)
    yield w
    for proc in w.procs.values():
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_two_vehicles_sending_in_one_slot_collide_over_lcm(world):
    """A TDMA misconfiguration: AUV1 and AUV2 both send in the same slot
    (psk5300: 0.5 s frames here); AUV3 between them hears neither, counts two
    collisions; each sender is deaf to the other's frame. A slot later, one
    at a time, every frame gets through."""
    cfg = {"profile": "psk5300", "frame_overhead_s": 0.5, **LOSSLESS}
    world.add_sim("AUV1", 0.0, 0.0, 10.0, cfg)
    world.add_sim("AUV2", 0.0, 600.0, 10.0, cfg)
    world.add_sim("AUV3", 0.0, 300.0, 10.0, cfg)
    world.tick(2)
    world.send("AUV1", 32, seq=1)
    world.send("AUV2", 32, seq=1)
    world.tick()
    world.run_for(1.0)
    assert world.msgs["AUV3.MODEM_RX"] == []
    assert world.status("AUV3").collided == 2
    # AUV1 and AUV2 (600 m apart, 0.4 s flight) were still sending when the other's frame arrived
    assert world.status("AUV1").deaf == 1 and world.status("AUV2").deaf == 1
    world.send("AUV1", 32, seq=2)
    world.tick()
    world.run_for(1.5)
    world.send("AUV2", 32, seq=2)
    world.tick()
    world.run_for(1.5)
    assert [(m.src_vehicle, m.seq) for m in world.msgs["AUV3.MODEM_RX"]] == [("AUV1", 2), ("AUV2", 2)]
    st = world.status("AUV3")
    assert (st.collided, st.received) == (2, 2)
    outs = world.close()
    assert "2 collided, 0 missed while sending" in outs["AUV3"]
    assert "1 missed while sending" in outs["AUV1"]
